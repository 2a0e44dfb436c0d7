// Fresnel equations and the Beckmann / GGX microfacet distributions (Walter et al. 2007).
#include <cmath>

#include "models/bsdf.h"

namespace erpt {

float fresnelDielectric(float cosThetaI, float eta, float* cosThetaT) {
  // eta = n_inside / n_outside; a negative cosine means the ray arrives from inside.
  float scale = cosThetaI > 0 ? 1.0f / eta : eta;
  float cosT2 = 1.0f - (1.0f - cosThetaI * cosThetaI) * scale * scale;
  if (cosT2 <= 0.0f) {  // total internal reflection
    if (cosThetaT) *cosThetaT = 0.0f;
    return 1.0f;
  }
  float ci = std::abs(cosThetaI), ct = std::sqrt(cosT2);
  float etaTI = cosThetaI > 0 ? eta : 1.0f / eta;
  float rs = (ci - etaTI * ct) / (ci + etaTI * ct);
  float rp = (etaTI * ci - ct) / (etaTI * ci + ct);
  if (cosThetaT) *cosThetaT = cosThetaI > 0 ? -ct : ct;
  return 0.5f * (rs * rs + rp * rp);
}

// Exact unpolarized reflectance of a conductor with complex IOR eta + i k, per channel.
Color fresnelConductor(float cosThetaI, Color eta, Color k) {
  Color out;
  float c = std::min(1.0f, std::abs(cosThetaI));
  float c2 = c * c, s2 = 1 - c2;
  for (int i = 0; i < 3; ++i) {
    float n = eta[i], kk = k[i];
    float temp1 = n * n - kk * kk - s2;
    float a2pb2 = std::sqrt(std::max(0.0f, temp1 * temp1 + 4 * kk * kk * n * n));
    float a = std::sqrt(std::max(0.0f, 0.5f * (a2pb2 + temp1)));
    float term1 = a2pb2 + c2, term2 = 2 * a * c;
    float rs = (term1 - term2) / (term1 + term2);
    float term3 = a2pb2 * c2 + s2 * s2, term4 = term2 * s2;
    float rp = rs * (term3 - term4) / (term3 + term4);
    out[i] = 0.5f * (rs + rp);
  }
  return out;
}

// Hemispherical average of the dielectric Fresnel reflectance, by numerical integration
// (used by plastic for light that is reflected back into the diffuse layer).
float diffuseFresnelReflectance(float eta) {
  const int n = 2048;
  double sum = 0;
  for (int i = 0; i < n; ++i) {
    double mu = (i + 0.5) / n;
    sum += fresnelDielectric(float(mu), eta) * 2.0 * mu;
  }
  return float(sum / n);
}

// Anisotropic forms (Walter et al. 2007, with the elliptical roughness of Heitz 2014): at an
// azimuth phi the roughness is alpha(phi) = sqrt(cos^2 phi ax^2 + sin^2 phi ay^2) for the
// projected slope (G1), and 1 / alpha(phi)^2 = cos^2 phi / ax^2 + sin^2 phi / ay^2 weights the
// squared slope in D. ax = ay gives the isotropic formulas.
namespace {
// tan^2(theta_m) / alpha^2 with the azimuth's elliptical alpha, from the direction's x, y, z.
float slope2OverAlpha2(Vec3 m, float ax, float ay) {
  return (m.x * m.x / (ax * ax) + m.y * m.y / (ay * ay)) / (m.z * m.z);
}
// alpha(phi)^2 tan^2(theta_v) of a direction v: the projected roughness times its slope.
float projectedAlpha2Tan2(Vec3 v, float ax, float ay) { return (v.x * v.x * ax * ax + v.y * v.y * ay * ay) / (v.z * v.z); }
}  // namespace

float microfacetD(MicrofacetKind kind, float ax, float ay, Vec3 m) {
  if (m.z <= 0) return 0.0f;
  const float cos2 = m.z * m.z;
  if (ax == ay) {  // isotropic: tan^2 from cos^2 alone
    const float tan2 = (1 - cos2) / cos2, a2 = ax * ax;
    if (kind == MicrofacetKind::Beckmann) return std::exp(-tan2 / a2) / (kPi * a2 * cos2 * cos2);
    const float d = a2 + tan2;
    return a2 / (kPi * cos2 * cos2 * d * d);
  }
  const float e = slope2OverAlpha2(m, ax, ay);
  if (kind == MicrofacetKind::Beckmann) return std::exp(-e) / (kPi * ax * ay * cos2 * cos2);
  const float d = 1 + e;
  return 1.0f / (kPi * ax * ay * cos2 * cos2 * d * d);
}

float microfacetG1(MicrofacetKind kind, float ax, float ay, Vec3 v, Vec3 m) {
  if (dot(v, m) * v.z <= 0) return 0.0f;
  const float cos2 = v.z * v.z;
  const float tan2 = std::max(0.0f, 1 - cos2) / cos2;
  if (tan2 == 0) return 1.0f;
  // alpha(phi_v): the roughness along v's azimuth.
  const float alpha = ax == ay ? ax : std::sqrt(projectedAlpha2Tan2(v, ax, ay) / tan2);
  if (kind == MicrofacetKind::GGX) return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
  float a = 1.0f / (alpha * std::sqrt(tan2));
  if (a >= 1.6f) return 1.0f;
  return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

// Samples m with density D(m) * cos(theta_m): the azimuth from the ellipse's distribution,
// tan^2(theta) from the slope distribution at that azimuth's alpha.
Vec3 microfacetSampleNormal(MicrofacetKind kind, float ax, float ay, float u1, float u2) {
  float phi = 2 * kPi * u2;
  if (ax != ay) {
    // tan(phi) = ay / ax tan(2 pi u2 + pi / 2); atan gives one half-circle, u2 > 0.5 the
    // other (a rotation of the mapping by pi, which leaves the density unchanged).
    phi = std::atan(ay / ax * std::tan(2 * kPi * u2 + 0.5f * kPi));
    if (u2 > 0.5f) phi += kPi;
  }
  const float cosPhi = std::cos(phi), sinPhi = std::sin(phi);
  const float alpha2 = ax == ay ? ax * ax : 1.0f / (cosPhi * cosPhi / (ax * ax) + sinPhi * sinPhi / (ay * ay));
  const float tan2 = kind == MicrofacetKind::Beckmann ? -alpha2 * std::log(1.0f - u1)
                                                      : alpha2 * u1 / std::max(1e-12f, 1.0f - u1);
  const float cosT = 1.0f / std::sqrt(1.0f + tan2), sinT = std::sqrt(std::max(0.0f, 1 - cosT * cosT));
  return {sinT * cosPhi, sinT * sinPhi, cosT};
}

float microfacetD(MicrofacetKind kind, float alpha, Vec3 m) { return microfacetD(kind, alpha, alpha, m); }
float microfacetG1(MicrofacetKind kind, float alpha, Vec3 v, Vec3 m) { return microfacetG1(kind, alpha, alpha, v, m); }
Vec3 microfacetSampleNormal(MicrofacetKind kind, float alpha, float u1, float u2) {
  return microfacetSampleNormal(kind, alpha, alpha, u1, u2);
}

}  // namespace erpt
