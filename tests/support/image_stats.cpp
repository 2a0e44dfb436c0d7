#include "support/image_stats.h"

#include <stdexcept>

namespace erpt::test {

double relativeMse(const RgbImage& img, const RgbImage& ref) {
  if (img.width != ref.width || img.height != ref.height) throw std::runtime_error("relativeMse: size mismatch");
  return compareImages(img, ref).relMse;
}

}  // namespace erpt::test
