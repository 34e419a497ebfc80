// prt/subsurface/dipole.h — the dipole diffusion BSSRDF of Jensen, Marschner, Levoy & Hanrahan
// 2001: per-channel coefficients, the radial profile R_d(r), its closed-form total diffuse
// reflectance, the inversion from a diffuse colour and a mean free path, and the paper's
// measured materials as named presets.
//
// Units: σ_a and σ_s′ in inverse length (the presets in mm⁻¹), r and lengths in the same unit.
// Per colour channel c (3 channels, linear RGB):
//   σ_t′ = σ_a + σ_s′ (reduced extinction),  α′ = σ_s′/σ_t′ (reduced albedo),
//   σ_tr = √(3 σ_a σ_t′) (effective transport coefficient),
//   F_dr(η) = −1.440/η² + 0.710/η + 0.668 + 0.0636 η (the paper's polynomial fit of the
//   diffuse Fresnel reflectance), A = (1 + F_dr)/(1 − F_dr),
//   z_r = 1/σ_t′ (real source depth), z_v = z_r (1 + 4A/3) (virtual source height),
//   d_r = √(r² + z_r²), d_v = √(r² + z_v²),
//   R_d(r) = α′/(4π) [ z_r (σ_tr d_r + 1) e^{−σ_tr d_r}/d_r³ + z_v (σ_tr d_v + 1) e^{−σ_tr
//   d_v}/d_v³ ] R_total(α′, A) = ∫_plane R_d dA = (α′/2)(1 + e^{−(4/3) A √(3(1−α′))})
//   e^{−√(3(1−α′))}.
// η is the relative index of refraction (material over outside, ≥ 1; the paper uses 1.3).
// σ_a = 0 is accepted (the non-absorbing limit: σ_tr = 0, R_total = 1); σ_s′ must be > 0.
// The single-scattering term of the paper is NOT implemented: its angular dependence cannot be
// held by a view-independent diffuse transfer vector (docs/SUBSURFACE.md).
// Fresnel: the exact dielectric reflectance of prt/brdf/fresnel.h; fresnel_transmittance is
// 1 − F_r(cos θ, η) for light crossing the boundary from outside, and
// diffuse_fresnel_transmittance(η) its cosine-weighted hemispherical mean
// T(η) = 2 ∫₀¹ (1 − F_r(μ, η)) μ dμ (computed by Gauss–Legendre quadrature, not by the fit).
// From outside (η ≥ 1) T is close to 1 (0.939 at η = 1.3); from inside, 1 − T(1/η) is the diffuse
// internal reflectance that the fit F_dr(η) approximates (0.441 at η = 1.3, fit 0.445).
// T(1/η) = T(η)/η² (reciprocity of radiance across the boundary). Any η > 0 is accepted.
// Runtime layer: standard library only, no threads, no exceptions; errors are prt::Status.
// References: Jensen, Marschner, Levoy & Hanrahan, "A Practical Model for Subsurface Light
// Transport", SIGGRAPH 2001 (eqs. 5, 6, 10 and Figure 5); docs/SUBSURFACE.md.
#pragma once

#include <array>
#include <string>
#include <string_view>
#include <vector>

#include "prt/core/status.h"

namespace prt::subsurface {

using Rgb = std::array<double, 3>;

// The optical coefficients of one homogeneous translucent material.
struct DipoleCoefficients {
  Rgb sigma_a{};        // absorption, per unit length, ≥ 0
  Rgb sigma_s_prime{};  // reduced scattering σ_s′ = σ_s (1 − g), per unit length, > 0
  double eta = 1.3;     // relative index of refraction, ≥ 1
};

// A named material: coefficients in mm⁻¹ and the diffuse reflectance the source table lists.
struct SubsurfaceMaterial {
  std::string name;
  DipoleCoefficients coefficients;
  Rgb listed_reflectance{};  // the "diffuse reflectance R_d" column of the paper's Figure 5
};

// The paper's measured materials (Figure 5, η = 1.3 for all), by lower-case name: apple,
// chicken1, chicken2, cream, ketchup, marble, potato, skimmilk, skin1, skin2, wholemilk.
const std::vector<SubsurfaceMaterial>& subsurface_presets();
// The preset of that name (case-insensitive); an error naming the known presets otherwise.
Result<SubsurfaceMaterial> find_subsurface_preset(std::string_view name);

// Refuses NaN/infinite values, σ_a < 0, σ_s′ ≤ 0 and η < 1 (or NaN), with one line naming the
// coefficient and the channel.
Status validate(const DipoleCoefficients& c);

// Fresnel terms. cos_theta in [0, 1] on the outside of the boundary.
double fresnel_transmittance(double cos_theta, double eta);
double diffuse_fresnel_transmittance(double eta);    // T(η), see above
double diffuse_fresnel_reflectance_fit(double eta);  // F_dr(η), the paper's polynomial
double boundary_factor(double eta);                  // A = (1 + F_dr)/(1 − F_dr)

// R_total for a reduced albedo in [0, 1] and a boundary factor A.
double total_diffuse_reflectance(double alpha_prime, double boundary_a);

// One channel of the dipole, derived once.
class DipoleProfile {
 public:
  DipoleProfile() = default;
  // Precondition: validate() accepted the coefficients.
  DipoleProfile(double sigma_a, double sigma_s_prime, double eta);

  double sigma_t_prime() const { return sigma_t_prime_; }
  double alpha_prime() const { return alpha_prime_; }
  double sigma_tr() const { return sigma_tr_; }
  double z_r() const { return z_r_; }
  double z_v() const { return z_v_; }
  double boundary_a() const { return a_; }

  // R_d(r), per unit area (inverse length squared), r ≥ 0.
  double profile(double r) const;
  // ∫ R_d over the plane, closed form.
  double total() const;
  // ∫_r^∞ 2πρ R_d(ρ) dρ, the reflectance beyond radius r (closed form, below).
  double tail(double r) const;
  // The radius beyond which the profile holds at most `fraction` of R_total (closed form of the
  // tail integral ∫_r^∞ 2πρ R_d dρ = (α′/2)(z_r e^{−σ_tr d_r}/d_r + z_v e^{−σ_tr d_v}/d_v),
  // solved by bisection). fraction in (0, 1).
  double radius_for_tail(double fraction) const;

 private:
  double sigma_t_prime_ = 1, alpha_prime_ = 0, sigma_tr_ = 0, z_r_ = 1, z_v_ = 1, a_ = 1;
};

// The three channels of a material, in the units of its coefficients.
struct DipoleMaterial {
  std::array<DipoleProfile, 3> channels;
  double eta = 1.3;
};
Result<DipoleMaterial> make_dipole(const DipoleCoefficients& c);

// The inverse of R_total: α′ in [0, 1) with R_total(α′, A) = reflectance (bisection to 1e-13 on
// a monotone function). reflectance in (0, 1), η ≥ 1; errors otherwise.
Result<double> invert_total_reflectance(double reflectance, double eta);

// Coefficients from a diffuse colour (R_total per channel, each in (0, 1)) and a diffuse mean
// free path ℓ_d = 1/σ_tr per channel (> 0, the unit of the result): α′ by the inversion, then
// σ_t′ = σ_tr/√(3(1 − α′)), σ_s′ = α′ σ_t′, σ_a = σ_t′ − σ_s′.
Result<DipoleCoefficients> coefficients_from_color(const Rgb& diffuse_color,
                                                   const Rgb& mean_free_path, double eta);

// The coefficients in another length unit: σ per mm times mm per unit gives σ per unit.
DipoleCoefficients scale_coefficients(const DipoleCoefficients& c, double mm_per_unit);

}  // namespace prt::subsurface
