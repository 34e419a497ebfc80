// prt/brdf/microfacet_distribution.h — GGX and Beckmann normal distributions with Smith
// masking, isotropic and anisotropic.
//
// Local frame: prt/brdf/brdf.h (+z normal, +x tangent, +y bitangent). α_x and α_y are the
// roughnesses along the tangent and bitangent (α_x = α_y: isotropic). With
// e(m) = (m_x/α_x)² + (m_y/α_y)² for a micro-normal m:
//   Beckmann [29]:  D(m) = exp(−e(m)/m_z²) / (π α_x α_y m_z⁴)
//   GGX [30, 32]:   D(m) = 1 / (π α_x α_y (e(m) + m_z²)²)
// both 0 for m_z ≤ 0, normalised so that ∫ D(m) (m·n) dm = 1 over the hemisphere.
// Smith's Λ for a direction ω, with a² = (α_x² ω_x² + α_y² ω_y²) / ω_z² [31]:
//   GGX:      Λ = (−1 + √(1 + a²)) / 2
//   Beckmann: Λ = (erf(ν) − 1)/2 + exp(−ν²)/(2ν√π),  ν = 1/a
// G1(ω) = 1/(1 + Λ(ω)) and the height-correlated masking-shadowing
// G2(ωi, ωo) = 1/(1 + Λ(ωi) + Λ(ωo)) [31]. Both satisfy the projected-area identity
// ∫ D(m) max(0, ω·m) dm = ω_z (1 + Λ(ω)), which the tests check by quadrature.
// sample_normal() draws m with density D(m) m_z in solid angle (the classic "sample D cos"
// scheme [30]). sample_visible_normal() (GGX only) draws from the distribution of normals
// visible from ωo, D_ωo(m) = G1(ωo) max(0, ωo·m) D(m) / ωo_z, by Heitz's 2018 method [42]:
// never a back-facing m, and reflecting ωo about it gives ωi the bounded density
// G1(ωo) D(h) / (4 ωo_z).
// Compiles as C++17.
// References: [29], [30], [31], [32], [42] of docs/REFERENCES.md.
#pragma once

#include "prt/brdf/vec3.h"

namespace prt::brdf {

enum class NormalDistribution { kGgx, kBeckmann };

// Returns "ggx" or "beckmann".
const char* distribution_name(NormalDistribution d);

struct MicrofacetDistribution {
  NormalDistribution type = NormalDistribution::kGgx;
  double alpha_x = 0.5;
  double alpha_y = 0.5;

  double d(const Vec3& m) const;
  double lambda(const Vec3& w) const;
  double g1(const Vec3& w) const { return 1.0 / (1.0 + lambda(w)); }
  double g2(const Vec3& wi, const Vec3& wo) const { return 1.0 / (1.0 + lambda(wi) + lambda(wo)); }
  // A micro-normal with density D(m) m_z over the upper hemisphere; u1, u2 in [0, 1).
  Vec3 sample_normal(double u1, double u2) const;
  // GGX only: a micro-normal with density D_ωo(m) (above); wo must be above the horizon.
  Vec3 sample_visible_normal(const Vec3& wo, double u1, double u2) const;
};

}  // namespace prt::brdf
