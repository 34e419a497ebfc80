// The normalised Blinn-Phong BRDF.
#include "prt/brdf/blinn_phong.h"

#include <cmath>

#include "brdf/lobe_mix.h"
#include "brdf/parameter_check.h"
#include "prt/brdf/lambert.h"
#include "sh/constants.h"

namespace prt::brdf {

namespace {
using sh::kPi;
}

Result<BlinnPhong> BlinnPhong::create(const Rgb& k_diffuse, const Rgb& k_glossy, double exponent) {
  Status s = detail::check_range("Blinn-Phong", "exponent", exponent, 0.0, 1e5);
  if (s) s = detail::check_rgb("Blinn-Phong", "k_L", k_diffuse);
  if (s) s = detail::check_rgb("Blinn-Phong", "k_G", k_glossy);
  if (s) s = detail::check_rgb("Blinn-Phong", "k_L + k_G", k_diffuse + k_glossy);
  if (!s) return s;
  return BlinnPhong(k_diffuse, k_glossy, exponent);
}

BlinnPhong::BlinnPhong(const Rgb& kd, const Rgb& kg, double s)
    : kd_(kd), kg_(kg), s_(s), p_diffuse_(detail::diffuse_probability(kd, kg)) {}

Rgb BlinnPhong::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const Vec3 h = normalize(wi + wo);
  const double lobe = (8.0 + s_) / (8.0 * kPi) * std::pow(std::fmax(0.0, h.z), s_);
  return (1.0 / kPi) * kd_ + lobe * kg_;
}

double BlinnPhong::glossy_pdf(const Vec3& wo, const Vec3& wi) const {
  if (wi.z <= 0.0) return 0.0;
  const Vec3 sum = wi + wo;
  if (dot(sum, sum) <= 1e-24) return 0.0;
  const Vec3 h = normalize(sum);
  const double oh = dot(wo, h);
  if (h.z <= 0.0 || oh <= 0.0) return 0.0;
  return (s_ + 1.0) / (2.0 * kPi) * std::pow(h.z, s_) / (4.0 * oh);
}

BrdfSample BlinnPhong::sample(const Vec3& wo, double u1, double u2) const {
  if (wo.z <= 0.0) return {};
  BrdfSample out;
  if (detail::pick_diffuse(p_diffuse_, u1)) {
    out.wi = detail::sample_cosine_direction(u1, u2);
  } else {
    const double cos_h = std::pow(1.0 - u1, 1.0 / (s_ + 1.0));  // 1 − u1 keeps cos_h > 0
    const Vec3 h = spherical_direction(cos_h, 2.0 * kPi * u2);
    if (dot(wo, h) <= 0.0) return {};
    out.wi = reflect(wo, h);
    if (out.wi.z <= 0.0) return {};  // below the horizon: discarded
  }
  out.pdf = pdf(wo, out.wi);
  out.f = eval(out.wi, wo);
  return out;
}

double BlinnPhong::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0) return 0.0;
  const double diffuse = wi.z > 0.0 ? wi.z / kPi : 0.0;
  return p_diffuse_ * diffuse + (1.0 - p_diffuse_) * glossy_pdf(wo, wi);
}

double blinn_phong_normal_albedo(double s) {
  const double a = 2.0 * (1.0 - std::pow(2.0, -(s + 4.0) / 2.0)) / (s + 4.0);
  const double b = (1.0 - std::pow(2.0, -(s + 2.0) / 2.0)) / (s + 2.0);
  return (8.0 + s) * (a - b);
}

}  // namespace prt::brdf
