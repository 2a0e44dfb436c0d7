// The diffuse vector kernel (stages/shade_path_diffuse.h) against the scalar body of the shade
// stage, slot by slot: the same hits, random numbers and path state must give the same next-event
// contribution, shadow ray, bounce, throughput and roulette outcome, and record the same seed
// vertex and connection, up to rounding. The scene
// has every case the kernel takes: two-sided walls seen from inside, a one-sided panel seen
// from both sides, smooth normals, light points behind the surface, roulette at every depth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "erpt/scene_loader.h"
#include "models/camera.h"
#include "stages/shade_path_diffuse.h"
#include "stages/stages.h"
#include "support/diffuse_room.h"
#include "support/environment_scene.h"
#include "support/shade_queues.h"
#include "support/slot_differences.h"
#include "support/stage_world.h"
#include "support/test_support.h"
#include "tracer/tracer.h"

namespace erpt {
namespace {


const std::string kScene = std::string(R"(<scene version="3.0.0">
)") + test::kDiffuseRoomWalls + R"(
  <shape type="rectangle">
    <bsdf type="diffuse"><rgb name="reflectance" value="0.4 0.4 0.9"/></bsdf>
    <transform name="to_world"><rotate x="1" angle="30"/><translate y="-0.5" x="-0.6"/></transform>
  </shape>
  <shape type="obj">
    <string name="filename" value="octahedron.obj"/>
    <bsdf type="diffuse"><rgb name="reflectance" value="0.2 0.8 0.4"/></bsdf>
    <transform name="to_world"><translate x="0.8" z="0.5"/></transform>
  </shape>
  LIGHTS
</scene>)";

constexpr const char* kTriangleLight = R"(<shape type="rectangle">
    <emitter type="area"><rgb name="radiance" value="5 5 5"/></emitter>
    <transform name="to_world"><scale value="0.4"/><rotate x="1" angle="90"/><translate y="1.9"/></transform>
  </shape>)";

// Sphere lights as the kernel samples them: in the cone from outside (one small, one large
// and close to the walls), by area from inside the one that emits inwards (around the panel),
// and a triangle light, so that batches mix both kinds.
constexpr const char* kSphereLights = R"(<shape type="sphere"><point name="center" value="-1.2, 1.5, -1.2"/>
    <float name="radius" value="0.15"/><emitter type="area"><rgb name="radiance" value="20 10 5"/></emitter></shape>
  <shape type="sphere"><point name="center" value="1.3, -1.3, -1.3"/><float name="radius" value="0.6"/>
    <emitter type="area"><rgb name="radiance" value="1 2 3"/></emitter></shape>
  <shape type="sphere"><point name="center" value="-0.6, -0.5, 0"/><float name="radius" value="0.9"/>
    <boolean name="flip_normals" value="true"/><emitter type="area"><rgb name="radiance" value="0.5 0.5 0.5"/></emitter></shape>
  <shape type="rectangle">
    <emitter type="area"><rgb name="radiance" value="2 2 2"/></emitter>
    <transform name="to_world"><scale value="0.3"/><rotate x="1" angle="90"/><translate y="1.9" x="1"/></transform>
  </shape>)";

// The environment: a map (sampled by its pixels, in the lanes' CDF searches) beside a triangle
// light, and a constant one (uniform directions) beside a sphere light.
constexpr const char* kEnvironmentMap = R"(<emitter type="envmap"><string name="filename" value="sky.exr"/>
    <float name="scale" value="0.05"/><transform name="to_world"><rotate y="1" angle="30"/></transform></emitter>
  <shape type="rectangle">
    <emitter type="area"><rgb name="radiance" value="2 2 2"/></emitter>
    <transform name="to_world"><scale value="0.3"/><rotate x="1" angle="90"/><translate y="1.9" x="1"/></transform>
  </shape>)";
constexpr const char* kConstantEnvironment = R"(<emitter type="constant"><rgb name="radiance" value="0.05 0.06 0.07"/></emitter>
  <shape type="sphere"><point name="center" value="-1.2, 1.5, -1.2"/>
    <float name="radius" value="0.15"/><emitter type="area"><rgb name="radiance" value="20 10 5"/></emitter></shape>)";

std::string sceneWithLights(const char* lights) {
  std::string scene = kScene;
  scene.replace(scene.find("LIGHTS"), 6, lights);
  return scene;
}

using Queues = test::ShadeQueues;

// n slots whose rays leave random points of the room in random directions, at depths 1..8,
// with random throughputs, already intersected.
Queues randomHits(const Tracer& tracer, uint64_t seed, size_t n) {
  Queues q(n);
  for (size_t k = 0; k < n; ++k) {
    const uint64_t key = streamKey(11, k, 0);
    const Vec3 origin(3 * uniformFloat(key, 0) - 1.5f, 3 * uniformFloat(key, 1) - 1.5f, 3 * uniformFloat(key, 2) - 1.5f);
    q.startSlot(k, seed, 97, origin, squareToUniformSphere(uniformFloat(key, 6), uniformFloat(key, 7)));
    q.paths.depth[k] = 1 + uint32_t(k % 8);
    q.paths.throughputSet(k, Color(0.2f + uniformFloat(key, 3), 0.2f + uniformFloat(key, 4), 0.2f + uniformFloat(key, 5)));
    q.paths.prevPdf[k] = 0.3f;
    q.paths.lastVertex[k] = int32_t(3 * k);  // a parent link the recorded vertex must carry
  }
  tracer.intersect(q.rays, q.hits, {0, n}, RayCoherence::Incoherent);
  return q;
}

using test::quantile;
using test::relativeDifference;

// A triangle light's density and normal are the same bits in both (read from the light's
// row); a sphere's and the environment's are computed, and agree up to rounding. `emitters`: every light of the
// scene is connected to somewhere (so each way of sampling is exercised).
void expectVectorKernelMatchesScalarBody(const char* lightShapes, size_t emitters) {
  test::TempDir dir;
  dir.write("octahedron.obj", test::kSmoothOctahedronObj);
  writeImageAtomic(dir.file("sky.exr"), test::skyImage());
  test::StageWorld world(dir.write("s.xml", sceneWithLights(lightShapes)), 5, 97, 4, 1);
  const Scene& scene = world.scene;
  const Tracer& tracer = world.tracer;
  StageContext& ctx = world.ctx;
  ctx.rrDepth = 3;
  const size_t n = 6007;  // not a multiple of the packet or of any vector width
  Queues scalar = randomHits(tracer, ctx.seed, n);
  Queues vector = scalar;

  // The kernel must take most of these hits (everything but the light and the misses).
  size_t taken = 0;
  {
    DiffuseShadePacket probe;
    for (size_t k = 0; k < n; ++k) {
      if (probe.full()) probe = DiffuseShadePacket();
      taken += probe.add(ctx, vector.paths, vector.slots, vector.hits, k) ? 1 : 0;
    }
  }
  EXPECT_GT(taken, n * 7 / 10);

  // Both record seeds, so the vertex history and the slots' seed columns are compared too.
  VertexQueue scalarHistory, vectorHistory;
  scalarHistory.resize(n);
  vectorHistory.resize(n);
  ctx.vectorShading = false;
  stageShadePath(ctx, scalar.paths, scalar.slots, scalar.rays, scalar.hits, scalar.shadowRays,
                 VertexHistory{&scalarHistory, 0}, {0, n});
  ctx.vectorShading = true;
  stageShadePath(ctx, vector.paths, vector.slots, vector.rays, vector.hits, vector.shadowRays,
                 VertexHistory{&vectorHistory, 0}, {0, n});

  size_t aliveDiffer = 0, neeDiffer = 0, alive = 0, connected = 0;
  std::map<int32_t, size_t> connectedTo;  // connections by light, in the scalar body
  // Lights whose sample the kernel computes (a triangle's density and normal it reads).
  std::set<int32_t> computedEmitters;
  for (uint32_t i = 0; i < scene.spheres.count(); ++i) computedEmitters.insert(scene.spheres.emitter[i]);
  if (scene.environment()) computedEmitters.insert(int32_t(scene.environment() - scene.emitters.data()));
  std::vector<double> throughputErr, dirErr, originErr, pdfErr, neeErr, shadowDirErr, tfarErr, vertexErr, seedErr;
  for (size_t k = 0; k < n; ++k) {
    const bool sAlive = scalar.slots.alive[k] != 0, vAlive = vector.slots.alive[k] != 0;
    aliveDiffer += sAlive != vAlive;
    const bool sNee = scalar.shadowRays.tfar[k] >= scalar.shadowRays.tnear[k];
    const bool vNee = vector.shadowRays.tfar[k] >= vector.shadowRays.tnear[k];
    neeDiffer += sNee != vNee;
    if (sAlive && vAlive) {
      ++alive;
      throughputErr.push_back(relativeDifference(vector.paths.throughputAt(k), scalar.paths.throughputAt(k)));
      dirErr.push_back(relativeDifference(vector.rays.dirAt(k), scalar.rays.dirAt(k)));
      originErr.push_back(relativeDifference(vector.rays.orgAt(k), scalar.rays.orgAt(k)));
      pdfErr.push_back(std::abs(vector.paths.prevPdf[k] - scalar.paths.prevPdf[k]) / scalar.paths.prevPdf[k]);
      EXPECT_EQ(vector.paths.depth[k], scalar.paths.depth[k]);
    }
    if (sNee) ++connectedTo[scalar.slots.neeLightEmitter[k]];
    if (sNee && vNee) {
      ++connected;
      neeErr.push_back(relativeDifference(vector.slots.neeAt(k), scalar.slots.neeAt(k)));
      shadowDirErr.push_back(relativeDifference(vector.shadowRays.dirAt(k), scalar.shadowRays.dirAt(k)));
      const float sTfar = scalar.shadowRays.tfar[k], vTfar = vector.shadowRays.tfar[k];
      tfarErr.push_back(sTfar == vTfar ? 0.0 : std::abs(vTfar - sTfar) / sTfar);  // the environment's: both infinite
    }
    EXPECT_EQ(vector.paths.radianceAt(k).x, scalar.paths.radianceAt(k).x);  // emission stays scalar

    // Seed recording: the hit's vertex and what the bounce's contributions were made of.
    ASSERT_EQ(vectorHistory.kind[k], scalarHistory.kind[k]) << "slot " << k;
    ASSERT_EQ(vectorHistory.material[k], scalarHistory.material[k]) << "slot " << k;
    ASSERT_EQ(vectorHistory.parent[k], scalarHistory.parent[k]) << "slot " << k;
    ASSERT_EQ(vectorHistory.emitter[k], scalarHistory.emitter[k]) << "slot " << k;
    ASSERT_EQ(vector.paths.lastVertex[k], scalar.paths.lastVertex[k]) << "slot " << k;
    ASSERT_EQ(vector.slots.pLengthHere[k], scalar.slots.pLengthHere[k]) << "slot " << k;
    ASSERT_EQ(vector.slots.emitWeight[k], scalar.slots.emitWeight[k]) << "slot " << k;
    vertexErr.push_back(std::max({relativeDifference(vectorHistory.pAt(k), scalarHistory.pAt(k)),
                                  relativeDifference(vectorHistory.nsAt(k), scalarHistory.nsAt(k)),
                                  relativeDifference(vectorHistory.ngAt(k), scalarHistory.ngAt(k)),
                                  relativeDifference(Vec3(vectorHistory.u[k], vectorHistory.v[k], 0.0f),
                                                     Vec3(scalarHistory.u[k], scalarHistory.v[k], 0.0f))}));
    if (sAlive && vAlive)
      pdfErr.push_back(std::abs(vectorHistory.pdfForward[k] - scalarHistory.pdfForward[k]) / scalarHistory.pdfForward[k]);
    if (sNee && vNee) {
      ASSERT_EQ(vector.slots.neeLightKind[k], scalar.slots.neeLightKind[k]) << "slot " << k;
      ASSERT_EQ(vector.slots.neeLightEmitter[k], scalar.slots.neeLightEmitter[k]) << "slot " << k;
      const double lightPdfErr =
          std::abs(vector.slots.neeLightPdf[k] - scalar.slots.neeLightPdf[k]) / scalar.slots.neeLightPdf[k];
      const double lightNormalErr = relativeDifference(vector.slots.neeLightNAt(k), scalar.slots.neeLightNAt(k));
      if (computedEmitters.count(scalar.slots.neeLightEmitter[k]) == 0) {
        ASSERT_EQ(lightPdfErr, 0.0) << "slot " << k;
        ASSERT_EQ(lightNormalErr, 0.0) << "slot " << k;
      }
      seedErr.push_back(std::max({lightPdfErr, lightNormalErr,
                                  relativeDifference(vector.slots.neeLightAt(k), scalar.slots.neeLightAt(k)),
                                  double(std::abs(vector.slots.neeWeight[k] - scalar.slots.neeWeight[k])),
                                  double(std::abs(vector.slots.neeBsdfPdf[k] - scalar.slots.neeBsdfPdf[k]) /
                                         scalar.slots.neeBsdfPdf[k])}));
    }
  }
  // Every case is exercised in numbers: bounces, roulette deaths, connections and failed ones.
  EXPECT_GT(alive, n / 3);
  EXPECT_LT(alive, n * 95 / 100);
  EXPECT_GT(connected, n / 5);
  EXPECT_LT(connected, n * 9 / 10);
  // A decision may differ only where rounding puts a value on the other side of a threshold.
  EXPECT_LE(aliveDiffer, n / 1000) << "of " << n;
  EXPECT_LE(neeDiffer, n / 1000) << "of " << n;
  EXPECT_EQ(connectedTo.size(), emitters);
  for (const auto& [emitter, count] : connectedTo) EXPECT_GT(count, n / 200) << "emitter " << emitter;
  const char* names[] = {"throughput", "direction",   "origin",          "pdf",           "next-event",
                         "shadow direction", "shadow tfar", "recorded vertex", "recorded light"};
  int i = 0;
  for (const auto* errors :
       {&throughputErr, &dirErr, &originErr, &pdfErr, &neeErr, &shadowDirErr, &tfarErr, &vertexErr, &seedErr}) {
    EXPECT_LT(quantile(*errors, 0.5), 1e-6) << names[i];
    EXPECT_LT(quantile(*errors, 0.99), 1e-4) << names[i];
    ++i;
  }
  std::printf("taken %zu alive %zu connected %zu of %zu; decisions differ: alive %zu, next event %zu\n", taken, alive,
              connected, n, aliveDiffer, neeDiffer);
}

TEST(ShadeDiffuse, VectorKernelMatchesTheScalarBodySlotBySlot) {
  expectVectorKernelMatchesScalarBody(kTriangleLight, 1);
}

TEST(ShadeDiffuse, VectorKernelMatchesTheScalarBodyUnderSphereLights) {
  expectVectorKernelMatchesScalarBody(kSphereLights, 4);
}

TEST(ShadeDiffuse, VectorKernelMatchesTheScalarBodyUnderEnvironmentLights) {
  expectVectorKernelMatchesScalarBody(kEnvironmentMap, 2);
  expectVectorKernelMatchesScalarBody(kConstantEnvironment, 2);
}

}  // namespace
}  // namespace erpt
