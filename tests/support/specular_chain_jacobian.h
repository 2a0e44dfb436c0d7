// An independent measurement of a specular chain's |d omega / dA|, for the manifold
// perturbation's tests: central differences of the map from the direction leaving a path's
// vertex b to the point where the ray, following the path's specular lobes through vertices
// b + 1 .. c - 1, lands on vertex c's surface. Traced with the scene's tracer one ray at a
// time; no manifold code is used.
#pragma once

#include <optional>

#include "support/erpt_world.h"

namespace erpt::test {

// |d omega_b / dA_c| of `path` (b non-specular, b + 1 .. c - 1 specular, c on a surface), with
// directions in the tangent plane of the path's direction leaving b and points in the tangent
// plane of c's geometric normal, by central differences of step h (radians); nullopt when a
// perturbed ray leaves the path's surfaces or lobes.
std::optional<double> solidAnglePerAreaByDifferences(const ErptWorld& w, const PathVertex* path, int b, int c, double h);

// The same with two steps that must agree within `agreement` (relative), else nullopt: a path
// near a silhouette or a facet edge is not smooth at this scale.
std::optional<double> stableSolidAnglePerArea(const ErptWorld& w, const PathVertex* path, int b, int c,
                                              double agreement = 0.01);

}  // namespace erpt::test
