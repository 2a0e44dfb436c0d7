// BDPT's diffuse walk kernel (stages/bdpt_walk_diffuse.h) against the scalar walk, bounce by
// bounce: from the same walks, hits and random numbers, both must write the same vertex (its
// geometry, beta and densities), the same density back to the previous vertex, the same next
// ray and walk state and the same roulette outcome, up to rounding. Both subpaths are walked in
// a closed room of two-sided walls, a one-sided panel (seen from both sides) and a smooth
// octahedron, lit by a triangle light and an environment map, so that light subpaths start at
// a point and at infinity; the walks go on with the scalar result, so each bounce starts both
// kernels from the same state. They run without a limit, with a depth limit, and with a
// strategy's caps on the subpaths' vertices (as mmlt's samples have). An analytic sphere's hits
// stay with the scalar walk, beside the packet's.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "core/rng.h"
#include "erpt/scene_loader.h"
#include "integrators/bdpt/bdpt_wavefront.h"
#include "models/camera.h"
#include "stages/bdpt_walk_diffuse.h"
#include "support/diffuse_room.h"
#include "support/environment_scene.h"
#include "support/slot_differences.h"
#include "support/stage_world.h"
#include "support/test_support.h"
#include "tracer/tracer.h"

namespace erpt {
namespace {

const std::string kRoom = std::string(R"(<scene version="3.0.0">
  <sensor type="perspective"><float name="fov" value="70"/>
    <transform name="to_world"><lookat origin="0.3,0.2,1.8" target="0,-0.2,0" up="0,1,0"/></transform>
    <film type="hdrfilm"><integer name="width" value="23"/><integer name="height" value="17"/></film></sensor>
)") + test::kDiffuseRoomWalls + R"(
  <shape type="rectangle">
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4 0.4 0.9"/></bsdf>
    <transform name="to_world"><rotate x="1" angle="30"/><translate y="-0.5" x="-0.6"/></transform>
  </shape>
  <shape type="obj"><string name="filename" value="octahedron.obj"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2 0.8 0.4"/></bsdf>
    <transform name="to_world"><scale value="2"/><translate x="0.6" z="0.3"/></transform></shape>
  <shape type="sphere"><point name="center" value="-0.9, 1, -0.8"/><float name="radius" value="0.3"/>
    <bsdf type="diffuse"/></shape>
  <shape type="rectangle">
    <emitter type="area"><rgb name="radiance" value="5 5 5"/></emitter>
    <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="90"/><translate y="1.9"/></transform>
  </shape>
  <emitter type="envmap"><string name="filename" value="sky.exr"/><float name="scale" value="0.02"/></emitter>
</scene>)";

struct Walk {
  BdptSubpaths paths;
  BdptWalkQueue walks;
  RayQueue rays;
  std::vector<uint8_t> alive;
};

TEST(BdptDiffuseWalk, VectorKernelMatchesTheScalarWalkBounceByBounce) {
  test::TempDir dir;
  writeImageAtomic(dir.file("sky.exr"), test::skyImage());
  dir.write("octahedron.obj", test::kSmoothOctahedronObj);
  test::StageWorld world(dir.write("s.xml", kRoom), 3, 23, 17, 5);
  const Tracer& tracer = world.tracer;
  StageContext& stage = world.ctx;
  stage.rrDepth = 2;
  const BdptContext ctx{stage, 17};
  const size_t n = 23 * 17 * 5;  // 1955: not a multiple of the packet or of any vector width

  size_t compared = 0, taken = 0, aliveDiffer = 0, bounced = 0, rouletteDeaths = 0, fromInfinity = 0;
  std::vector<double> vertexErr, betaErr, densityErr, rayErr, walkErr;
  size_t depthStops = 0;  // vertices written without a bounce, at the depth limit or a cap
  size_t smooth = 0;      // vertices whose shading normal is not their face's
  std::vector<double> smoothLightBetaErr;
  struct Run {
    BdptSide side;
    int maxDepth;
    bool capped;
  };
  for (const Run& r : {Run{BdptSide::Light, -1, false}, Run{BdptSide::Camera, -1, false}, Run{BdptSide::Light, 3, false},
                       Run{BdptSide::Camera, 3, false}, Run{BdptSide::Light, -1, true}, Run{BdptSide::Camera, -1, true}}) {
    const BdptSide side = r.side;
    stage.maxDepth = r.maxDepth;
    BdptWavefront w;
    w.prepare(n);
    for (size_t i = 0; i < n; ++i) w.paths.pixel[i] = uint32_t(i % (23 * 17)), w.paths.sample[i] = uint32_t(i / (23 * 17));
    if (r.capped) {  // a strategy (s, t) per sample, s + t <= 7, as mmlt draws them
      w.paths.strategyS.resize(n);
      w.paths.strategyT.resize(n);
      for (size_t i = 0; i < n; ++i) {
        w.paths.strategyS[i] = int16_t(1 + i % 5);
        w.paths.strategyT[i] = int16_t(1 + (i / 5) % 6);
      }
    }
    w.paths.reserveVertices(n);
    if (side == BdptSide::Light) stageBdptStartLight(ctx, w.paths, w.walks, w.rays, 0, w.alive, {0, n});
    else stageBdptStartCamera(ctx, w.paths, w.walks, w.rays, 0, w.alive, {0, n});
    w.paths.used = n;
    size_t live = compactWalks(w.walks, w.rays, w.alive, n);
    for (int bounce = 0; bounce < 6 && live > 0; ++bounce) {
      tracer.intersect(w.rays, w.hits, {0, live}, RayCoherence::Incoherent);
      w.paths.reserveVertices(live);
      const size_t base = w.paths.used;
      Walk scalar{w.paths, w.walks, w.rays, w.alive}, vector = scalar;
      for (bool vec : {false, true}) {
        Walk& run = vec ? vector : scalar;
        stage.vectorShading = vec;
        stageBdptExtend(ctx, side, run.paths, run.walks, run.rays, w.hits, base, run.alive, {0, live});
      }
      {  // how many the packet takes
        BdptDiffuseWalkPacket probe;
        for (size_t k = 0; k < live; ++k) {
          if (probe.full()) probe = BdptDiffuseWalkPacket();
          taken += probe.add(ctx, side, w.paths, w.walks, w.hits, k) ? 1 : 0;
        }
      }
      for (size_t k = 0; k < live; ++k) {
        ++compared;
        const size_t v = base + k;
        const uint32_t i = w.walks.sample[k];
        ASSERT_EQ(vector.paths.lightEnd[i], scalar.paths.lightEnd[i]) << "walk " << k;
        ASSERT_EQ(vector.paths.cameraEnd[i], scalar.paths.cameraEnd[i]) << "walk " << k;
        const int32_t end = side == BdptSide::Light ? scalar.paths.lightEnd[i] : scalar.paths.cameraEnd[i];
        if (end == int32_t(v) && !bdptWalkContinues(ctx, side, w.paths, i, w.walks.depth[k])) ++depthStops;
        if (end == int32_t(v)) {  // a vertex was written
          const BdptVertex a = vector.paths.vertices.row(v), b = scalar.paths.vertices.row(v);
          ASSERT_EQ(a.kind, b.kind) << "walk " << k;
          ASSERT_EQ(a.material, b.material) << "walk " << k;
          ASSERT_EQ(a.emitter, b.emitter) << "walk " << k;
          ASSERT_EQ(a.primitive, b.primitive) << "walk " << k;
          ASSERT_EQ(a.parent, b.parent) << "walk " << k;
          vertexErr.push_back(std::max({test::relativeDifference(a.p, b.p), test::relativeDifference(a.ng, b.ng),
                                        test::relativeDifference(a.ns, b.ns),
                                        test::relativeDifference(Vec3(a.u, a.v, 0.0f), Vec3(b.u, b.v, 0.0f))}));
          const double bErr = test::relativeDifference(a.beta, b.beta);
          betaErr.push_back(bErr);
          if (test::relativeDifference(b.ns, b.ng) > 1e-3) {
            ++smooth;
            // From the light a vertex's beta holds 1 / |cos| at its face: a mix-up of the two
            // normals shows only here.
            if (side == BdptSide::Light) smoothLightBetaErr.push_back(bErr);
          }
          densityErr.push_back(std::abs(a.pdfForward - b.pdfForward) / std::max(b.pdfForward, 1e-6f));
          const int32_t prev = b.parent;
          const float pa = vector.paths.vertices.pdfReverse[size_t(prev)], pb = scalar.paths.vertices.pdfReverse[size_t(prev)];
          densityErr.push_back(std::abs(pa - pb) / std::max(pb, 1e-6f));
          fromInfinity += w.paths.vertices.kind[size_t(prev)] == kEnvironmentVertex;
          if (side == BdptSide::Light && w.walks.depth[k] == 1)
            densityErr.push_back(std::abs(vector.paths.lightNextEvent[i] - scalar.paths.lightNextEvent[i]) /
                                 std::max(scalar.paths.lightNextEvent[i], 1e-6f));
        }
        aliveDiffer += vector.alive[k] != scalar.alive[k];
        if (scalar.alive[k] && vector.alive[k]) {
          ++bounced;
          rayErr.push_back(std::max(test::relativeDifference(vector.rays.dirAt(k), scalar.rays.dirAt(k)),
                                    test::relativeDifference(vector.rays.orgAt(k), scalar.rays.orgAt(k))));
          walkErr.push_back(std::max({test::relativeDifference(vector.walks.betaAt(k), scalar.walks.betaAt(k)),
                                      test::relativeDifference(vector.walks.scatterAt(k), scalar.walks.scatterAt(k)),
                                      double(std::abs(vector.walks.pdfNext[k] - scalar.walks.pdfNext[k]) /
                                             scalar.walks.pdfNext[k])}));
          ASSERT_EQ(vector.walks.depth[k], scalar.walks.depth[k]);
          ASSERT_EQ(vector.walks.vertex[k], scalar.walks.vertex[k]);
        } else if (!scalar.alive[k] && w.walks.depth[k] >= uint32_t(stage.rrDepth)) {
          ++rouletteDeaths;
        }
      }
      // On from the scalar walk's state.
      w.paths = scalar.paths;
      w.walks = scalar.walks;
      w.rays = scalar.rays;
      w.alive = scalar.alive;
      w.paths.used = base + live;
      live = compactWalks(w.walks, w.rays, w.alive, live);
    }
  }
  std::printf("compared %zu, taken %zu, bounced %zu, roulette or other deaths %zu, from infinity %zu, stopped at the "
              "depth limit or a cap %zu, smooth %zu; alive differs %zu\n",
              compared, taken, bounced, rouletteDeaths, fromInfinity, depthStops, smooth, aliveDiffer);
  // Every case in numbers: most walks in the packet, bounces, deaths, light subpaths from the map.
  EXPECT_GT(taken, compared * 6 / 10);
  EXPECT_GT(bounced, compared / 3);
  EXPECT_GT(rouletteDeaths, compared / 50);
  EXPECT_GT(fromInfinity, n / 50);
  EXPECT_GT(depthStops, compared / 50);
  EXPECT_GT(smooth, compared / 20);
  EXPECT_GT(smoothLightBetaErr.size(), compared / 100);
  EXPECT_LT(test::quantile(smoothLightBetaErr, 0.99), 1e-4) << "beta of smooth vertices from the light";
  EXPECT_LE(aliveDiffer, compared / 1000);
  const char* names[] = {"vertex", "beta", "densities", "next ray", "walk"};
  int k = 0;
  for (const auto* errors : {&vertexErr, &betaErr, &densityErr, &rayErr, &walkErr}) {
    EXPECT_LT(test::quantile(*errors, 0.5), 1e-6) << names[k];
    EXPECT_LT(test::quantile(*errors, 0.99), 1e-4) << names[k];
    ++k;
  }
}

}  // namespace
}  // namespace erpt
