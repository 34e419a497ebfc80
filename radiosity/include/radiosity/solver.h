// radiosity/solver.h — solving the radiosity equation for patch radiance
//
//   L_j = E_j + ρ_j · Σ_i K_ji L_i,   K_ji = A_i F_ij / A_j,
//
// (E emission, ρ albedo, both RGB; F from radiosity/form_factors.h, row i computed at sender i).
// K is the gather matrix that reciprocity (A_i F_ij = A_j F_ji) gives from the senders' rows:
// power A_i F_ij L_i leaves i toward j. Written this way a patch never hands on more power than
// it has (Σ_j F_ij ≤ 1), so energy is conserved for any estimate of F, and progressive
// refinement (which shoots rows) and the full-matrix solvers solve the same system.
//
// Solvers (Cohen & Greenberg 1985 and Cohen, Chen, Wallace & Greenberg 1988: [24], [25] of
// docs/REFERENCES.md):
//   GaussSeidel, Jacobi: iterate on the full matrix from L = E; one sweep per iteration.
//   Progressive: repeatedly shoot the unshot radiance of the patch with the most unshot power
//     A_i·Σ_c ΔL_i,c (ties: the lowest index), its form-factor row computed when first needed
//     and kept (in parallel with the rows of up to 15 further patches with the most unshot
//     power that have none yet). The display estimate adds the ambient term of [25]: L_i +
//     ρ_i·L_amb with L_amb = Σ_j A_j ΔL_j / Σ_j A_j / (1 − ρ̄), ρ̄ the area-weighted mean albedo.
// Stop criterion (all three): the unshot power Σ_i A_i Σ_c r_i,c, with the residual
// r = E + ρ·K·L − L (progressive: r = ΔL), is at most tolerance × the emitted power Σ A Σ_c E,
// or max_iterations (sweeps; progressive: shots) is reached (Solution::converged = false).
// Every solver starts below the solution and only adds non-negative amounts, so r ≥ 0.
// Energy is checked after every step: the unshot power must not grow (relative slack 1e-9) and
// no residual may be negative beyond rounding; a violation throws std::logic_error.
// Results do not depend on the thread count (rows are independent; sums are sequential).
//
// The full-matrix solvers work on the gather matrix K (GatherMatrix), which depends on the
// patch geometry and F only: a change of emission or albedo re-solves with the same K and no
// form factors (docs/RADIOSITY.md, "Resuming"). Each step evaluates g = K·L once (rows in
// parallel, each row summed in double over four interleaved partial sums per channel, in a
// fixed order); Jacobi takes its next iterate from that same g, Gauss–Seidel sweeps the rows in
// order. The energy account of the result is taken from the last evaluation, under K:
// escaped_i uses the fraction Σ_j A_j K_ji / A_i that K moves out of patch i.
#pragma once

#include <cstddef>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

enum class SolverKind { GaussSeidel, Jacobi, Progressive };

// Every solver keeps N² floats of form factors (progressive: the rows it has computed; the
// full-matrix solvers: F and K, 8·N² bytes). Callers refuse scenes with more patches than this
// (8·16384² bytes = 2 GiB).
constexpr std::size_t kMaxPatches = 16384;

struct SolveOptions {
  SolverKind solver = SolverKind::GaussSeidel;
  double tolerance = 1e-6;  // relative unshot power at which to stop
  std::size_t max_iterations = 100000;
};

// Power accounts, per RGB channel, in units of radiance × area (multiply by π for flux).
struct EnergyAccount {
  glm::dvec3 emitted{0.0};   // Σ A_i E_i
  glm::dvec3 absorbed{0.0};  // Σ_j (1 − ρ_j) · arrived_j, arrived_j = Σ_i A_i F_ij L_i
  glm::dvec3 escaped{0.0};   // Σ_i A_i L_i (1 − Σ_j F_ij): left the scene or hit a back face
  glm::dvec3 unshot{0.0};    // Σ A r: not yet propagated
  // |emitted − absorbed − escaped − unshot| / emitted, the largest over the channels.
  double balance_error() const;
};

struct Solution {
  std::vector<glm::dvec3> radiance;          // per patch (for progressive: without ambient)
  std::vector<glm::dvec3> display_radiance;  // progressive: with the ambient term; else = radiance
  std::size_t iterations = 0;                // sweeps or shots
  bool converged = false;
  double relative_unshot = 0.0;        // unshot / emitted power at the end
  std::vector<double> unshot_history;  // relative unshot power after each step
  EnergyAccount energy;
  std::size_t rows_computed = 0;  // progressive: form-factor rows computed
};

// The gather matrix of F: K_ji = A_i F_ij / A_j as floats (computed in double), row j
// contiguous; 4·N² bytes. Zero rows for patches of zero area.
struct GatherMatrix {
  std::size_t size = 0;
  std::vector<float> k;     // size², K_ji at k[j·size + i]
  std::vector<double> out;  // Σ_j A_j K_ji / A_i per patch i: the fraction K moves out of i
};
GatherMatrix make_gather_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f);

// Full-matrix solvers (GaussSeidel or Jacobi) on a prepared K (any emission and albedo of the
// same geometry), or on F (K is made first).
Solution solve_matrix(const std::vector<Patch>& patches, const GatherMatrix& k,
                      const SolveOptions& options);
Solution solve_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                      const SolveOptions& options);

// Progressive refinement; form-factor rows from form_factor_row(…, ff_options).
Solution solve_progressive(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                           const FormFactorOptions& ff_options, const SolveOptions& options);

// The energy account of radiance L under F (the matrix solvers' account).
EnergyAccount energy_account(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                             const std::vector<glm::dvec3>& radiance);

}  // namespace prt::radiosity
