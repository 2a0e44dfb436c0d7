// The path tracer's seed store: the image is exactly the sum of the seeds' contributions,
// and every recorded density and estimate can be recomputed from the stored vertices.
#include <gtest/gtest.h>

#include "core/seeds.h"
#include "models/bsdf.h"
#include "models/light_sampler.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "models/surface.h"
#include "support/environment_scene.h"
#include "support/test_support.h"

namespace erpt {
namespace {

struct SeededRender {
  RgbImage image;
  SeedStore seeds;
};

SeededRender renderWithSeeds(const Scene& scene, int size, int spp, int threads = 0) {
  SeededRender out;
  RenderSettings s;
  s.integrator = "path";
  s.width = s.height = size;
  s.spp = spp;
  s.seed = 3;
  s.threads = threads;
  s.filterSet = true;
  s.filter = FilterKind::Box;
  s.seeds = &out.seeds;
  RenderStats stats;
  out.image = render(scene, s, stats);
  EXPECT_EQ(stats.invalidSamples, 0u);
  return out;
}

Vec3 vertexPosition(const VertexQueue& v, size_t i) { return v.pAt(i); }

// Where the ray from vertex i towards vertex j started: the path tracer pushes ray origins
// off the surface (offsetOrigin), so directions are recomputed from that point, as traced.
Vec3 rayOrigin(const VertexQueue& v, size_t i, size_t j) {
  Vec3 x = vertexPosition(v, i);
  if (v.kind[i] == kEyeVertex) return x;
  return offsetOrigin(x, v.ngAt(i), vertexPosition(v, j) - x);
}

class SeedStoreTest : public ::testing::TestWithParam<const char*> {
 protected:
  Scene scene() const {
    std::string which = GetParam();
    if (which == "cornell") return loadScene(test::sharedScenesDir() + "/cornell-box/scene.xml");
    // Plastic has a Dirac coat and a smooth lobe at the same vertex: a next-event seed there is
    // non-specular, whatever lobe the path tracer's continuation took.
    if (which == "plastic") return loadScene(test::sourceDir() + "/tests/data/plastic-box.xml");
    // A sphere light (next-event estimation samples the cone it subtends) and glass spheres.
    if (which == "spheres") return loadScene(test::sourceDir() + "/tests/data/sphere-lights.xml");
    // An environment map (radiance and pdf by direction) with a sun and a glass sphere.
    if (which == "envmap") {
      test::TempDir dir;
      return loadScene(test::writeEnvmapGlassScene(dir));
    }
    return loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  }
};

TEST_P(SeedStoreTest, ImageIsTheSumOfSeedContributions) {
  Scene sc = scene();
  const int size = 24, spp = 8;
  SeededRender r = renderWithSeeds(sc, size, spp);
  ASSERT_GT(r.seeds.size(), 1000u);
  std::vector<double> sum(size_t(size) * size * 3, 0.0);
  for (size_t i = 0; i < r.seeds.size(); ++i) {
    Color c = r.seeds.contribution(i);
    for (int ch = 0; ch < 3; ++ch) sum[3 * r.seeds.seeds.pixel[i] + ch] += c[ch];
  }
  for (size_t p = 0; p < size_t(size) * size; ++p)
    for (int ch = 0; ch < 3; ++ch) {
      double expected = r.image.pixels[p][ch], got = sum[3 * p + ch] / spp;
      ASSERT_NEAR(got, expected, 1e-5 + 1e-4 * expected) << "pixel " << p << " channel " << ch;
    }
}

TEST_P(SeedStoreTest, DensitiesAndEstimatesRecomputeFromVertices) {
  Scene sc = scene();
  const int size = 16;
  // The sphere light is small: BSDF samples reach it rarely, so more samples per pixel.
  SeededRender r = renderWithSeeds(sc, size, std::string(GetParam()) == "spheres" ? 256 : 32);
  LightSampler lights(sc);
  const VertexQueue& v = r.seeds.vertices;
  const SeedQueue& s = r.seeds.seeds;
  size_t checkedSpecular = 0, checkedExplicit = 0, checkedImplicit = 0;
  for (size_t k = 0; k < r.seeds.size(); ++k) {
    const size_t b = s.vertexBegin[k], n = s.vertexCount[k];
    ASSERT_GE(n, 2u);
    ASSERT_EQ(v.kind[b], kEyeVertex);
    ASSERT_TRUE(v.kind[b + n - 1] == kLightVertex || v.kind[b + n - 1] == kEnvironmentVertex);
    // The pixel is the one the film position lies in (box filter).
    EXPECT_EQ(s.pixel[k], uint32_t(int(s.filmY[k]) * size + int(s.filmX[k])));
    const bool explicitLight = s.explicitLight[k] != 0;
    Color estimate(1.0f);
    for (size_t i = 1; i + 1 < n; ++i) {
      const size_t at = b + i;
      Vec3 x = vertexPosition(v, at);
      const bool toLight = explicitLight && i + 2 == n;  // next-event rays aim from x itself
      Vec3 wi = normalize(rayOrigin(v, at - 1, at) - x);
      Vec3 wo = normalize(vertexPosition(v, at + 1) - (toLight ? x : rayOrigin(v, at, at + 1)));
      Frame frame(v.nsAt(at));
      const Material& m = sc.materials[v.material[at]];
      SurfaceColors colors = sc.surfaceColors(v.material[at], v.u[at], v.v[at]);
      Vec3 wiL = frame.toLocal(wi), woL = frame.toLocal(wo);
      if (v.kind[at] == kSpecularVertex) {
        Color value;
        float p;
        ASSERT_TRUE(bsdfDeltaLobe(m, colors, wiL, woL, value, p)) << "seed " << k << " vertex " << i;
        EXPECT_NEAR(p, v.pdfForward[at], 1e-4f * std::max(1.0f, p)) << "p_s, seed " << k << " vertex " << i;
        estimate *= value / p;
        ++checkedSpecular;
        continue;
      }
      ASSERT_EQ(v.kind[at], kNonSpecularVertex);
      Color f = bsdfEval(m, colors, wiL, woL);
      float pd = bsdfPdf(m, colors, wiL, woL);
      // Vertices are floats (about 1e-6 apart from the traced points): over a short segment
      // at a grazing angle that moves cos(theta), so the tolerance grows as 1e-6 / (len cos).
      const float segment = length(vertexPosition(v, at + 1) - x);
      const float slack = 1e-6f / (segment * std::max(std::abs(woL.z), 1e-3f));
      EXPECT_NEAR(pd, v.pdfForward[at], (2e-3f + slack) * pd + 1e-6f) << "p_d, seed " << k << " vertex " << i;
      if (toLight) {
        // The last segment was sampled on the light: pLight is the area density of that.
        Vec3 l = vertexPosition(v, at + 1);
        if (v.kind[at + 1] == kEnvironmentVertex) {
          estimate *= f / s.pLight[k];
        } else {
          Vec3 nl = v.ngAt(at + 1);
          Vec3 d = l - x;
          float dist2 = dot(d, d);
          estimate *= f * (std::abs(dot(nl, wo)) / (dist2 * s.pLight[k]));
        }
      } else {
        estimate *= f / pd;
      }
    }
    // The scenes have one emitter each: its radiance (an environment's: along the direction).
    const size_t last = b + n - 1;
    Color le = sc.emitters[0].radiance;
    if (v.kind[last] == kEnvironmentVertex) {
      const Vec3 towardsEnvironment = -v.ngAt(last);
      le = sc.emitters[0].environmentRadiance(towardsEnvironment);
      // Either way the path found it, the density next-event estimation would have had there.
      EXPECT_NEAR(s.pLight[k], lights.pdfEnvironment(towardsEnvironment), 1e-4f * s.pLight[k]) << "seed " << k;
    }
    estimate = estimate * le / s.pLength[k];
    Color recorded = s.estimateAt(k);
    for (int ch = 0; ch < 3; ++ch)
      EXPECT_NEAR(estimate[ch], recorded[ch], 2e-3f * std::abs(recorded[ch]) + 1e-6f)
          << "seed " << k << " channel " << ch << " (" << n << " vertices, explicit " << explicitLight << ")";
    (explicitLight ? checkedExplicit : checkedImplicit)++;
    if (HasFailure()) break;
  }
  EXPECT_GT(checkedExplicit, 100u);
  EXPECT_GT(checkedImplicit, 100u);
  if (std::string(GetParam()) != "cornell" && std::string(GetParam()) != "plastic") {
    EXPECT_GT(checkedSpecular, 100u);
  }
}

TEST(SeedStore, SameSeedsForAnyThreadCount) {
  Scene sc = loadScene(test::sourceDir() + "/scenes/default/scene.xml");
  SeededRender a = renderWithSeeds(sc, 16, 2, 1), b = renderWithSeeds(sc, 16, 2, 2);
  ASSERT_EQ(a.seeds.size(), b.seeds.size());
  for (size_t k = 0; k < a.seeds.size(); ++k) {
    ASSERT_EQ(a.seeds.seeds.pixel[k], b.seeds.seeds.pixel[k]);
    ASSERT_EQ(a.seeds.seeds.estimateR[k], b.seeds.seeds.estimateR[k]);
    ASSERT_EQ(a.seeds.seeds.vertexCount[k], b.seeds.seeds.vertexCount[k]);
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, SeedStoreTest, ::testing::Values("cornell", "default", "plastic", "spheres", "envmap"));

}  // namespace
}  // namespace erpt
