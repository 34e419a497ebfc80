// The Lambertian BRDF.
#include "prt/brdf/lambert.h"

#include <cmath>

#include "brdf/lobe_mix.h"
#include "brdf/parameter_check.h"
#include "sh/constants.h"

namespace prt::brdf {

namespace {
using sh::kPi;
}

Result<Lambert> Lambert::create(const Rgb& reflectance) {
  Status s = detail::check_rgb("Lambert", "reflectance", reflectance);
  if (!s) return s;
  return Lambert(reflectance);
}

Rgb Lambert::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  return (1.0 / kPi) * rho_;
}

BrdfSample sample_by_cosine(const Brdf& f, const Vec3& wo, double u1, double u2) {
  if (wo.z <= 0.0) return {};
  BrdfSample s;
  s.wi = detail::sample_cosine_direction(u1, u2);
  s.pdf = numerics::cosine_hemisphere_pdf(s.wi.z);
  s.f = f.eval(s.wi, wo);
  return s;
}

double cosine_sampling_pdf(const Vec3& wo, const Vec3& wi) {
  if (wo.z <= 0.0 || wi.z <= 0.0) return 0.0;
  return wi.z / kPi;
}

BrdfSample Lambert::sample(const Vec3& wo, double u1, double u2) const {
  return sample_by_cosine(*this, wo, u1, u2);
}

double Lambert::pdf(const Vec3& wo, const Vec3& wi) const {
  return cosine_sampling_pdf(wo, wi);
}

}  // namespace prt::brdf
