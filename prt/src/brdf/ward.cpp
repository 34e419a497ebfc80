// Ward's anisotropic BRDF.
#include "prt/brdf/ward.h"

#include <cmath>

#include "brdf/lobe_mix.h"
#include "brdf/parameter_check.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/microfacet.h"
#include "sh/constants.h"

namespace prt::brdf {

namespace {
using sh::kPi;
}

Result<Ward> Ward::create(const WardParams& p) {
  Status s = detail::check_roughness("Ward", "alpha_x", p.alpha_x);
  if (s) s = detail::check_roughness("Ward", "alpha_y", p.alpha_y);
  if (s) s = detail::check_rgb("Ward", "rho_d", p.rho_d);
  if (s) s = detail::check_rgb("Ward", "rho_s", p.rho_s);
  if (s) s = detail::check_rgb("Ward", "rho_d + rho_s", p.rho_d + p.rho_s);
  if (s && p.form != WardForm::kOriginal && p.form != WardForm::kDuer &&
      p.form != WardForm::kNormalized) {
    s = Status::Error("Ward: unknown form");
  }
  if (!s) return s;
  return Ward(p);
}

Ward::Ward(const WardParams& p)
    : params_(p),
      beckmann_{NormalDistribution::kBeckmann, p.alpha_x, p.alpha_y},
      p_diffuse_(detail::diffuse_probability(p.rho_d, p.rho_s)) {}

Rgb Ward::eval(const Vec3& wi, const Vec3& wo) const {
  if (wi.z <= 0.0 || wo.z <= 0.0) return {};
  const Vec3 h = wi + wo;
  const double ex = h.x / params_.alpha_x, ey = h.y / params_.alpha_y;
  const double e = (ex * ex + ey * ey) / (h.z * h.z);
  const double axy = params_.alpha_x * params_.alpha_y;
  double spec;
  if (params_.form == WardForm::kOriginal) {
    spec = std::exp(-e) / (4.0 * kPi * axy * std::sqrt(wi.z * wo.z));
  } else if (params_.form == WardForm::kDuer) {
    spec = std::exp(-e) / (4.0 * kPi * axy * wi.z * wo.z);
  } else {
    const double hz2 = h.z * h.z;
    spec = std::exp(-e) * dot(h, h) / (kPi * axy * hz2 * hz2);
  }
  return (1.0 / kPi) * params_.rho_d + spec * params_.rho_s;
}

BrdfSample Ward::sample(const Vec3& wo, double u1, double u2) const {
  if (wo.z <= 0.0) return {};
  BrdfSample out;
  if (detail::pick_diffuse(p_diffuse_, u1)) {
    out.wi = detail::sample_cosine_direction(u1, u2);
  } else {
    const Vec3 m = beckmann_.sample_normal(u1, u2);
    if (dot(wo, m) <= 0.0) return {};
    out.wi = reflect(wo, m);
    if (out.wi.z <= 0.0) return {};  // below the horizon: discarded
  }
  out.pdf = pdf(wo, out.wi);
  out.f = eval(out.wi, wo);
  return out;
}

double Ward::pdf(const Vec3& wo, const Vec3& wi) const {
  if (wo.z <= 0.0) return 0.0;
  const double diffuse = wi.z > 0.0 ? wi.z / kPi : 0.0;
  return p_diffuse_ * diffuse + (1.0 - p_diffuse_) * reflected_normal_pdf(beckmann_, wo, wi);
}

}  // namespace prt::brdf
