// report/sun_study.h — where SH fails: the exit radiance of glossy surfaces under a sun (a disc of
// the sun's real angular diameter, 0.53°) plus a uniform sky, shaded through prt's glossy runtime
// path (prt/glossy/brdf_projection.h: b(ωo) · L', with L' the lighting's SH in the local frame, as
// prt/glossy/relighter.h does for an unshadowed convex surface, whose transfer matrix is the SH
// rotation into the local frame), against the exact exit radiance, a quadrature of f·cos over
// the sun disc that uses no SH. `prt report --sun-study` runs it; docs/GLOSSY.md, "Where SH
// fails", has the figures.
//
// Conventions: the SH basis of sh/basis.h; the BRDF frame of prt/brdf/brdf.h (+z normal); every
// direction is in that local frame. The sun's radiance is uniform over the disc; its irradiance
// on a plane facing it is E = L·π·sin²δ (δ the half angle), its solid angle 2π(1 − cos δ).
// The sky is a uniform radiance: order 1, so SH holds it exactly at every order. Its share of the
// exit radiance is taken as b_0·L_0 on both sides of the comparison (the same b), so every
// difference measured is the sun's.
// Errors: relative RMS = sqrt(Σ |approx − exact|² / Σ |exact|²) over configurations and RGB;
// relative peak = max |approx − exact| / max |exact|.
// Memory: a per-vertex n² × n² transfer matrix (one channel, as the shadowed glossy bake writes)
// costs n⁴ × 4 bytes at f32 and n⁴ × 2 at f16.
// Nothing here starts threads. Compiles as C++17. References: [2], [55] of docs/REFERENCES.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "prt/brdf/brdf.h"
#include "prt/brdf/material.h"
#include "prt/glossy/brdf_projection.h"

namespace prt::report {

inline constexpr double kSunAngularDiameterDegrees = 0.53;

// Solid angle of a disc of half angle δ (radians): 2π(1 − cos δ).
double disc_solid_angle(double half_angle);
// Irradiance on a plane facing a uniform disc of radiance L: L·π·sin²δ.
double disc_normal_irradiance(double half_angle, double radiance);

// SH zonal coefficients about the disc's axis, bands 0..order−1, of a uniform disc of half angle
// δ and radiance L: h_l = 2π√((2l+1)/4π)·L·∫_{cos δ}^{1} P_l(t) dt (sh/zonal.h's rotate_zonal
// places it at any direction).
std::vector<double> disc_zonal_coefficients(int order, double half_angle, double radiance);

// The exact exit radiance toward local ωo from the disc of half angle δ and radiance L centred on
// the local direction `sun`: ∫_disc f(ωi, ωo) cos⁺θi L dωi, by a product Gauss–Legendre rule in
// the cosine of the angle from the disc's axis (`rings` nodes) × uniform azimuth (`sectors`).
brdf::Rgb sun_exit_radiance(const brdf::Brdf& brdf, const brdf::Vec3& wo, const brdf::Vec3& sun,
                            double half_angle, double radiance, int rings = 6, int sectors = 12);

struct SunStudyMaterial {
  std::string name;
  brdf::Material material;
};

// Lambert (ρ 0.8), a GGX metal (F0 0.95 grey, Schlick, no diffuse) per α of `ggx_alphas`, and the
// three lobes of `prt make-scene --scene glossy` (glossy_red, brushed_steel, rough_gold).
std::vector<SunStudyMaterial> sun_study_materials(const std::vector<double>& ggx_alphas);

struct OrderError {
  int order = 0;
  double rms = 0, peak = 0;  // relative, see above
};

// The configurations of the sphere study, in the LOCAL frame of the surface: the views (unit ωo,
// z > 0) and the sun's directions (unit, over the whole sphere: a sun below the horizon gives
// no light but its SH rings), i.e. every orientation of a surface relative to the sun, seen at
// each view's elevation. Sun: half angle and radiance; sky: a uniform radiance (order 1, exact
// in SH at every order).
struct SunSphereSetup {
  double half_angle = 0, sun_radiance = 0, sky = 0;
  std::vector<brdf::Vec3> views, suns;
  std::vector<std::string> view_names;  // one per view, for the outputs
};

// The default setup: the real sun with normal irradiance 1, a uniform sky of irradiance
// `sky_fraction` on a plane (π·L_sky), views at elevations 90°, 60°, 30° and 10° above the
// tangent plane (θo 0°, 30°, 60°, 80°; at azimuth 0° and, for θo > 0, 90° from the tangent), and
// `sun_count` Fibonacci directions of the sun over the sphere. Every θo is a multiple of 5°, a
// node of sun_study_projection_options()'s isotropic table.
SunSphereSetup default_sun_setup(double sky_fraction, int sun_count);

// BrdfProjection options of the study: the runtime's kAuto with the isotropic table at 5° steps
// (19 elevations, so the views sit on nodes: no interpolation in θo) and 32 nodes per panel (the
// default 8 adds error above order 24 for broad lobes; docs/GLOSSY.md measures both).
BrdfProjectionOptions sun_study_projection_options();

// Errors of the runtime path at orders 1..max_order over every (view, sun direction): b(ωo) from
// one BrdfProjection of `material` at max_order (b at a lower order n is its first n² entries:
// b_i does not depend on n) times the lighting's SH in the local frame (sh::rotate_zonal of the
// disc, plus the sky's constant). Throws std::runtime_error on a material or order
// BrdfProjection refuses. `per_view` (optional) receives the errors of each view alone.
std::vector<OrderError> sphere_errors(
    const brdf::Material& material, const SunSphereSetup& setup, int max_order,
    const BrdfProjectionOptions& options = sun_study_projection_options(),
    std::vector<std::vector<OrderError>>* per_view = nullptr);

// Errors at normal incidence (ωo = the normal), sun only, for an ISOTROPIC material: there
// f(ωi, n)·cos θi is exactly zonal about the normal, so the SH series of the exit radiance is
// Σ_l b_l0·h_l·P_l(cos ψ) (ψ the sun's angle from the normal) and reaches orders far beyond the
// runtime path cheaply. b_l0 by Gauss–Legendre panels in θi (graded towards the normal); the
// configurations are ψ ∈ [0, π/2) weighted by solid angle. Orders 1..max_order.
std::vector<OrderError> normal_incidence_errors(const brdf::Brdf& brdf, double half_angle,
                                                int max_order);

// The smallest order n ≤ the last computed whose error (rms) and every later one is ≤ target;
// 0 when none.
int direct_needed_order(const std::vector<OrderError>& errors, double target);

// A fit of log(rms) over the second half of the curve (orders ≥ half the largest), either
// exponential (log e = a + b·n) or power law (log e = a + b·log n), whichever has the smaller
// residual; `order_for` extrapolates (0 when the fit does not fall).
struct DecayFit {
  bool exponential = true;
  double a = 0, b = 0, residual = 0;
  int first_order = 0, last_order = 0;
  double error_at(int order) const;
  int order_for(double target) const;  // smallest order with error_at ≤ target; 0 if none
};
DecayFit fit_decay(const std::vector<OrderError>& errors);

// Bytes of one vertex's n² × n² matrix, and the largest order whose `vertices` matrices fit in
// `budget_bytes` (0 when even order 1 does not).
double transfer_matrix_bytes(int order, int bytes_per_value);
int largest_fitting_order(double vertices, int bytes_per_value, double budget_bytes);

struct SunStudyOptions {
  std::string output_dir;
  bool quick = false;
  std::vector<double> ggx_alphas = {0.05, 0.1, 0.2, 0.4};
  double sky_fraction = 0.15;
  double vertices = 50000;
  double object_budget_gib = 1, machine_budget_gib = 24;
  std::vector<double> targets = {0.1, 0.01};
  std::function<void(const std::string&)> log;
};

struct SunStudyResult {
  std::vector<std::string> files_written;
};

// Runs the study and writes sun_study_file_names() into output_dir (created when missing; each
// file written atomically). Throws std::runtime_error "PATH: problem".
SunStudyResult run_sun_study(const SunStudyOptions& options);
std::vector<std::string> sun_study_file_names();

}  // namespace prt::report
