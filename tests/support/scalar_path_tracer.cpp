#include "support/scalar_path_tracer.h"

#include <embree3/rtcore.h>

#include <random>

#include "models/bsdf.h"
#include "models/camera.h"
#include "models/surface.h"

namespace erpt::test {

namespace {

RTCScene buildScene(RTCDevice device, const Scene& s) {
  const TriangleSoup& mesh = s.mesh;
  RTCScene scene = rtcNewScene(device);
  if (s.spheres.count() > 0) {  // geometry 0; the triangles are geometry 1
    RTCGeometry spheres = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_SPHERE_POINT);
    auto* p = static_cast<float*>(
        rtcSetNewGeometryBuffer(spheres, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 16, s.spheres.count()));
    for (uint32_t i = 0; i < s.spheres.count(); ++i) {
      const Vec3 c = s.spheres.center(i);
      p[4 * i] = c.x;
      p[4 * i + 1] = c.y;
      p[4 * i + 2] = c.z;
      p[4 * i + 3] = s.spheres.radius[i];
    }
    rtcCommitGeometry(spheres);
    rtcAttachGeometry(scene, spheres);
    rtcReleaseGeometry(spheres);
  }
  RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 16, mesh.vertexCount()));
  for (size_t i = 0; i < mesh.vertexCount(); ++i) {
    v[4 * i] = mesh.px[i];
    v[4 * i + 1] = mesh.py[i];
    v[4 * i + 2] = mesh.pz[i];
    v[4 * i + 3] = 0;
  }
  auto* idx = static_cast<unsigned*>(
      rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, mesh.triangleCount()));
  for (size_t t = 0; t < mesh.triangleCount(); ++t) {
    idx[3 * t] = mesh.v0[t];
    idx[3 * t + 1] = mesh.v1[t];
    idx[3 * t + 2] = mesh.v2[t];
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(scene);
  return scene;
}

}  // namespace

RgbImage scalarPathTrace(const Scene& scene, int width, int height, int spp, int maxDepth, uint64_t seed,
                         RgbImage* varianceOfMean) {
  RTCDevice device = rtcNewDevice(nullptr);
  RTCScene rtc = buildScene(device, scene);
  Camera camera(scene.camera, width, height);
  const Emitter* env = scene.environment();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> uni(0.0f, 1.0f);
  RgbImage img, var;
  img.width = var.width = width;
  img.height = var.height = height;
  img.pixels.resize(size_t(width) * height);
  var.pixels.resize(img.pixels.size());
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Color sum(0.0f), sumSq(0.0f);
      for (int s = 0; s < spp; ++s) {
        Camera::Ray cr = camera.generateRay(x + uni(rng), y + uni(rng));
        Vec3 org = cr.origin, dir = cr.direction;
        float tnear = cr.tnear;
        Color throughput(1.0f), radiance(0.0f);
        float etaSquared = 1;
        for (int depth = 1;; ++depth) {
          RTCIntersectContext ctx;
          rtcInitIntersectContext(&ctx);
          RTCRayHit rh{};
          rh.ray.org_x = org.x;
          rh.ray.org_y = org.y;
          rh.ray.org_z = org.z;
          rh.ray.dir_x = dir.x;
          rh.ray.dir_y = dir.y;
          rh.ray.dir_z = dir.z;
          rh.ray.tnear = tnear;
          rh.ray.tfar = std::numeric_limits<float>::infinity();
          rh.ray.mask = 0xffffffffu;
          rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
          rtcIntersect1(rtc, &ctx, &rh);
          if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
            if (env) radiance += throughput * env->environmentRadiance(dir);
            break;
          }
          SurfacePoint sp;
          if (scene.spheres.count() > 0 && rh.hit.geomID == 0) {
            float u, v;
            const float t = refineSphereHit(scene.spheres, rh.hit.primID, org, dir, rh.ray.tfar);
            sphereCoordinates(scene.spheres, rh.hit.primID, org + dir * t, u, v);
            sp = sphereSurfaceAt(scene.spheres, rh.hit.primID, scene.spherePrimitive(rh.hit.primID), u, v);
          } else {
            sp = triangleSurfaceAt(scene.mesh, rh.hit.primID, rh.hit.u, rh.hit.v);
          }
          int e = sp.emitter;
          if (e >= 0 && dot(sp.geometricNormal, dir) < 0) radiance += throughput * scene.emitters[e].radiance;
          if (maxDepth >= 0 && depth >= maxDepth) break;
          const Material& m = scene.materials[sp.material];
          BsdfSample bs;
          if (!bsdfSample(m, scene.surfaceColors(sp.material, sp.u, sp.v), sp.shading.toLocal(-dir), uni(rng), uni(rng),
                          uni(rng), bs))
            break;
          throughput *= bs.weight;
          etaSquared *= bs.eta * bs.eta;
          if (depth >= 5) {  // roulette on the largest throughput component, boosted by eta^2 as Mitsuba's
            float q = std::min(0.95f, maxComponent(throughput) * etaSquared);
            if (uni(rng) >= q) break;
            throughput = throughput / q;
          }
          dir = sp.shading.toWorld(bs.wo);
          org = offsetOrigin(sp.position, sp.geometricNormal, dir);
          tnear = 0;
        }
        sum += radiance;
        sumSq += radiance * radiance;
      }
      Color mean = sum / float(spp);
      img.at(x, y) = mean;
      var.at(x, y) = (sumSq / float(spp) - mean * mean) / float(std::max(1, spp - 1));
    }
  rtcReleaseScene(rtc);
  rtcReleaseDevice(device);
  if (varianceOfMean) *varianceOfMean = var;
  return img;
}

}  // namespace erpt::test
