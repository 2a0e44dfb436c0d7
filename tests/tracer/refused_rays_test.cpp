// The tracer never hands Embree a ray with a non-finite origin or direction, a zero
// direction or a NaN interval (Debian's Embree aborts on them in its AVX-512 kernels). The
// check is ours, so these tests mean the same on every CPU: refused rays come back flagged,
// counted, and the samples they belong to are dropped as invalid.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "tracer/tracer.h"
#include "support/test_support.h"

namespace erpt {
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

Scene quadScene(const test::TempDir& dir) {
  return loadScene(dir.write("s.xml", R"(<scene version="3.0.0"><shape type="rectangle"/></scene>)"));
}

struct BadRay {
  Vec3 org, dir;
  float tnear, tfar;
};

// Every way a ray can be untraceable; each would hit the unit quad at z = 0 if it were sane.
const BadRay kBadRays[] = {
    {{kNaN, 0, 1}, {0, 0, -1}, 0, kInf},   {{0, kInf, 1}, {0, 0, -1}, 0, kInf},
    {{0, 0, -kInf}, {0, 0, -1}, 0, kInf},  {{0, 0, 1}, {0, 0, kNaN}, 0, kInf},
    {{0, 0, 1}, {kInf, 0, -1}, 0, kInf},   {{0, 0, 1}, {0, 0, 0}, 0, kInf},
    {{0, 0, 1}, {0, 0, -1}, kNaN, kInf},   {{0, 0, 1}, {0, 0, -1}, 0, kNaN},
    {{0, 0, 1}, {0, 0, -1}, -kInf, kInf},  {{0, 0, 1}, {0, 0, -1}, -1, kInf},
};

// Good rays interleaved with bad ones, so that a refusal must not disturb its neighbours.
void fillMixedBatch(RayQueue& rays, size_t& bad) {
  const size_t n = 2 * std::size(kBadRays) + 1;
  prepareRays(rays, n);
  bad = 0;
  for (size_t i = 0; i < n; ++i) {
    if (i % 2 == 0) {
      setRay(rays, i, Vec3(0.25f, -0.25f, 1.0f), Vec3(0, 0, -1), 0.0f, kInf);
    } else {
      const BadRay& b = kBadRays[i / 2];
      setRay(rays, i, b.org, b.dir, b.tnear, b.tfar);
      ++bad;
    }
  }
}

TEST(RefusedRays, IntersectFlagsAndCountsEveryUntraceableRay) {
  test::TempDir dir;
  Scene scene = quadScene(dir);
  Tracer tracer(scene);
  RayQueue rays;
  HitQueue hits;
  size_t bad = 0;
  fillMixedBatch(rays, bad);
  hits.resize(rays.size());
  tracer.intersect(rays, hits, {0, rays.size()}, RayCoherence::Incoherent);
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 2 == 0) {
      EXPECT_NE(hits.geomID[i], kNoHit) << i;
      EXPECT_NE(hits.geomID[i], kRefusedRay) << i;
      EXPECT_NEAR(rays.tfar[i], 1.0f, 1e-5f) << i;
    } else {
      EXPECT_EQ(hits.geomID[i], kRefusedRay) << "bad ray " << i / 2;
    }
  }
  EXPECT_EQ(tracer.refusedRays(), bad);
}

// Each kind of bad ray alone among good ones, at every position of a SIMD batch and in the
// scalar tail: the batch test must see it by itself.
TEST(RefusedRays, EachKindAloneIsFoundAnywhereInTheBatch) {
  test::TempDir dir;
  Scene scene = quadScene(dir);
  Tracer tracer(scene);
  const size_t n = 37;  // not a multiple of any SIMD width: a scalar tail too
  uint64_t expected = 0;
  for (const BadRay& b : kBadRays)
    for (size_t at = 0; at < n; ++at) {
      RayQueue rays;
      HitQueue hits;
      prepareRays(rays, n);
      hits.resize(n);
      for (size_t i = 0; i < n; ++i) setRay(rays, i, Vec3(0.25f, -0.25f, 1.0f), Vec3(0, 0, -1), 0.0f, kInf);
      setRay(rays, at, b.org, b.dir, b.tnear, b.tfar);
      tracer.intersect(rays, hits, {0, n}, RayCoherence::Incoherent);
      ++expected;
      ASSERT_EQ(hits.geomID[at], kRefusedRay) << "bad ray " << (&b - kBadRays) << " at " << at;
      ASSERT_EQ(tracer.refusedRays(), expected);
    }
}

TEST(RefusedRays, OccludedReportsRefusedShadowRaysAsBlocked) {
  test::TempDir dir;
  Scene scene = quadScene(dir);
  Tracer tracer(scene);
  RayQueue rays;
  size_t bad = 0;
  fillMixedBatch(rays, bad);
  // The good rays stop short of the quad: unoccluded.
  for (size_t i = 0; i < rays.size(); i += 2) rays.tfar[i] = 0.5f;
  tracer.occluded(rays, {0, rays.size()});
  for (size_t i = 0; i < rays.size(); ++i) {
    if (i % 2 == 0) EXPECT_EQ(rays.tfar[i], 0.5f) << i;
    else EXPECT_EQ(rays.tfar[i], -kInf) << "bad ray " << i / 2;
  }
  EXPECT_EQ(tracer.refusedRays(), bad);
}

// Disabled rays (an empty interval) are skipped, not refused, whatever stale numbers their
// columns hold.
TEST(RefusedRays, DisabledRaysAreNotRefused) {
  test::TempDir dir;
  Scene scene = quadScene(dir);
  Tracer tracer(scene);
  RayQueue rays;
  HitQueue hits;
  prepareRays(rays, 3);
  hits.resize(3);
  setRay(rays, 0, Vec3(kNaN), Vec3(0, 0, kInf), 0.0f, kInf);
  disableRay(rays, 0);
  setRay(rays, 1, Vec3(0, 0, 1), Vec3(0, 0, -1), 0.0f, kInf);
  setRay(rays, 2, Vec3(0, 0, 1), Vec3(0, 0, -1), 0.0f, kInf);
  disableRay(rays, 2);
  tracer.intersect(rays, hits, {0, 3}, RayCoherence::Incoherent);
  EXPECT_EQ(hits.geomID[0], kNoHit);
  EXPECT_NE(hits.geomID[1], kNoHit);
  EXPECT_EQ(hits.geomID[2], kNoHit);
  EXPECT_EQ(tracer.refusedRays(), 0u);
}

// End to end: a camera whose transform is valid in double but whose rays overflow in float
// cannot be built from XML any more (transform_checks_test.cpp), so the path tracer is fed a
// scene whose camera is poisoned after loading. Every sample is dropped and counted; nothing
// crashes, whichever CPU runs it.
TEST(RefusedRays, PathTracerDropsAndCountsTheSamples) {
  test::TempDir dir;
  Scene scene = quadScene(dir);
  scene.camera.toWorld(0, 3) = std::numeric_limits<double>::quiet_NaN();
  for (const char* integrator : {"path", "direct"}) {
    RenderSettings settings;
    settings.integrator = integrator;
    settings.width = 7;
    settings.height = 5;
    settings.spp = 2;
    settings.threads = 1;
    RenderStats stats;
    RgbImage image = render(scene, resolveSettings(scene, settings), stats);
    EXPECT_EQ(stats.invalidSamples, 7u * 5u * 2u) << integrator;
    EXPECT_EQ(stats.refusedRays, 7u * 5u * 2u) << integrator;
    for (const Color& c : image.pixels) EXPECT_TRUE(isFinite(c)) << integrator;
  }
}

}  // namespace
}  // namespace erpt
