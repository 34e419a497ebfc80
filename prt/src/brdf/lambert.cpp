// The Lambertian BRDF.
#include "prt/brdf/lambert.h"

#include <cmath>

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

Vec3 sample_cosine_hemisphere(double u1, double u2) {
  const double r = std::sqrt(u1);
  const double phi = 2.0 * kPi * u2;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::fmax(0.0, 1.0 - u1))};
}

BrdfSample sample_by_cosine(const Brdf& f, const Vec3& wo, double u1, double u2) {
  if (wo.z <= 0.0) return {};
  BrdfSample s;
  s.wi = sample_cosine_hemisphere(u1, u2);
  s.pdf = s.wi.z / kPi;
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
