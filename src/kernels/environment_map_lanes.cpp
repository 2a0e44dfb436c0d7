// The lanes' versions of environment_map.cpp's pickInterval, tentOffset, uvToDirection,
// directionToUv and the bilinear lookup, in the same order of operations.
#include "kernels/environment_map_lanes.h"

#include "kernels/lane_gather.h"

namespace erpt {

namespace {

using namespace lanes3;
using imask = indices::batch_bool_type;

V3 rowTimes(const Vec3 rows[3], const V3& v) {
  auto row = [&](const Vec3& r) { return batch(r.x) * v.x + batch(r.y) * v.y + batch(r.z) * v.z; };
  return {row(rows[0]), row(rows[1]), row(rows[2])};
}

// pickInterval: the interval of a CDF (n + 1 entries from cdf + base, per lane) that holds u,
// searched between the entries its guide bucket names, and u's position within it.
indices pickInterval(const float* cdf, const indices& base, int n, const uint32_t* guide, const indices& guideBase,
                     int buckets, const batch& u, batch& within) {
  const auto* guideEntries = reinterpret_cast<const int32_t*>(guide);
  const indices bucket = xsimd::min(indices(buckets - 1), xsimd::batch_cast<int32_t>(u * float(buckets)));
  const indices lo = gatherLanes(guideEntries, guideBase + bucket);
  const indices hi = gatherLanes(guideEntries, guideBase + bucket + 1);
  // upperBoundIndex(cdf + lo, hi - lo, u): every lane halves its own range until one entry is
  // left; lanes that are done keep their place.
  indices low = lo, count = hi - lo;
  for (imask more = count > indices(1); xsimd::any(more); more = count > indices(1)) {
    const indices half = count >> 1;
    const indices probe = xsimd::select(more, low + half - 1, low);
    const imask below = xsimd::bool_cast(gatherLanes(cdf, base + probe) <= u) & more;
    low = xsimd::select(below, low + half, low);
    count = xsimd::select(more, count - half, count);
  }
  const imask past = (count > indices(0)) & xsimd::bool_cast(gatherLanes(cdf, base + low) <= u);
  indices i = xsimd::select(past, low + 1, low);
  i = xsimd::min(indices(n - 1), xsimd::max(i - 1, indices(0)));
  // Past empty intervals, as the scalar search skips them.
  for (;;) {
    const imask empty = (i + 1 < indices(n)) &
                        xsimd::bool_cast(~(gatherLanes(cdf, base + i + 1) > gatherLanes(cdf, base + i)));
    if (!xsimd::any(empty)) break;
    i = xsimd::select(empty, i + 1, i);
  }
  const batch start = gatherLanes(cdf, base + i), width = gatherLanes(cdf, base + i + 1) - start;
  within = xsimd::select(width > batch(0.0f),
                         xsimd::min(xsimd::max((u - start) / width, batch(0.0f)), batch(0x1.fffffep-1f)), batch(0.5f));
  return i;
}

batch tentOffset(const batch& u) {
  return xsimd::select(u < batch(0.5f), xsimd::sqrt(2.0f * u) - 1.0f, 1.0f - xsimd::sqrt(2.0f - 2.0f * u));
}

// The map's bilinear interpolant of per-pixel values at uv (columns wrap, rows clamp).
struct LaneBilinear {
  indices i00, i10, i01, i11;  // pixel indices: (x0, y0), (x1, y0), (x0, y1), (x1, y1)
  batch tx, ty;
  batch of(const float* values, int stride, int component) const {
    auto at = [&](const indices& i) { return gatherLanes(values, i * stride + component); };
    return (at(i00) * (1.0f - tx) + at(i10) * tx) * (1.0f - ty) + (at(i01) * (1.0f - tx) + at(i11) * tx) * ty;
  }
};

LaneBilinear bilinearAt(const EnvironmentMap::Tables& map, const batch& u, const batch& v) {
  const batch x = u * float(map.width) - 0.5f, y = v * float(map.height) - 0.5f;
  const batch fx = xsimd::floor(x), fy = xsimd::floor(y);
  LaneBilinear b;
  b.tx = x - fx, b.ty = y - fy;
  // A NaN converts to the most negative integer, which the wrap and the clamps keep in range.
  const indices ix = xsimd::batch_cast<int32_t>(fx), iy = xsimd::batch_cast<int32_t>(fy);
  const indices width(map.width), last(map.height - 1);
  const indices x0 = xsimd::select(ix < indices(0), width - 1, xsimd::min(ix, width - 1));
  const indices x1 = xsimd::select(x0 + 1 == width, indices(0), x0 + 1);
  const indices y0 = xsimd::min(xsimd::max(iy, indices(0)), last) * width;
  const indices y1 = xsimd::min(xsimd::max(iy + 1, indices(0)), last) * width;
  b.i00 = y0 + x0, b.i10 = y0 + x1, b.i01 = y1 + x0, b.i11 = y1 + x1;
  return b;
}

}  // namespace

V3 environmentEvalAndPdfLanes(const EnvironmentMap::Tables& map, const V3& direction, batch& pdf) {
  // directionToUv
  V3 d = rowTimes(map.toLocal, direction);
  d = d / xsimd::sqrt(dot(d, d));
  batch u = xsimd::atan2(d.x, -d.z) * (0.5f * kInvPi);
  // At the poles xsimd's atan2(0, 0) is NaN where std::atan2's is 0 or pi by the zeros' signs.
  u = xsimd::select(xsimd::isnan(u), xsimd::select(xsimd::copysign(batch(1.0f), -d.z) < batch(0.0f), batch(0.5f), batch(0.0f)), u);
  u -= xsimd::floor(u);
  u = xsimd::select(u >= batch(1.0f), batch(0.0f), u);
  const batch y = xsimd::min(xsimd::max(d.y, batch(-1.0f)), batch(1.0f));
  const batch v = xsimd::acos(y) * kInvPi;
  const batch sinTheta = xsimd::sqrt(xsimd::max(batch(0.0f), 1.0f - y * y));
  const LaneBilinear b = bilinearAt(map, u, v);
  pdf = xsimd::select(sinTheta > batch(0.0f), b.of(map.weight, 1, 0) / sinTheta, batch(0.0f));
  return {b.of(map.radiance, 3, 0), b.of(map.radiance, 3, 1), b.of(map.radiance, 3, 2)};
}

LaneEnvironmentSample sampleEnvironmentLanes(const EnvironmentMap::Tables& map, const batch& u1, const batch& u2) {
  batch withinRow, withinColumn;
  const indices row = pickInterval(map.rowCdf, indices(0), map.height, map.rowGuide, indices(0), map.rowBuckets, u2,
                                   withinRow);
  const indices column = pickInterval(map.columnCdf, row * (map.width + 1), map.width, map.columnGuide,
                                      row * (map.columnBuckets + 1), map.columnBuckets, u1, withinColumn);
  const batch width(float(map.width)), height(float(map.height));
  batch x = xsimd::batch_cast<float>(column) + 0.5f + tentOffset(withinColumn);
  batch y = xsimd::batch_cast<float>(row) + 0.5f + tentOffset(withinRow);
  x = xsimd::select(x < batch(0.0f), x + width, x);
  x = xsimd::select(x >= width, x - width, x);
  y = xsimd::select(y < batch(0.0f), -y, y);
  y = xsimd::select(y > height, 2.0f * height - y, y);
  // uvToDirection
  const batch u = xsimd::min(x / width, batch(0x1.fffffep-1f)), v = xsimd::min(y / height, batch(1.0f));
  const auto phi = xsimd::sincos(batch(2 * kPi) * u), theta = xsimd::sincos(batch(kPi) * v);
  LaneEnvironmentSample s;
  s.direction = rowTimes(map.toWorld, {theta.first * phi.first, theta.second, -theta.first * phi.second});
  // From the direction, as sample() does.
  s.radiance = environmentEvalAndPdfLanes(map, s.direction, s.pdf);
  s.ok = s.pdf > batch(0.0f);
  return s;
}

}  // namespace erpt
