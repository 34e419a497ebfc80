// prt/brdf/lambert.h — the Lambertian (ideal diffuse) BRDF: f = ρ/π.
//
// Frame and conventions: prt/brdf/brdf.h. ρ is the linear-RGB reflectance, each channel in
// [0, 1]; the directional albedo is exactly ρ for every ωo above the horizon. Sampling is
// cosine-weighted over the upper hemisphere (pdf = cos θi / π), so no sample goes below the
// horizon and f cos θi / pdf = ρ exactly. Reciprocal. Compiles as C++17.
#pragma once

#include "prt/brdf/brdf.h"
#include "prt/core/status.h"

namespace prt::brdf {

class Lambert final : public Brdf {
 public:
  // Refuses a channel that is NaN, negative or above 1.
  static Result<Lambert> create(const Rgb& reflectance);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override;
  double pdf(const Vec3& wo, const Vec3& wi) const override;
  bool reciprocal() const override { return true; }

  const Rgb& reflectance() const { return rho_; }

 private:
  explicit Lambert(const Rgb& rho) : rho_(rho) {}
  Rgb rho_;
};

// Sampling of `f` by the cosine alone (Lambert, and MERL, whose measured lobe is not sampled):
// wi cosine-weighted (numerics::sample_cosine_hemisphere, Malley's method on the concentric
// disc), pdf = cos θi / π, f = f.eval(wi, wo); an empty
// sample (pdf 0) for wo at or below the horizon.
BrdfSample sample_by_cosine(const Brdf& f, const Vec3& wo, double u1, double u2);
// The pdf of sample_by_cosine: cos θi / π, 0 when wo or wi is at or below the horizon.
double cosine_sampling_pdf(const Vec3& wo, const Vec3& wi);

}  // namespace prt::brdf
