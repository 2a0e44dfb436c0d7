// Chi-square goodness-of-fit test for direction samplers on the unit sphere.
//
// The sphere is cut into thetaBins x phiBins cells that are uniform in cos(theta) and phi,
// so every cell covers the same solid angle (dcos dphi is the solid-angle measure). Samples
// are histogrammed; expected counts come from integrating the claimed pdf over each cell.
// Samples the sampler cannot produce (failures, Dirac lobes) form one extra "missing mass"
// category whose expected share is 1 - (integral of the pdf over the sphere), so a sampler
// that loses or invents probability is caught as well as one whose shape is wrong.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "erpt/math.h"
#include "core/rng.h"

namespace erpt::test {

struct ChiSquareResult {
  double statistic = 0;
  int dof = 0;
  double pValue = 0;
  uint64_t sampleCount = 0;
  uint64_t missingObserved = 0;    // samples that failed or were Dirac
  double missingExpected = 0;      // sampleCount * (1 - pdfIntegral), clamped at 0
  double pdfIntegral = 0;          // numerical integral of the pdf over the sphere
  uint64_t invalidSamples = 0;     // non-finite or non-unit directions (forces p = 0)
  uint64_t samplesInZeroPdfBins = 0;  // samples where the pdf integrates to 0 (forces p = 0)
  int pooledBins = 0;              // bins merged because their expected count was < 5
  std::string worstBins;           // the largest per-bin contributions, for diagnosis

  std::string summary() const;
};

// Returns false when no direction is produced (that sample counts as missing mass).
using DirectionSampler = std::function<bool(uint64_t index, Vec3& dir)>;
using DirectionPdf = std::function<float(Vec3 dir)>;

// `subdivisions` x `subdivisions` midpoint sub-cells integrate the pdf over each bin.
ChiSquareResult chiSquareTest(const DirectionSampler& sample, const DirectionPdf& pdf, int thetaBins,
                              int phiBins, uint64_t sampleCount, int subdivisions = 8);

// Regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a).
double regularizedGammaQ(double a, double x);
// P(X >= statistic) for X ~ chi-square with `dof` degrees of freedom.
double chiSquarePValue(double statistic, int dof);

// Deterministic uniform numbers for sample `index`: one counter-based stream per sample,
// so a test's outcome never depends on the order or number of samples drawn before.
constexpr uint64_t kTestSeed = 0x5eed0f7e575ull;
inline float testUniform(uint64_t index, uint32_t dim, uint64_t seed = kTestSeed) {
  return uniformFloat(streamKey(seed, index, 0), dim);
}

}  // namespace erpt::test
