// prt/brdf/brdf.h — the common interface of prt's BRDFs: evaluate, importance-sample, pdf.
//
// Conventions shared by every model (each model's header adds its own):
// - Local shading frame (prt/brdf/vec3.h): +z the normal, +x the tangent (the direction of α_x
//   for anisotropic models), +y the bitangent. ωi points towards the light, ωo towards the
//   viewer, both away from the surface, both unit vectors.
// - f(ωi, ωo) is in 1/sr, per linear-RGB channel. The reflected radiance is
//   L_o(ωo) = ∫ f(ωi, ωo) L_i(ωi) cos θi dωi over the upper hemisphere.
// - Every model is ONE-SIDED: f = 0 when cos θi ≤ 0 or cos θo ≤ 0. A renderer that shades back
//   faces flips the frame first.
// - pdf(ωo, ωi) is a density in solid angle (1/sr) over the UPPER hemisphere of ωi (0 below
//   it). Samplers that reflect ωo about a sampled micro-normal m put part of their mass below
//   the horizon, and at grazing ωo may draw an m facing away from ωo (ωo·m ≤ 0, no reflected
//   direction at all). Such draws are DISCARDED: sample() returns pdf = 0 ("no sample"), which
//   an estimator Σ f cos θi / pdf over all draws counts as zero — still unbiased, since the
//   density of the kept samples is exactly pdf(). So ∫ pdf over the upper hemisphere is
//   1 − P(no sample), below 1 for those samplers (docs/BRDF.md tabulates the discarded
//   fraction); the tests check the sum. (Keeping below-horizon directions would make the
//   sphere integral 1 but give the pdf an integrable 1/|ωi + ωo| spike at ωi = −ωo, which
//   no quadrature in the tests, and no MIS weight, would handle well.)
//   When ωo is below the horizon, sample() returns pdf = 0 and pdf() returns 0.
// - sample() uses two uniform numbers in [0, 1); models with two lobes choose a lobe with u1
//   and rescale it, so a stratified (u1, u2) pattern stays stratified within each lobe.
// Creation never throws: each model has a static create() returning prt::Result, and refuses
// NaN, infinite or out-of-range parameters with a one-line message.
// Compiles as C++17.
#pragma once

#include <cstdint>

#include "prt/brdf/vec3.h"

namespace prt::brdf {

struct BrdfSample {
  Vec3 wi;         // the sampled incident direction, above the horizon when pdf > 0
  double pdf = 0;  // its density in solid angle; 0 means "no sample" (see above)
  Rgb f;           // f(wi, wo)
};

class Brdf {
 public:
  virtual ~Brdf() = default;
  // f(ωi, ωo) in 1/sr.
  virtual Rgb eval(const Vec3& wi, const Vec3& wo) const = 0;
  // A direction ωi drawn with density pdf(wo, ·), from uniform numbers u1, u2 in [0, 1).
  virtual BrdfSample sample(const Vec3& wo, double u1, double u2) const = 0;
  // The density of sample()'s ωi given ωo, in 1/sr over the sphere.
  virtual double pdf(const Vec3& wo, const Vec3& wi) const = 0;
  // Whether f(ωi, ωo) = f(ωo, ωi) holds (Helmholtz reciprocity).
  virtual bool reciprocal() const = 0;
};

// Directional albedo a(ωo) = ∫ f(ωi, ωo) cos θi dωi (per channel), estimated by importance
// sampling with n × n jittered strata (numerics::SplitMix64 stream from `seed`). Its standard error
// is returned in *standard_error (per-channel maximum) when that pointer is not null.
Rgb directional_albedo(const Brdf& brdf, const Vec3& wo, int n, uint64_t seed = 1,
                       double* standard_error = nullptr);

}  // namespace prt::brdf
