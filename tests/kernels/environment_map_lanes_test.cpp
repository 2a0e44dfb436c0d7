// The environment map's lane kernels (kernels/environment_map_lanes.h) against
// EnvironmentMap::sample and evalAndPdf: the same pixel for the same numbers (the CDF searches
// compare the same floats), and directions, densities and radiance equal up to the rounding
// of xsimd's trigonometry against the C library's. Two maps: the test sky with its small sun,
// and a sparse map whose empty rows and columns make zero-width CDF intervals, lit at the seam
// and at both poles, at a size that is not a power of two.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "erpt/environment_map.h"
#include "kernels/environment_map_lanes.h"
#include "support/environment_scene.h"
#include "support/slot_differences.h"

namespace erpt {
namespace {

using namespace lanes3;
constexpr size_t kLanes = batch::size;

RgbImage sparseImage() {
  RgbImage img;
  img.width = 37;
  img.height = 19;
  img.pixels.assign(size_t(img.width) * img.height, Color(0.0f));
  auto set = [&](int x, int y, Color c) { img.pixels[size_t(y) * img.width + x] = c; };
  set(0, 0, Color(3.0f, 1.0f, 0.5f));     // the north pole, at the seam
  set(36, 5, Color(0.2f, 0.4f, 2.0f));    // the seam's other side
  set(17, 9, Color(50.0f, 40.0f, 30.0f)); // a sun on the equator
  set(18, 9, Color(5.0f, 4.0f, 3.0f));
  set(4, 18, Color(1.0f, 1.0f, 1.0f));    // the south pole
  return img;
}

struct Differences {
  std::vector<double> direction, pdf, radiance;
  size_t okDiffer = 0, far = 0, count = 0;
};

Differences compareSamples(const EnvironmentMap& map, size_t n) {
  Differences d;
  const EnvironmentMap::Tables tables = map.tables();
  alignas(64) float u1[kLanes], u2[kLanes];
  alignas(64) float out[8][kLanes];
  for (size_t i = 0; i < n; i += kLanes) {
    for (size_t j = 0; j < kLanes; ++j) {
      const uint64_t key = streamKey(5, i + j, 0);
      u1[j] = uniformFloat(key, 0), u2[j] = uniformFloat(key, 1);
      if ((i + j) % 101 == 0) u1[j] = 0.0f, u2[j] = 0x1.fffffep-1f;  // the ends of both CDFs
      if ((i + j) % 103 == 0) u1[j] = 0x1.fffffep-1f, u2[j] = 0.0f;
    }
    const LaneEnvironmentSample s = sampleEnvironmentLanes(tables, batch::load_aligned(u1), batch::load_aligned(u2));
    s.direction.x.store_aligned(out[0]), s.direction.y.store_aligned(out[1]), s.direction.z.store_aligned(out[2]);
    s.radiance.x.store_aligned(out[3]), s.radiance.y.store_aligned(out[4]), s.radiance.z.store_aligned(out[5]);
    s.pdf.store_aligned(out[6]);
    xsimd::select(s.ok, batch(1.0f), batch(0.0f)).store_aligned(out[7]);
    for (size_t j = 0; j < kLanes; ++j) {
      Vec3 direction;
      float pdf;
      Color radiance;
      const bool ok = map.sample(u1[j], u2[j], direction, pdf, &radiance);
      ++d.count;
      d.okDiffer += ok != (out[7][j] != 0);
      if (!ok || out[7][j] == 0) continue;
      const double dirDiff = test::relativeDifference(Vec3(out[0][j], out[1][j], out[2][j]), direction);
      // A twentieth of a pixel: only a different pick moves a direction this far.
      d.far += dirDiff > 0.05 * kPi / map.height();
      d.direction.push_back(dirDiff);
      d.pdf.push_back(std::abs(out[6][j] - pdf) / pdf);
      d.radiance.push_back(test::relativeDifference(Color(out[3][j], out[4][j], out[5][j]), radiance));
    }
  }
  return d;
}

Differences compareLookups(const EnvironmentMap& map, size_t n) {
  Differences d;
  const EnvironmentMap::Tables tables = map.tables();
  alignas(64) float x[kLanes], y[kLanes], z[kLanes], out[4][kLanes];
  for (size_t i = 0; i < n; i += kLanes) {
    for (size_t j = 0; j < kLanes; ++j) {
      const uint64_t key = streamKey(6, i + j, 0);
      Vec3 w = squareToUniformSphere(uniformFloat(key, 0), uniformFloat(key, 1));
      if ((i + j) % 50 == 0) w = Vec3(0.0f, (i + j) % 100 == 0 ? 1.0f : -1.0f, 0.0f);  // the poles
      if ((i + j) % 50 == 1) w = normalize(Vec3(1e-7f * uniformFloat(key, 2), 0.3f, -1.0f));  // beside the seam
      x[j] = w.x, y[j] = w.y, z[j] = w.z;
    }
    batch pdf;
    const V3 radiance = environmentEvalAndPdfLanes(
        tables, {batch::load_aligned(x), batch::load_aligned(y), batch::load_aligned(z)}, pdf);
    radiance.x.store_aligned(out[0]), radiance.y.store_aligned(out[1]), radiance.z.store_aligned(out[2]);
    pdf.store_aligned(out[3]);
    for (size_t j = 0; j < kLanes; ++j) {
      float pdfScalar;
      const Color r = map.evalAndPdf(Vec3(x[j], y[j], z[j]), pdfScalar);
      ++d.count;
      d.okDiffer += (pdfScalar > 0) != (out[3][j] > 0);
      d.radiance.push_back(test::relativeDifference(Color(out[0][j], out[1][j], out[2][j]), r, 1e-3f));
      // Relative to the uniform density at least: far out in a bright pixel's bilinear tail a
      // density is tiny, and the rounding of its weight t large against it.
      if (pdfScalar > 0) d.pdf.push_back(std::abs(out[3][j] - pdfScalar) / std::max(pdfScalar, kUniformSpherePdf));
    }
  }
  return d;
}

void expectRoundingOnly(const Differences& d, const char* what) {
  EXPECT_LE(d.okDiffer, d.count / 10000) << what;
  EXPECT_EQ(d.far, 0u) << what;
  for (const auto* errors : {&d.direction, &d.pdf, &d.radiance}) {
    EXPECT_LT(test::quantile(*errors, 0.5), 1e-6) << what;
    // The tail: u W rounds to 4e-6 of a pixel at the map's right edge, and a bright pixel's
    // bilinear slope multiplies that; a wrong pick, weight or density is off by O(1).
    EXPECT_LT(test::quantile(*errors, 0.999), 1e-3) << what;
  }
}

TEST(EnvironmentMapLanes, SamplesAreTheScalarSamples) {
  const EnvironmentMap sky(test::skyImage(), 1.0f, Transform::rotate(1, 0, 0.5, 35));
  expectRoundingOnly(compareSamples(sky, 200000), "sky");
  const EnvironmentMap sparse(sparseImage(), 2.0f, Transform::rotate(0, 1, 0, 30));
  expectRoundingOnly(compareSamples(sparse, 200000), "sparse map");
}

TEST(EnvironmentMapLanes, LookupsAreTheScalarLookups) {
  const EnvironmentMap sky(test::skyImage(), 1.0f, Transform::rotate(1, 0, 0.5, 35));
  expectRoundingOnly(compareLookups(sky, 200000), "sky");
  const EnvironmentMap sparse(sparseImage(), 2.0f, Transform::rotate(0, 1, 0, 30));
  expectRoundingOnly(compareLookups(sparse, 200000), "sparse map");
}

}  // namespace
}  // namespace erpt
