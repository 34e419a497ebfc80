// prt/brdf/blinn_phong.h — the normalised Blinn-Phong BRDF.
//
//   f(ωi, ωo) = k_L/π + k_G (8 + s)/(8π) (h·n)^s,   h = normalize(ωi + ωo)
// k_L (diffuse) and k_G (glossy) are linear-RGB weights, each channel in [0, 1] with
// k_L + k_G ≤ 1; s ≥ 0 is the exponent (at most 1e5). Frame and conventions: prt/brdf/brdf.h.
// (8 + s)/(8π) is the usual approximate normalisation [35]: the glossy lobe's cosine-weighted
// integral at normal incidence is (8 + s)·[2(1 − 2^−(s+4)/2)/(s + 4) − (1 − 2^−(s+2)/2)/(s + 2)],
// exactly 1 at s = 0 and as s → ∞ but up to about 1.08 between (docs/BRDF.md tabulates it), and
// the model has no shadowing, so its albedo can exceed k_L + k_G. Reciprocal.
// Sampling: the diffuse lobe is cosine-weighted; the glossy lobe draws h with density
// (s + 1)/(2π) (h·n)^s and reflects ωo about it (pdf(ωi) = that density / (4 ωo·h)); draws that
// land below the horizon or meet a back-facing h are discarded (brdf.h). The lobe is chosen by the
// channel means of k_L and k_G. Compiles as C++17. References: [35] of docs/REFERENCES.md.
#pragma once

#include "prt/brdf/brdf.h"
#include "prt/core/status.h"

namespace prt::brdf {

class BlinnPhong final : public Brdf {
 public:
  static Result<BlinnPhong> create(const Rgb& k_diffuse, const Rgb& k_glossy, double exponent);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override;
  double pdf(const Vec3& wo, const Vec3& wi) const override;
  bool reciprocal() const override { return true; }

  double exponent() const { return s_; }

 private:
  BlinnPhong(const Rgb& kd, const Rgb& kg, double s);
  double glossy_pdf(const Vec3& wo, const Vec3& wi) const;
  Rgb kd_, kg_;
  double s_;
  double p_diffuse_;
};

// The closed form above: the glossy lobe's (k_G = 1) directional albedo at normal incidence.
double blinn_phong_normal_albedo(double exponent);

}  // namespace prt::brdf
