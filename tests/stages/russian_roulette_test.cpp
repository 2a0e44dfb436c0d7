// Russian roulette's survival rule, in the shade stage: min(0.95, max(throughput) eta^2), eta
// the product of the relative IORs crossed (Mitsuba 0.6's). Without eta^2 a path refracting
// into glass (BSDF weight 1/eta^2 = 0.44 at eta 1.5) survived with 0.44 instead of 0.95, and
// interiors lit through glass were left half black.
#include <gtest/gtest.h>

#include <limits>

#include "models/camera.h"
#include "erpt/scene_loader.h"
#include "stages/stages.h"
#include "tracer/tracer.h"
#include "support/shade_queues.h"
#include "support/stage_world.h"
#include "support/test_support.h"

namespace erpt {
namespace {

// Paths that went on after the bounce, by the way they left the glass.
struct Outcome {
  size_t refractedAlive = 0, reflectedAlive = 0;
};

// n paths at depth `depth` with throughput 1 hit a glass slab head-on; counts which went on.
Outcome shadeAtGlass(int depth, size_t n) {
  test::TempDir dir;
  test::StageWorld world(dir.write("s.xml", R"(<scene version="3.0.0">
    <shape type="cube"><bsdf type="dielectric"><float name="int_ior" value="1.5"/><float name="ext_ior" value="1"/></bsdf>
      <transform name="to_world"><scale x="2" y="2" z="0.1"/></transform></shape>
    <emitter type="constant"/></scene>)"),
                         7, 4, 4, 1);
  const StageContext& ctx = world.ctx;
  test::ShadeQueues q(n);
  auto& [paths, slots, rays, shadowRays, hits] = q;
  for (size_t k = 0; k < n; ++k) {
    q.startSlot(k, ctx.seed, 16, Vec3(0, 0, 3), Vec3(0, 0, -1));
    paths.depth[k] = uint32_t(depth);
  }
  world.tracer.intersect(rays, hits, {0, n}, RayCoherence::Incoherent);
  stageShadePath(ctx, paths, slots, rays, hits, shadowRays, VertexHistory{}, {0, n});
  Outcome o;
  // Survivors carry their next ray: down into the slab (refracted) or back up (reflected). A
  // path the roulette ended has alive = 0; the BSDF sample itself never fails here.
  for (size_t k = 0; k < n; ++k)
    if (slots.alive[k]) ++(rays.dirAt(k).z < 0 ? o.refractedAlive : o.reflectedAlive);
  return o;
}

TEST(RussianRoulette, RefractionIntoGlassSurvivesAsOftenAsMitsubas) {
  const size_t n = 20000;
  // Before roulette (depth 1) every path goes on: 4% reflect (Fresnel at normal incidence, eta
  // 1.5), 96% refract.
  const Outcome before = shadeAtGlass(1, n);
  const double refractShare = double(before.refractedAlive) / double(n);
  EXPECT_NEAR(refractShare, 0.96, 0.01);
  EXPECT_EQ(before.refractedAlive + before.reflectedAlive, n);
  // From depth 5: a refracted path has throughput 1/eta^2 and eta^2 = 2.25, so it survives
  // with min(0.95, 1) = 0.95 (0.44 without the eta^2); a reflected one with 0.95 too.
  const Outcome after = shadeAtGlass(5, n);
  const double survival = double(after.refractedAlive) / (refractShare * double(n));
  EXPECT_NEAR(survival, 0.95, 0.02) << "refracted survivors " << after.refractedAlive;
}

}  // namespace
}  // namespace erpt
