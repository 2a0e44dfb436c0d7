// Exact spheres: loading, hits (position, normal, sphere coordinates), solid-angle light
// sampling against its pdf and against area sampling, closed-form furnaces, and the exact
// sphere against a fine tessellation of it, block by block.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>

#include "models/light_sampler.h"
#include "erpt/render.h"
#include "erpt/scene_loader.h"
#include "models/surface.h"
#include "tracer/tracer.h"
#include "core/warp.h"
#include "support/chi_square.h"
#include "support/image_stats.h"
#include "support/test_support.h"

namespace erpt {
namespace {

using test::TempDir;
using test::testUniform;

// A scene of the given shapes, seen by a fixed camera.
std::string sceneWith(const std::string& shapes) {
  return R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="40"/>
      <transform name="to_world"><lookat origin="0,0,6" target="0,0,0" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="32"/><integer name="height" value="32"/>
        <rfilter type="box"/></film></sensor>)" +
         shapes + "</scene>";
}

TEST(ExactSphere, LoadsAsOneExactSphereWithItsTransform) {
  TempDir dir;
  Scene s = loadScene(dir.write("s.xml", sceneWith(R"(
    <shape type="sphere"><point name="center" value="1, 0, 0"/><float name="radius" value="0.5"/>
      <transform name="to_world"><scale value="2"/><rotate z="1" angle="90"/><translate x="0.5"/></transform>
      <emitter type="area"><rgb name="radiance" value="3"/></emitter></shape>)")));
  ASSERT_EQ(s.spheres.count(), 1u);
  EXPECT_EQ(s.mesh.triangleCount(), 0u);
  EXPECT_EQ(s.shapes[0].sphere, 0);
  // centre (1,0,0) scaled by 2 -> (2,0,0), rotated 90 degrees about z -> (0,2,0), then +x 0.5.
  EXPECT_NEAR(s.spheres.cx[0], 0.5f, 1e-5f);
  EXPECT_NEAR(s.spheres.cy[0], 2.0f, 1e-5f);
  EXPECT_NEAR(s.spheres.cz[0], 0.0f, 1e-5f);
  EXPECT_NEAR(s.spheres.radius[0], 1.0f, 1e-6f);
  EXPECT_EQ(s.spheres.emitter[0], 0);
  EXPECT_EQ(s.emitterOf(s.spherePrimitive(0)), 0);
  // The frame follows the rotation: the sphere's own x axis now points along world y.
  EXPECT_NEAR(s.spheres.frame[0].s.y, 1.0f, 1e-5f);
  EXPECT_TRUE(s.warnings.messages.empty());
}

TEST(ExactSphere, UnevenScaleOrTheOptionTessellates) {
  TempDir dir;
  const std::string file = dir.write("s.xml", sceneWith(R"(
    <shape type="sphere"><transform name="to_world"><scale x="2" y="1" z="1"/></transform></shape>)"));
  Scene uneven = loadScene(file);
  EXPECT_EQ(uneven.spheres.count(), 0u);
  EXPECT_GT(uneven.mesh.triangleCount(), 100000u);
  ASSERT_EQ(uneven.warnings.messages.size(), 1u);
  EXPECT_NE(uneven.warnings.messages[0].find("tessellated"), std::string::npos);

  LoadOptions tessellate;
  tessellate.tessellateSpheres = true;
  Scene t = loadScene(dir.write("t.xml", sceneWith(R"(<shape type="sphere"/>)")), tessellate);
  EXPECT_EQ(t.spheres.count(), 0u);
  EXPECT_GT(t.mesh.triangleCount(), 100000u);
  EXPECT_TRUE(t.warnings.messages.empty());
}

// Rays from outside and from inside hit the analytic point; the hit's (primitive, u, v)
// reconstructs it on the sphere with the radial normal and Mitsuba's texture coordinates.
TEST(ExactSphere, HitsReconstructTheAnalyticPoint) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", sceneWith(R"(
    <shape type="rectangle"><transform name="to_world"><translate z="-5"/></transform></shape>
    <shape type="sphere"><point name="center" value="0.3, -0.2, 0.1"/><float name="radius" value="0.7"/></shape>)")));
  ASSERT_EQ(scene.spheres.count(), 1u);
  Tracer tracer(scene);
  const Vec3 c(0.3f, -0.2f, 0.1f);
  const float r = 0.7f;
  RayQueue rays;
  HitQueue hits;
  const int n = 256;
  prepareRays(rays, n);
  hits.resize(n);
  for (int i = 0; i < n; ++i) {
    // Aim at a point on the sphere from outside (even i) or start at the centre (odd i).
    const Vec3 target = c + squareToUniformSphere(testUniform(i, 0), testUniform(i, 1)) * r;
    const Vec3 org = i % 2 == 0 ? target + normalize(target - c) * 2.0f + Vec3(0.01f, 0.02f, 0.0f) : c;
    setRay(rays, size_t(i), org, normalize(target - org), 0.0f, 1e30f);
  }
  tracer.intersect(rays, hits, {0, size_t(n)}, RayCoherence::Incoherent);
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    ASSERT_NE(hits.geomID[i], kNoHit) << i;
    ASSERT_TRUE(scene.isSphere(hits.primID[i])) << i;
    const SurfacePoint sp = surfaceAt(scene, hits.primID[i], hits.u[i], hits.v[i]);
    const Vec3 expected = rays.orgAt(i) + rays.dirAt(i) * rays.tfar[i];
    worst = std::max(worst, double(length(sp.position - expected)));
    EXPECT_NEAR(length(sp.position - c), r, 2e-6f * r);
    EXPECT_NEAR(dot(sp.geometricNormal, normalize(sp.position - c)), 1.0f, 1e-5f);
    EXPECT_NEAR(dot(sp.shading.n, sp.geometricNormal), 1.0f, 1e-5f);
  }
  EXPECT_LT(worst, 1e-4 * r);
  // Texture coordinates: u = azimuth / 2 pi, v = polar angle / pi (Mitsuba 0.6).
  float u, v;
  sphereCoordinates(scene.spheres, 0, c + Vec3(0, r, 0), u, v);
  EXPECT_NEAR(u, 0.25f, 1e-6f);
  EXPECT_NEAR(v, 0.5f, 1e-6f);
  sphereCoordinates(scene.spheres, 0, c + Vec3(0, 0, -r), u, v);
  EXPECT_NEAR(v, 1.0f, 1e-6f);
  sphereCoordinates(scene.spheres, 0, c + Vec3(-r, 0, 0), u, v);
  EXPECT_NEAR(u, 0.5f, 1e-6f);
}

// A sphere light and a reference point; `inside`: the reference point is inside a sphere
// that emits inwards (sampled by area), otherwise outside an outward one (sampled in the cone).
struct SphereLight {
  TempDir dir;
  Scene scene;
  Vec3 ref, c;
  float r;
  SphereLight(Vec3 center, float radius, Vec3 reference, bool inside) : ref(reference), c(center), r(radius) {
    char shape[512];
    std::snprintf(shape, sizeof shape, R"(<shape type="sphere"><point name="center" value="%g, %g, %g"/>
      <float name="radius" value="%g"/><boolean name="flip_normals" value="%s"/>
      <emitter type="area"><rgb name="radiance" value="2, 1, 0.5"/></emitter></shape>)",
                  center.x, center.y, center.z, radius, inside ? "true" : "false");
    scene = loadScene(dir.write("s.xml", sceneWith(shape)));
  }
  // The light point a ray from ref along w reaches first (the far side from inside).
  std::optional<SurfacePoint> hit(Vec3 w) const {
    const Vec3 oc = ref - c;
    const float b = dot(oc, w), cc = dot(oc, oc) - r * r, disc = b * b - cc;
    if (disc < 0) return std::nullopt;
    const float t = cc > 0 ? -b - std::sqrt(disc) : -b + std::sqrt(disc);
    if (t <= 0) return std::nullopt;
    float u, v;
    sphereCoordinates(scene.spheres, 0, ref + w * t, u, v);
    return sphereSurfaceAt(scene.spheres, 0, scene.spherePrimitive(0), u, v);
  }
};

// The sampled directions follow the pdf pdfSolidAngle() states (chi-square over the sphere of
// directions), every sample states that same pdf, and pdfArea() is its area-measure form.
void expectSamplesFollowThePdf(const SphereLight& l) {
  LightSampler lights(l.scene);
  uint64_t mismatched = 0;
  auto sample = [&](uint64_t i, Vec3& w) {
    LightSample ls;
    if (!lights.sample(l.ref, testUniform(i, 0), testUniform(i, 1), testUniform(i, 2), ls)) return false;
    w = ls.direction;
    const std::optional<SurfacePoint> sp = l.hit(w);
    if (!sp || std::abs(ls.pdf / lights.pdfSolidAngle(*sp, l.ref) - 1) > 1e-3f ||
        std::abs(ls.pdfLight / lights.pdfArea(sp->primitive, l.ref, ls.position, ls.normal) - 1) > 1e-3f ||
        length(sp->position - ls.position) > 1e-4f * l.r)
      ++mismatched;
    return true;
  };
  auto pdf = [&](Vec3 w) {
    const std::optional<SurfacePoint> sp = l.hit(w);
    return sp ? lights.pdfSolidAngle(*sp, l.ref) : 0.0f;
  };
  const test::ChiSquareResult chi = test::chiSquareTest(sample, pdf, 40, 32, 400000, 48);  // fine: the cone edge cuts bins
  EXPECT_GT(chi.pValue, 1e-4) << chi.summary();
  EXPECT_LT(mismatched, 400000u / 2000u);  // silhouette grazing samples may round differently
}

TEST(ExactSphere, ConeSamplingFollowsItsPdf) {
  expectSamplesFollowThePdf(SphereLight(Vec3(0.2f, 0.3f, 1.0f), 0.8f, Vec3(0.0f), false));
}

TEST(ExactSphere, AreaSamplingFromInsideFollowsItsPdf) {
  expectSamplesFollowThePdf(SphereLight(Vec3(0.2f, 0.3f, 0.1f), 1.0f, Vec3(0.0f), true));
}

// Irradiance from a sphere of radiance Le that subtends a cone of half-angle theta at a
// point whose normal points at its centre: E = pi Le sin^2(theta). Solid-angle sampling and
// plain area sampling (done here by hand) both estimate it.
TEST(StatisticalExactSphere, ConeAndAreaSamplingAgreeWithTheClosedForm) {
  const Vec3 c(0.0f, 0.0f, 3.0f);
  const float r = 1.0f;
  SphereLight l(c, r, Vec3(0.0f), false);
  LightSampler lights(l.scene);
  const double exact = kPi * 1.0 * (r * r) / dot(c, c);  // green channel: Le = 1
  const int n = 200000;
  double cone = 0, cone2 = 0, area = 0, area2 = 0;
  for (int i = 0; i < n; ++i) {
    LightSample ls;
    double x = 0;
    if (lights.sample(l.ref, testUniform(i, 0), testUniform(i, 1), testUniform(i, 2), ls))
      x = ls.radiance.y * std::max(0.0f, ls.direction.z) / ls.pdf;
    cone += x;
    cone2 += x * x;
    // Area sampling: a uniform point on the whole sphere, counted where it faces the point.
    const Vec3 radial = squareToUniformSphere(testUniform(i, 3), testUniform(i, 4));
    const Vec3 d = c + radial * r;
    const float dist2 = dot(d, d);
    const Vec3 w = d / std::sqrt(dist2);
    const float cosL = -dot(radial, w);
    const double y = cosL > 0 ? 1.0 * w.z * cosL / dist2 * (4 * kPi * r * r) : 0.0;
    area += y;
    area2 += y * y;
  }
  const double coneMean = cone / n, areaMean = area / n;
  const double coneErr = std::sqrt((cone2 / n - coneMean * coneMean) / n);
  const double areaErr = std::sqrt((area2 / n - areaMean * areaMean) / n);
  EXPECT_NEAR(coneMean, exact, 4 * coneErr + 1e-6);
  EXPECT_NEAR(areaMean, exact, 4 * areaErr);
  EXPECT_LT(coneErr, 0.5 * areaErr);  // the point of sampling the cone
}

// A diffuse plane (albedo a) under a sphere light: at the point below the centre,
// L = a / pi * E = a Le sin^2(theta), for both the path tracer (next-event estimation
// MIS-weighted against BSDF samples that hit the sphere) and the direct integrator.
TEST(StatisticalExactSphere, SphereLightOverPlaneMatchesClosedForm) {
  TempDir dir;
  Scene scene = loadScene(dir.write("s.xml", R"(<scene version="3.0.0">
    <sensor type="perspective"><float name="fov" value="0.5"/>
      <transform name="to_world"><lookat origin="0,0,10" target="0,0,0" up="0,1,0"/></transform>
      <film type="hdrfilm"><integer name="width" value="8"/><integer name="height" value="8"/>
        <rfilter type="box"/></film></sensor>
    <shape type="rectangle"><transform name="to_world"><scale value="20"/></transform>
      <bsdf type="diffuse"><rgb name="reflectance" value="0.5"/></bsdf></shape>
    <shape type="sphere"><point name="center" value="1.5, 0, 2"/><float name="radius" value="1"/>
      <bsdf type="diffuse"><rgb name="reflectance" value="0"/></bsdf>
      <emitter type="area"><rgb name="radiance" value="4"/></emitter></shape>
  </scene>)"));
  // The camera looks at the origin; the centre is at (1.5, 0, 2): normal (0,0,1), cos = 2/2.5.
  // E = Le * pi * sin^2(theta) * cos(angle to the centre) for a sphere fully above the horizon.
  const double sin2 = 1.0 / (1.5 * 1.5 + 2 * 2), cosC = 2 / std::sqrt(1.5 * 1.5 + 2 * 2);
  const double expected = 0.5 / kPi * (4 * kPi * sin2 * cosC);
  for (const char* integrator : {"path", "direct"}) {
    RenderSettings s;
    s.integrator = integrator;
    s.spp = 4096;
    s.maxDepth = 2;
    s.seed = 11;
    RenderStats stats;
    const Color mean = test::meanOf(render(scene, s, stats));
    EXPECT_NEAR(mean.y, expected, 0.01 * expected) << integrator;
  }
}

// The default scene's glass and mirror spheres, exact and as 256 x 512 tessellations:
// independent renders of each, block by block (8x8 blocks of 64x64). Facets would show as
// bias in the caustic under the glass sphere and in the mirror's reflections.
TEST(StatisticalExactSphere, ExactAndTessellatedSpheresGiveTheSameImage) {
  const std::string file = test::sourceDir() + "/scenes/default/scene.xml";
  LoadOptions tessellate;
  tessellate.tessellateSpheres = true;
  const Scene exact = loadScene(file), mesh = loadScene(file, tessellate);
  ASSERT_EQ(exact.spheres.count(), 2u);
  ASSERT_EQ(mesh.spheres.count(), 0u);
  auto renders = [](const Scene& scene, uint64_t seed) {
    RenderSettings s;
    s.integrator = "path";
    s.width = s.height = 64;
    s.filterSet = true;
    s.filter = FilterKind::Box;
    s.spp = 256;
    s.tracer = std::make_shared<const Tracer>(scene);
    std::vector<RgbImage> images;
    for (int k = 0; k < 6; ++k) {
      s.seed = seed + uint64_t(k);
      RenderStats stats;
      images.push_back(render(scene, s, stats));
    }
    return images;
  };
  const test::BlockZScores z = test::blockZScores(renders(exact, 100), renders(mesh, 200), 8);
  std::printf("exact vs tessellated: %zu blocks: mean z^2 %.2f, worst |z| %.2f\n", z.z.size(), z.meanSquare, z.worst);
  EXPECT_EQ(z.z.size(), 64u);
  EXPECT_LT(z.meanSquare, 2.0);
  EXPECT_LT(z.worst, 4.5);
}

}  // namespace
}  // namespace erpt
