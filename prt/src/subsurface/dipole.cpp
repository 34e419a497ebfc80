// The dipole BSSRDF (prt/subsurface/dipole.h); derivations in docs/SUBSURFACE.md.
#include "prt/subsurface/dipole.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "prt/brdf/fresnel.h"

namespace prt::subsurface {
namespace {

constexpr const char* kChannel[3] = {"red", "green", "blue"};

SubsurfaceMaterial preset(const char* name, Rgb sigma_s_prime, Rgb sigma_a, Rgb listed) {
  SubsurfaceMaterial m;
  m.name = name;
  m.coefficients.sigma_a = sigma_a;
  m.coefficients.sigma_s_prime = sigma_s_prime;
  m.coefficients.eta = 1.3;
  m.listed_reflectance = listed;
  return m;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& ch : out) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return out;
}

std::string format_value(double v) {
  if (std::isnan(v)) return "NaN";
  std::string s = std::to_string(v);
  return s;
}

}  // namespace

const std::vector<SubsurfaceMaterial>& subsurface_presets() {
  // Jensen et al. 2001, Figure 5: σ_s′ [mm⁻¹], σ_a [mm⁻¹], diffuse reflectance R_d; η = 1.3.
  static const std::vector<SubsurfaceMaterial> table = {
      preset("apple", {2.29, 2.39, 1.97}, {0.0030, 0.0034, 0.046}, {0.85, 0.84, 0.53}),
      preset("chicken1", {0.15, 0.21, 0.38}, {0.015, 0.077, 0.19}, {0.31, 0.15, 0.10}),
      preset("chicken2", {0.19, 0.25, 0.32}, {0.018, 0.088, 0.20}, {0.32, 0.16, 0.10}),
      preset("cream", {7.38, 5.47, 3.15}, {0.0002, 0.0028, 0.0163}, {0.98, 0.90, 0.73}),
      preset("ketchup", {0.18, 0.07, 0.03}, {0.061, 0.97, 1.45}, {0.16, 0.01, 0.00}),
      preset("marble", {2.19, 2.62, 3.00}, {0.0021, 0.0041, 0.0071}, {0.83, 0.79, 0.75}),
      preset("potato", {0.68, 0.70, 0.55}, {0.0024, 0.0090, 0.12}, {0.77, 0.62, 0.21}),
      preset("skimmilk", {0.70, 1.22, 1.90}, {0.0014, 0.0025, 0.0142}, {0.81, 0.81, 0.69}),
      preset("skin1", {0.74, 0.88, 1.01}, {0.032, 0.17, 0.48}, {0.44, 0.22, 0.13}),
      preset("skin2", {1.09, 1.59, 1.79}, {0.013, 0.070, 0.145}, {0.63, 0.44, 0.34}),
      preset("wholemilk", {2.55, 3.21, 3.77}, {0.0011, 0.0024, 0.014}, {0.91, 0.88, 0.76}),
  };
  return table;
}

Result<SubsurfaceMaterial> find_subsurface_preset(std::string_view name) {
  const std::string key = lower(name);
  std::string known;
  for (const SubsurfaceMaterial& m : subsurface_presets()) {
    if (m.name == key) return m;
    known += known.empty() ? m.name : ", " + m.name;
  }
  return Status::Error("unknown subsurface preset '" + std::string(name) + "' (known: " + known +
                       ")");
}

Status validate(const DipoleCoefficients& c) {
  for (int ch = 0; ch < 3; ++ch) {
    const double a = c.sigma_a[ch], s = c.sigma_s_prime[ch];
    if (!std::isfinite(a) || a < 0)
      return Status::Error(std::string("sigma_a (") + kChannel[ch] +
                           ") must be finite and >= 0, got " + format_value(a));
    if (!std::isfinite(s) || s <= 0)
      return Status::Error(std::string("sigma_s' (") + kChannel[ch] +
                           ") must be finite and > 0, got " + format_value(s));
  }
  if (!std::isfinite(c.eta) || c.eta < 1)
    return Status::Error("eta must be finite and >= 1, got " + format_value(c.eta));
  return Status::Ok();
}

double fresnel_transmittance(double cos_theta, double eta) {
  return 1.0 - brdf::fresnel_dielectric(std::clamp(cos_theta, 0.0, 1.0), eta);
}

double diffuse_fresnel_transmittance(double eta) {
  // 2 ∫₀¹ (1 − F_r(μ)) μ dμ on panels graded toward μ = 0 and, for η < 1, split at the critical
  // cosine √(1 − η²), where total internal reflection starts (F_r's kink).
  std::vector<double> x, w;
  std::vector<double> edges = {0.0, 0.02, 0.1, 0.4, 1.0};
  if (eta < 1) {
    const double mu_c = std::sqrt(1.0 - eta * eta);
    edges = {0.0, mu_c, mu_c + 0.1 * (1 - mu_c), mu_c + 0.4 * (1 - mu_c), 1.0};
  }
  for (size_t p = 0; p + 1 < edges.size(); ++p)
    numerics::append_gauss_legendre(32, edges[p], edges[p + 1], &x, &w);
  double sum = 0;
  for (size_t i = 0; i < x.size(); ++i) sum += w[i] * fresnel_transmittance(x[i], eta) * x[i];
  return 2.0 * sum;
}

double diffuse_fresnel_reflectance_fit(double eta) {
  return -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
}

double boundary_factor(double eta) {
  const double f = diffuse_fresnel_reflectance_fit(eta);
  return (1 + f) / (1 - f);
}

double total_diffuse_reflectance(double alpha_prime, double boundary_a) {
  const double s = std::sqrt(3.0 * std::max(0.0, 1.0 - alpha_prime));
  return 0.5 * alpha_prime * (1.0 + std::exp(-(4.0 / 3.0) * boundary_a * s)) * std::exp(-s);
}

DipoleProfile::DipoleProfile(double sigma_a, double sigma_s_prime, double eta) {
  sigma_t_prime_ = sigma_a + sigma_s_prime;
  alpha_prime_ = sigma_s_prime / sigma_t_prime_;
  sigma_tr_ = std::sqrt(3.0 * sigma_a * sigma_t_prime_);
  a_ = boundary_factor(eta);
  z_r_ = 1.0 / sigma_t_prime_;
  z_v_ = z_r_ * (1.0 + 4.0 * a_ / 3.0);
}

double DipoleProfile::profile(double r) const {
  const double r2 = r * r;
  const double dr = std::sqrt(r2 + z_r_ * z_r_), dv = std::sqrt(r2 + z_v_ * z_v_);
  const double real = z_r_ * (sigma_tr_ * dr + 1.0) * std::exp(-sigma_tr_ * dr) / (dr * dr * dr);
  const double virt = z_v_ * (sigma_tr_ * dv + 1.0) * std::exp(-sigma_tr_ * dv) / (dv * dv * dv);
  return alpha_prime_ * numerics::kInvFourPi * (real + virt);
}

double DipoleProfile::total() const {
  return total_diffuse_reflectance(alpha_prime_, a_);
}

double DipoleProfile::tail(double r) const {
  const double dr = std::sqrt(r * r + z_r_ * z_r_), dv = std::sqrt(r * r + z_v_ * z_v_);
  return 0.5 * alpha_prime_ *
         (z_r_ * std::exp(-sigma_tr_ * dr) / dr + z_v_ * std::exp(-sigma_tr_ * dv) / dv);
}

double DipoleProfile::radius_for_tail(double fraction) const {
  const double target = fraction * total();
  double lo = 0, hi = z_v_;
  while (tail(hi) > target && hi < 1e300) hi *= 2;
  for (int i = 0; i < 200 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) > target ? lo : hi) = mid;
  }
  return hi;
}

Result<DipoleMaterial> make_dipole(const DipoleCoefficients& c) {
  if (Status s = validate(c); !s) return s;
  DipoleMaterial m;
  m.eta = c.eta;
  for (int ch = 0; ch < 3; ++ch)
    m.channels[ch] = DipoleProfile(c.sigma_a[ch], c.sigma_s_prime[ch], c.eta);
  return m;
}

Result<double> invert_total_reflectance(double reflectance, double eta) {
  if (!std::isfinite(reflectance) || reflectance <= 0 || reflectance >= 1)
    return Status::Error("diffuse reflectance must lie in (0, 1), got " +
                         format_value(reflectance));
  if (!std::isfinite(eta) || eta < 1)
    return Status::Error("eta must be finite and >= 1, got " + format_value(eta));
  const double a = boundary_factor(eta);
  // R_total(α′) rises monotonically from 0 at α′ = 0 to 1 at α′ = 1.
  double lo = 0, hi = 1;
  for (int i = 0; i < 200 && hi - lo > 1e-15; ++i) {
    const double mid = 0.5 * (lo + hi);
    (total_diffuse_reflectance(mid, a) < reflectance ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

Result<DipoleCoefficients> coefficients_from_color(const Rgb& diffuse_color,
                                                   const Rgb& mean_free_path, double eta) {
  DipoleCoefficients c;
  c.eta = eta;
  for (int ch = 0; ch < 3; ++ch) {
    const double l = mean_free_path[ch];
    if (!std::isfinite(l) || l <= 0)
      return Status::Error(std::string("mean free path (") + kChannel[ch] +
                           ") must be finite and > 0, got " + format_value(l));
    Result<double> alpha = invert_total_reflectance(diffuse_color[ch], eta);
    if (!alpha)
      return Status::Error(std::string(kChannel[ch]) + " channel: " + alpha.status().message());
    const double sigma_tr = 1.0 / l;
    const double sigma_t = sigma_tr / std::sqrt(3.0 * (1.0 - *alpha));
    c.sigma_s_prime[ch] = *alpha * sigma_t;
    c.sigma_a[ch] = sigma_t - c.sigma_s_prime[ch];
  }
  if (Status s = validate(c); !s) return s;
  return c;
}

DipoleCoefficients scale_coefficients(const DipoleCoefficients& c, double mm_per_unit) {
  DipoleCoefficients out = c;
  for (int ch = 0; ch < 3; ++ch) {
    out.sigma_a[ch] *= mm_per_unit;
    out.sigma_s_prime[ch] *= mm_per_unit;
  }
  return out;
}

}  // namespace prt::subsurface
