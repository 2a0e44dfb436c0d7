// The path tracer's splatting films (film_splat.h): the unbiased one estimates what filter
// importance sampling does (block by block away from the border, where the two films define
// the filtered image differently); the weighted one converges to it; with a box filter both are
// the importance-sampled film; and the image is bit-identical for any thread count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "models/film_splat.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

Scene defaultScene() { return loadScene(test::sourceDir() + "/scenes/default/scene.xml"); }

RgbImage renderFilm(const Scene& scene, FilmMode film, FilterKind filter, int spp, uint64_t seed, int threads = 0) {
  RenderSettings s;
  s.integrator = "path";
  s.width = s.height = 64;
  s.spp = spp;
  s.seed = seed;
  s.threads = threads;
  s.filterSet = true;
  s.filter = filter;
  s.film = film;
  RenderStats stats;
  return render(scene, s, stats);
}

// The image without a border of `b` pixels.
RgbImage crop(const RgbImage& img, int b) {
  RgbImage out;
  out.width = img.width - 2 * b;
  out.height = img.height - 2 * b;
  for (int y = b; y < img.height - b; ++y)
    for (int x = b; x < img.width - b; ++x) out.pixels.push_back(img.pixels[size_t(y) * size_t(img.width) + size_t(x)]);
  return out;
}

// Ten renders of each film, Welch z per 10x10 block of the 60x60 interior (support/image_stats.h).
test::BlockZScores againstImportanceSampling(FilmMode film, FilterKind filter, int spp, uint64_t seed) {
  const Scene scene = defaultScene();
  std::vector<RgbImage> a, b;
  for (int k = 0; k < 10; ++k) {
    a.push_back(crop(renderFilm(scene, film, filter, spp, seed + uint64_t(k)), 2));
    b.push_back(crop(renderFilm(scene, FilmMode::Fis, filter, spp, seed + 100 + uint64_t(k)), 2));
  }
  const test::BlockZScores z = test::blockZScores(a, b, 10);
  std::printf("%s, %d spp: %zu blocks, mean z^2 %.2f, worst |z| %.2f\n", filmModeName(film), spp, z.z.size(),
              z.meanSquare, z.worst);
  return z;
}

// 64 spp: the unbiased film spreads a caustic firefly at full weight over the pixels its filter
// reaches (the weighted one divides it by the weights, which include its own), so its tails are
// heavier; ten renders of 16 spp gave one block at |z| 5.0, of 64 spp mean z^2 0.64.
TEST(StatisticalFilm, UnbiasedSplatMatchesImportanceSamplingBlockByBlock) {
  for (FilterKind f : {FilterKind::Tent, FilterKind::Gaussian}) {
    const test::BlockZScores z = againstImportanceSampling(FilmMode::SplatUnbiased, f, 64, 300);
    ASSERT_EQ(z.z.size(), 36u);
    EXPECT_LT(z.meanSquare, 2.0);
    EXPECT_LT(z.worst, 4.5);
  }
}

// The weighted film is a ratio estimate: its bias falls like 1/spp; at 16 spp it is far below
// the noise of ten renders.
TEST(StatisticalFilm, WeightedSplatMatchesImportanceSamplingBlockByBlock) {
  const test::BlockZScores z = againstImportanceSampling(FilmMode::Splat, FilterKind::Tent, 16, 400);
  EXPECT_LT(z.meanSquare, 2.0);
  EXPECT_LT(z.worst, 4.5);
}

TEST(Film, BoxSplatIsImportanceSampling) {
  const Scene scene = defaultScene();
  const RgbImage fis = renderFilm(scene, FilmMode::Fis, FilterKind::Box, 4, 9);
  for (FilmMode m : {FilmMode::Splat, FilmMode::SplatUnbiased}) {
    const RgbImage s = renderFilm(scene, m, FilterKind::Box, 4, 9);
    for (size_t i = 0; i < fis.pixels.size(); ++i)
      for (int c = 0; c < 3; ++c) ASSERT_NEAR(s.pixels[i][c], fis.pixels[i][c], 1e-5f * (1 + fis.pixels[i][c])) << i;
  }
}

TEST(Film, SplatSameImageForAnyThreadCount) {
  const Scene scene = defaultScene();
  for (FilmMode m : {FilmMode::Splat, FilmMode::SplatUnbiased})
    for (FilterKind f : {FilterKind::Tent, FilterKind::Gaussian})
      test::expectBitIdentical(renderFilm(scene, m, f, 3, 5, 1), renderFilm(scene, m, f, 3, 5, 2));
}

TEST(Film, AutoSplatsWideFiltersOnly) {
  EXPECT_EQ(filmModeFor(FilmMode::Auto, FilterKind::Box), FilmMode::Fis);
  EXPECT_EQ(filmModeFor(FilmMode::Auto, FilterKind::Tent), FilmMode::Splat);
  EXPECT_EQ(filmModeFor(FilmMode::Auto, FilterKind::Gaussian), FilmMode::Splat);
  EXPECT_EQ(filmModeFor(FilmMode::SplatUnbiased, FilterKind::Box), FilmMode::SplatUnbiased);
}

}  // namespace
}  // namespace erpt
