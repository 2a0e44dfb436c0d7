// Fuzz target: scenes that load are built and a few camera rays are traced. Parsing alone
// (scene_xml_fuzzer.cpp) did not find a camera matrix that loaded but produced non-finite
// rays, which aborted Debian's Embree on AVX-512 machines. Here the loader's promise is
// checked on every CPU: with the camera within 1e30 of the origin (beyond that single
// precision runs out in ordinary arithmetic), every camera ray is well formed, so the tracer
// refuses none of them; and whatever the rays, tracing them must not crash.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "models/camera.h"
#include "erpt/scene_loader.h"
#include "tracer/tracer.h"
#include "fuzz_input.h"

namespace {

void traceCameraRays(const erpt::Scene& scene) {
  const int width = 5, height = 3;  // not square, so the fov axis matters
  const erpt::Camera camera(scene.camera, width, height);
  erpt::RayQueue rays;
  erpt::HitQueue hits;
  const size_t n = size_t(width * height) * 2;
  erpt::prepareRays(rays, n);
  hits.resize(n);
  for (size_t i = 0; i < n; ++i) {
    // Pixel corners and centres: the film's edges are where the directions are largest.
    const float x = float(i % width) + (i < n / 2 ? 0.0f : 0.5f), y = float((i / width) % height);
    erpt::Camera::Ray r = camera.generateRay(x, y);
    if (camera.hasLens()) camera.throughLens(0.9f, 0.1f, r.origin, r.direction, r.tnear, r.tfar);
    erpt::setRay(rays, i, r.origin, r.direction, r.tnear, r.tfar);
  }
  const erpt::Tracer tracer(scene);
  tracer.intersect(rays, hits, {0, n}, erpt::RayCoherence::Coherent);
  const erpt::Vec3 p = camera.position();
  const bool ordinary = std::abs(p.x) < 1e30f && std::abs(p.y) < 1e30f && std::abs(p.z) < 1e30f &&
                        scene.camera.focusDistance < 1e30f;
  if (ordinary && tracer.refusedRays() > 0) {
    std::fprintf(stderr, "fuzz: the scene loaded but %llu of its camera rays were not well formed\n",
                 (unsigned long long)tracer.refusedRays());
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string path = erpt::fuzz::writeInput("scene.xml", data, size);
  erpt::fuzz::expectCleanFailure([&] { traceCameraRays(erpt::loadScene(path)); }, erpt::fuzz::Place::Line);
  return 0;
}
