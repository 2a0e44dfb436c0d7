// Escaping rays under an environment map: the shade stage's vector lookups
// (stages/shade_path_miss.h) against its scalar body, slot by slot. The same rays must add the
// same MIS-weighted light to their paths and record the same environment vertex, up to the
// rounding of the map lookup's trigonometry.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

#include "core/rng.h"
#include "core/warp.h"
#include "erpt/scene_loader.h"
#include "models/camera.h"
#include "stages/stages.h"
#include "support/environment_scene.h"
#include "support/shade_queues.h"
#include "support/slot_differences.h"
#include "support/stage_world.h"
#include "support/test_support.h"
#include "tracer/tracer.h"

namespace erpt {
namespace {

TEST(ShadeMiss, VectorLookupsMatchTheScalarBody) {
  test::TempDir dir;
  writeImageAtomic(dir.file("sky.exr"), test::skyImage());
  test::StageWorld world(dir.write("s.xml", R"(<scene version="3.0.0">
  <shape type="rectangle"><bsdf type="diffuse"/>
    <transform name="to_world"><rotate x="1" angle="-90"/></transform></shape>
  <shape type="sphere"><float name="radius" value="0.2"/>
    <emitter type="area"><rgb name="radiance" value="5 5 5"/></emitter></shape>
  <emitter type="envmap"><string name="filename" value="sky.exr"/>
    <transform name="to_world"><rotate x="1" y="1" angle="40"/></transform></emitter>
</scene>)"),
                         5, 97, 4, 1);
  StageContext& ctx = world.ctx;
  const size_t n = 5003;  // not a multiple of the packet or of any vector width
  test::ShadeQueues q(n);
  for (size_t k = 0; k < n; ++k) {
    const uint64_t key = streamKey(12, k, 0);
    const Vec3 origin(2 * uniformFloat(key, 0) - 1, 0.5f + uniformFloat(key, 1), 2 * uniformFloat(key, 2) - 1);
    q.startSlot(k, ctx.seed, 97, origin, squareToUniformSphere(uniformFloat(key, 6), uniformFloat(key, 7)));
    q.paths.depth[k] = 1 + uint32_t(k % 5);
    q.paths.throughputSet(k, Color(0.2f + uniformFloat(key, 3), 0.2f + uniformFloat(key, 4), 0.2f + uniformFloat(key, 5)));
    q.paths.prevPdf[k] = k % 7 == 0 ? 0.0f : 0.05f + uniformFloat(key, 8);  // a specular bounce now and then
    q.paths.lastVertex[k] = int32_t(2 * k);
  }
  world.tracer.intersect(q.rays, q.hits, {0, n}, RayCoherence::Incoherent);
  const HitQueue& hits = q.hits;

  struct Run {
    test::ShadeQueues q;
    VertexQueue history;
  };
  auto shade = [&](bool vector) {
    Run r{q, {}};
    r.history.resize(n);
    ctx.vectorShading = vector;
    stageShadePath(ctx, r.q.paths, r.q.slots, r.q.rays, hits, r.q.shadowRays, VertexHistory{&r.history, 0}, {0, n});
    return r;
  };
  const Run scalarRun = shade(false), vectorRun = shade(true);
  const test::ShadeQueues &scalar = scalarRun.q, &vector = vectorRun.q;

  size_t misses = 0;
  std::vector<double> radianceErr, vertexErr, weightErr, emitErr;
  for (size_t k = 0; k < n; ++k) {
    if (hits.geomID[k] != kNoHit) continue;
    ++misses;
    ASSERT_EQ(vectorRun.history.kind[k], scalarRun.history.kind[k]) << "slot " << k;
    ASSERT_EQ(vectorRun.history.kind[k], kEnvironmentVertex) << "slot " << k;
    ASSERT_EQ(vectorRun.history.emitter[k], scalarRun.history.emitter[k]) << "slot " << k;
    ASSERT_EQ(vectorRun.history.parent[k], scalarRun.history.parent[k]) << "slot " << k;
    radianceErr.push_back(test::relativeDifference(vector.paths.radianceAt(k), scalar.paths.radianceAt(k), 1e-3f));
    vertexErr.push_back(std::max(test::relativeDifference(vectorRun.history.pAt(k), scalarRun.history.pAt(k)),
                                 test::relativeDifference(vectorRun.history.nsAt(k), scalarRun.history.nsAt(k))));
    weightErr.push_back(std::abs(vector.slots.emitWeight[k] - scalar.slots.emitWeight[k]));
    emitErr.push_back(test::relativeDifference(vector.slots.emitAt(k), scalar.slots.emitAt(k), 1e-3f));
  }
  EXPECT_GT(misses, n / 3);
  const char* names[] = {"radiance", "recorded vertex", "MIS weight", "recorded emission"};
  int i = 0;
  for (const auto* errors : {&radianceErr, &vertexErr, &weightErr, &emitErr}) {
    EXPECT_LT(test::quantile(*errors, 0.5), 1e-6) << names[i];
    EXPECT_LT(test::quantile(*errors, 0.99), 1e-4) << names[i];
    ++i;
  }
  // The hits are shaded alike too (the packet leaves them to the other paths); a decision may
  // differ only where rounding puts a value on the other side of a threshold.
  size_t aliveDiffer = 0;
  for (size_t k = 0; k < n; ++k) aliveDiffer += hits.geomID[k] != kNoHit && vector.slots.alive[k] != scalar.slots.alive[k];
  EXPECT_LE(aliveDiffer, n / 1000);
}

}  // namespace
}  // namespace erpt
