// bake/subsurface_approx/gaussian_sum_fit.h — the dipole profile as a sum of Gaussians, for
// mesh-space diffusion (d'Eon & Luebke 2007's texture-space diffusion, on the mesh).
//
// A sum of K normalised 2D Gaussians with variances v_i shared by the three channels and weights
// w_i,c per channel:  R_fit,c(r) = Σ_i w_i,c G(v_i, r),  G(v, r) = e^{−r²/2v}/(2πv), so that
// ∫_plane G dA = 1 and ∫ R_fit,c dA = Σ_i w_i,c (the fit's total diffuse reflectance).
// The fit: least squares on r·R_d(r) (the profile's energy per unit radius over 2π), sampled at
// kFitSamples radii uniform on [0, r_max], r_max the radius holding all but 1e-4 of the widest
// channel's R_total (DipoleProfile::radius_for_tail). For given variances the weights solve a
// non-negative least-squares problem (exact: every subset of active weights is tried, K ≤ 8);
// the variances are a geometric series v_i = v_0 q^i whose v_0 and q are chosen by a grid search
// minimising the sum over channels of the residual relative to ‖r·R_d‖. Shared variances are
// d'Eon & Luebke's choice: one blur per Gaussian serves the three channels. Least squares on the
// shape leaves the total a little low (the long tail weighs little: 1–4% for the presets), so
// the weights are then scaled per channel to make Σ_i w_i,c = R_total,c exactly, as d'Eon &
// Luebke normalise theirs to the total reflectance; fitted_total keeps the sum before scaling.
// Units: those of the material's coefficients (r in the unit of 1/σ).
// References: d'Eon & Luebke, "Advanced Techniques for Realistic Real-Time Skin Rendering",
// GPU Gems 3 ch. 14 (2007); Jensen et al. 2001 for R_d (prt/subsurface/dipole.h).
#pragma once

#include <array>
#include <vector>

#include "prt/subsurface/dipole.h"

namespace prt::bake {

inline constexpr int kFitSamples = 2048;

struct GaussianSum {
  std::vector<double> variances;               // v_i, ascending
  std::vector<std::array<double, 3>> weights;  // w_i,c ≥ 0
  std::array<double, 3> relative_residual{};  // ‖r·R_fit − r·R_d‖ / ‖r·R_d‖ per channel
  std::array<double, 3> fitted_total{};       // Σ_i w_i,c before the scaling to R_total,c

  // R_fit,c(r).
  double evaluate(int channel, double r) const;
  // ∫ R_fit,c dA = Σ_i w_i,c.
  double total(int channel) const;
};

// Fits `count` Gaussians (1 to 8) to the three channels of `material`.
GaussianSum fit_gaussian_sum(const subsurface::DipoleMaterial& material, int count = 6);

// The best non-negative weights for fixed variances (exposed for tests): w minimising
// Σ_s (Σ_i w_i r_s G(v_i, r_s) − y_s)² with w ≥ 0; returns the residual norm.
double fit_gaussian_weights(const std::vector<double>& radii, const std::vector<double>& targets,
                            const std::vector<double>& variances, std::vector<double>& weights);

}  // namespace prt::bake
