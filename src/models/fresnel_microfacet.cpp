// Fresnel equations and the Beckmann / GGX microfacet distributions (Walter et al. 2007).
#include <cmath>

#include "erpt/bsdf.h"

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

float microfacetD(MicrofacetKind kind, float alpha, Vec3 m) {
  if (m.z <= 0) return 0.0f;
  float cos2 = m.z * m.z, tan2 = (1 - cos2) / cos2, a2 = alpha * alpha;
  if (kind == MicrofacetKind::Beckmann) return std::exp(-tan2 / a2) / (kPi * a2 * cos2 * cos2);
  float d = a2 + tan2;
  return a2 / (kPi * cos2 * cos2 * d * d);
}

float microfacetG1(MicrofacetKind kind, float alpha, Vec3 v, Vec3 m) {
  if (dot(v, m) * v.z <= 0) return 0.0f;
  float cos2 = v.z * v.z;
  float tan2 = std::max(0.0f, 1 - cos2) / cos2;
  if (tan2 == 0) return 1.0f;
  if (kind == MicrofacetKind::GGX) return 2.0f / (1.0f + std::sqrt(1.0f + alpha * alpha * tan2));
  float a = 1.0f / (alpha * std::sqrt(tan2));
  if (a >= 1.6f) return 1.0f;
  return (3.535f * a + 2.181f * a * a) / (1.0f + 2.276f * a + 2.577f * a * a);
}

// Samples m with density D(m) * cos(theta_m).
Vec3 microfacetSampleNormal(MicrofacetKind kind, float alpha, float u1, float u2) {
  float tan2 = kind == MicrofacetKind::Beckmann ? -alpha * alpha * std::log(1.0f - u1)
                                                : alpha * alpha * u1 / std::max(1e-12f, 1.0f - u1);
  float cosT = 1.0f / std::sqrt(1.0f + tan2), sinT = std::sqrt(std::max(0.0f, 1 - cosT * cosT));
  float phi = 2 * kPi * u2;
  return {sinT * std::cos(phi), sinT * std::sin(phi), cosT};
}

}  // namespace erpt
