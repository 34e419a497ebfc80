// bake/src/brdf_projection.cpp — see bake/brdf_projection.h.
#include "bake/brdf_projection.h"

#include <algorithm>
#include <cmath>

#include "bake/transfer_baker.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"

namespace prt::bake {
namespace {

// splitmix64 (Steele, Lea & Flood 2014) mapped to [0, 1) with 53 bits.
struct SplitMix {
  uint64_t state;
  double next() {
    uint64_t z = (state += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    return static_cast<double>(z >> 11) * 0x1p-53;
  }
};

// One node: b_c,i(wo) by importance sampling the BRDF with n × n jittered strata.
void project_node(const brdf::Brdf& f, const brdf::Vec3& wo, int order, int n, SplitMix& rng,
                  float* out) {
  const int K = order * order;
  std::vector<double> acc(3 * static_cast<std::size_t>(K), 0.0), y(static_cast<std::size_t>(K));
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) {
      const double u1 = (a + rng.next()) / n, u2 = (b + rng.next()) / n;
      const brdf::BrdfSample s = f.sample(wo, std::min(u1, 1.0 - 0x1p-53), std::min(u2, 1.0 - 0x1p-53));
      if (!(s.pdf > 0.0) || s.wi.z <= 0.0) continue;
      const double w = s.wi.z / s.pdf;
      sh::evaluate(order, s.wi.x, s.wi.y, s.wi.z, y.data());
      const double fc[3] = {s.f.r * w, s.f.g * w, s.f.b * w};
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < K; ++i) acc[c * K + i] += fc[c] * y[i];
    }
  }
  const double inv = 1.0 / (double(n) * n);
  for (int i = 0; i < 3 * K; ++i) out[i] = static_cast<float>(acc[i] * inv);
}

// θ of node j: (π/2) · j / (T − ½), from the normal (j = 0) to just above the horizon.
double node_theta(int j) { return 0.5 * sh::kPi * j / (BrdfProjection::kThetaNodes - 0.5); }

}  // namespace

BrdfProjection::BrdfProjection(const brdf::Material& material, int order, int samples,
                               uint64_t seed, const std::string& name)
    : order_(order), K_(order * order), lambertian_(material.lambertian()) {
  const std::size_t K = static_cast<std::size_t>(K_);
  if (lambertian_) {
    lambert_.assign(3 * K, 0.f);
    const double rho[3] = {material.diffuse.r, material.diffuse.g, material.diffuse.b};
    for (int l = 0; l < order; ++l) {
      const double z = sh::clamped_cosine_zonal_coefficient(l) / sh::kPi;
      for (int c = 0; c < 3; ++c)
        lambert_[c * K + static_cast<std::size_t>(sh::index(l, 0))] = static_cast<float>(rho[c] * z);
    }
    return;
  }
  auto made = brdf::make_brdf(material);
  if (!made.ok()) throw BakeError(name + ": " + made.status().message());
  const brdf::Brdf& f = *made.value();
  table_.assign(std::size_t(kThetaNodes) * kPhiNodes * 3 * K, 0.f);
  SplitMix rng{seed ^ 0x5bd1e995u};
  for (int j = 0; j < kThetaNodes; ++j) {
    const double cos_t = std::cos(node_theta(j));
    for (int k = 0; k < kPhiNodes; ++k) {
      const double phi = 2.0 * sh::kPi * (k + 0.5) / kPhiNodes;
      project_node(f, brdf::spherical_direction(cos_t, phi), order, samples, rng,
                   &table_[(std::size_t(j) * kPhiNodes + k) * 3 * K]);
    }
  }
}

void BrdfProjection::evaluate(const glm::vec3& wo, float* out) const {
  const std::size_t n = 3 * static_cast<std::size_t>(K_);
  if (!(wo.z > 0.f)) {
    std::fill(out, out + n, 0.f);
    return;
  }
  if (lambertian_) {
    std::copy(lambert_.begin(), lambert_.end(), out);
    return;
  }
  // Bilinear on (θ_o, φ_o): nodes at (π/2) · j/(T − ½) and 2π(k + ½)/P.
  const float theta = std::acos(std::min(wo.z, 1.f));
  const float ft = std::clamp(theta / static_cast<float>(0.5 * sh::kPi) * (kThetaNodes - 0.5f), 0.f,
                              float(kThetaNodes - 1));
  const int j0 = std::min(static_cast<int>(ft), kThetaNodes - 2);
  const float tt = ft - static_cast<float>(j0);
  float phi = std::atan2(wo.y, wo.x);
  if (phi < 0.f) phi += 2.f * static_cast<float>(sh::kPi);
  float fp = phi / (2.f * static_cast<float>(sh::kPi)) * kPhiNodes - 0.5f;
  if (fp < 0.f) fp += kPhiNodes;
  const int k0 = std::min(static_cast<int>(fp), kPhiNodes - 1);
  const float tp = fp - static_cast<float>(k0);
  const int k1 = (k0 + 1) % kPhiNodes;
  const float w00 = (1 - tt) * (1 - tp), w01 = (1 - tt) * tp, w10 = tt * (1 - tp), w11 = tt * tp;
  const float* a = &table_[(std::size_t(j0) * kPhiNodes + k0) * n];
  const float* b = &table_[(std::size_t(j0) * kPhiNodes + k1) * n];
  const float* c = &table_[(std::size_t(j0 + 1) * kPhiNodes + k0) * n];
  const float* d = &table_[(std::size_t(j0 + 1) * kPhiNodes + k1) * n];
  for (std::size_t i = 0; i < n; ++i) out[i] = w00 * a[i] + w01 * b[i] + w10 * c[i] + w11 * d[i];
}

}  // namespace prt::bake
