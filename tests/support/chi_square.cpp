#include "support/chi_square.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

namespace erpt::test {

namespace {

constexpr double kTwoPi = 6.283185307179586476925;
// Cells with fewer expected samples than this make the chi-square approximation poor.
constexpr double kMinExpected = 5.0;

struct Category {
  double expected = 0;
  double observed = 0;
  int bin = -1;  // -1: the missing-mass category
};

int binIndex(Vec3 d, int thetaBins, int phiBins) {
  double z = std::clamp(double(d.z), -1.0, 1.0);
  int iz = std::min(int((z + 1) * 0.5 * thetaBins), thetaBins - 1);
  double phi = std::atan2(double(d.y), double(d.x));
  if (phi < 0) phi += kTwoPi;
  int ip = std::min(int(phi / kTwoPi * phiBins), phiBins - 1);
  return iz * phiBins + ip;
}

std::string describeBin(int bin, int thetaBins, int phiBins) {
  if (bin < 0) return "missing mass";
  int iz = bin / phiBins, ip = bin % phiBins;
  char buf[128];
  std::snprintf(buf, sizeof buf, "cos[%.3f,%.3f] phi[%.3f,%.3f]", -1 + 2.0 * iz / thetaBins,
                -1 + 2.0 * (iz + 1) / thetaBins, kTwoPi * ip / phiBins, kTwoPi * (ip + 1) / phiBins);
  return buf;
}

// Series expansion of the regularized lower gamma P(a, x); converges well for x < a + 1.
double lowerGammaSeries(double a, double x) {
  double term = 1.0 / a, sum = term;
  for (int n = 1; n < 1000000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-15) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Continued fraction for the regularized upper gamma Q(a, x) (modified Lentz); converges
// well for x >= a + 1.
double upperGammaContinuedFraction(double a, double x) {
  const double tiny = 1e-300;
  double b = x + 1 - a, c = 1 / tiny, d = 1 / b, h = d;
  for (int i = 1; i < 1000000; ++i) {
    double an = -i * (i - a);
    b += 2;
    d = an * d + b;
    if (std::abs(d) < tiny) d = tiny;
    c = b + an / c;
    if (std::abs(c) < tiny) c = tiny;
    d = 1 / d;
    double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1) < 1e-15) break;
  }
  return h * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

}  // namespace

double regularizedGammaQ(double a, double x) {
  if (!(a > 0)) return std::numeric_limits<double>::quiet_NaN();
  if (x <= 0) return 1.0;
  if (x < a + 1) return std::clamp(1.0 - lowerGammaSeries(a, x), 0.0, 1.0);
  return std::clamp(upperGammaContinuedFraction(a, x), 0.0, 1.0);
}

double chiSquarePValue(double statistic, int dof) {
  if (dof <= 0) return statistic > 0 ? 0.0 : 1.0;
  return regularizedGammaQ(0.5 * dof, 0.5 * statistic);
}

ChiSquareResult chiSquareTest(const DirectionSampler& sample, const DirectionPdf& pdf, int thetaBins,
                              int phiBins, uint64_t sampleCount, int subdivisions) {
  ChiSquareResult r;
  r.sampleCount = sampleCount;
  const int binCount = thetaBins * phiBins;

  // Histogram of the sampled directions.
  std::vector<double> observed(binCount, 0.0);
  for (uint64_t i = 0; i < sampleCount; ++i) {
    Vec3 d;
    if (!sample(i, d)) {
      ++r.missingObserved;
      continue;
    }
    double len = std::sqrt(double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z);
    if (!isFinite(d) || std::abs(len - 1) > 1e-3) {
      ++r.invalidSamples;
      continue;
    }
    observed[binIndex(d, thetaBins, phiBins)] += 1;
  }

  // Expected counts: midpoint rule on sub-cells (never on bin edges, where pdfs may jump,
  // e.g. at the horizon). Sines and cosines of the sub-cell azimuths are shared by rows.
  const int sub = std::max(1, subdivisions);
  const double dz = 2.0 / (double(thetaBins) * sub), dphi = kTwoPi / (double(phiBins) * sub);
  std::vector<double> cosPhi(size_t(phiBins) * sub), sinPhi(cosPhi.size());
  for (size_t j = 0; j < cosPhi.size(); ++j) {
    double phi = (j + 0.5) * dphi;
    cosPhi[j] = std::cos(phi);
    sinPhi[j] = std::sin(phi);
  }
  std::vector<double> expected(binCount, 0.0);
  for (int row = 0; row < thetaBins * sub; ++row) {
    double z = -1 + (row + 0.5) * dz, rxy = std::sqrt(std::max(0.0, 1 - z * z));
    int iz = row / sub;
    for (size_t j = 0; j < cosPhi.size(); ++j) {
      Vec3 w(float(rxy * cosPhi[j]), float(rxy * sinPhi[j]), float(z));
      expected[iz * phiBins + int(j) / sub] += double(pdf(w));
    }
  }
  double integral = 0;
  for (double& e : expected) {
    e *= dz * dphi;
    integral += e;
    e *= double(sampleCount);
  }
  r.pdfIntegral = integral;
  r.missingExpected = std::max(0.0, 1.0 - integral) * double(sampleCount);

  // Categories: every bin plus the missing mass. Samples where the pdf vanishes entirely
  // are flagged on their own, since pooling could otherwise dilute them.
  std::vector<Category> cats;
  cats.reserve(binCount + 1);
  for (int b = 0; b < binCount; ++b) {
    if (expected[b] == 0) {
      r.samplesInZeroPdfBins += uint64_t(observed[b]);
      continue;
    }
    cats.push_back({expected[b], observed[b], b});
  }
  // The missing mass always takes part: its expected share may round to 0 when the numerical
  // integral slightly exceeds 1, so a lone failed sample must not be a hard failure.
  cats.push_back({r.missingExpected, double(r.missingObserved), -1});

  // Pool the smallest cells (ascending expected) until each pooled group reaches kMinExpected;
  // a final group that falls short joins the previous category.
  std::sort(cats.begin(), cats.end(), [](const Category& a, const Category& b) { return a.expected < b.expected; });
  std::vector<Category> finalCats;
  Category pool;
  int poolSize = 0;
  for (const Category& c : cats) {
    if (c.expected == 0 && c.observed == 0) continue;
    if (poolSize == 0 && c.expected >= kMinExpected) {
      finalCats.push_back(c);
      continue;
    }
    pool.expected += c.expected;
    pool.observed += c.observed;
    ++poolSize;
    r.pooledBins += 1;
    if (pool.expected >= kMinExpected) {
      pool.bin = poolSize == 1 ? c.bin : -2;
      finalCats.push_back(pool);
      pool = Category{};
      poolSize = 0;
    }
  }
  if (poolSize > 0) {
    if (finalCats.empty()) {
      pool.bin = -2;
      finalCats.push_back(pool);
    } else {
      finalCats.back().expected += pool.expected;
      finalCats.back().observed += pool.observed;
      finalCats.back().bin = -2;
    }
  }

  std::vector<std::pair<double, const Category*>> contributions;
  for (const Category& c : finalCats) {
    double diff = c.observed - c.expected, term = diff * diff / c.expected;
    r.statistic += term;
    contributions.push_back({term, &c});
  }
  r.dof = int(finalCats.size()) - 1;
  r.pValue = chiSquarePValue(r.statistic, r.dof);
  if (r.invalidSamples > 0 || r.samplesInZeroPdfBins > 0) r.pValue = 0;

  std::sort(contributions.begin(), contributions.end(),
            [](const auto& a, const auto& b) { return a.first > b.first; });
  for (size_t i = 0; i < std::min<size_t>(5, contributions.size()); ++i) {
    const Category& c = *contributions[i].second;
    char buf[256];
    std::snprintf(buf, sizeof buf, "  %s: observed %.0f, expected %.1f (chi2 term %.1f)\n",
                  c.bin == -2 ? "pooled cells" : describeBin(c.bin, thetaBins, phiBins).c_str(), c.observed,
                  c.expected, contributions[i].first);
    r.worstBins += buf;
  }
  return r;
}

std::string ChiSquareResult::summary() const {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "chi2 = %.1f, dof = %d, p = %.4g; %llu samples, missing mass observed %llu vs expected %.1f "
                "(pdf integral %.5f); %d bins pooled; invalid directions %llu; samples where pdf = 0: %llu\n"
                "largest contributions:\n",
                statistic, dof, pValue, (unsigned long long)sampleCount, (unsigned long long)missingObserved,
                missingExpected, pdfIntegral, pooledBins, (unsigned long long)invalidSamples,
                (unsigned long long)samplesInZeroPdfBins);
  return buf + worstBins;
}

}  // namespace erpt::test
