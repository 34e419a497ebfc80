// sh/projection.h — projection of an environment map onto spherical harmonics, and evaluation of
// an expansion in a direction.
//
// Basis: sh/basis.h (real orthonormal SH, no Condon–Shortley phase, k = l(l+1)+m, functions of
// the unit (x, y, z) of the glTF scene frame, polar axis +z). Map layouts and texel solid angles:
// sh/env_map.h. The projection is the quadrature
//     L_c,k = Σ_texels ω_texel · L_c(texel) · Y_k(dir_texel)
// with the EXACT solid angle ω of every texel (so a constant map gives √(4π)·c in k = 0 to
// rounding) and the direction of the texel centre, accumulated in double.
//
// Lat-long maps take a separable path that gives the same sum (to rounding) at every order, in
// O(H·W·min(n, W/2) + H·n² + n³) for an n-order projection of a W×H map instead of the direct
// sum's O(H·W·n²). Rows are circles of constant y, so the sum is first formed in the basis whose
// polar axis is +y — the functions Y_k(P d), P(x, y, z) = (z, x, y) (sh/polar_axis.h) — where
// each basis function is Λ_l|m|(y)·{cos, sin}(|m|φ'):
//   1. per row, its Fourier sums Σ_col L·{cos, sin}(mφ'_col) for m < n (only m ≤ W/2 are summed;
//      the others follow from the periodicity of the equispaced columns);
//   2. per frequency m, the sums over rows weighted by Λ_lm(cos θ_row) for l = m..n−1, the
//      normalised associated Legendre factor (incl. sin^m θ) run by the recurrence of
//      sh/basis.h, rows θ and π−θ paired by the parity of Λ;
//   3. the change of polar axis c = G(Pᵀ) c' of sh/polar_axis.h, band by band (stable at every
//      l < kMaxOrder).
// Measured agreement with the direct sum (tests/sh/test_projection.cpp) and run times
// (docs/BENCHMARKS.md, "Environment projection").
// Other layouts take the direct sum (no separable structure), O(texels·n²): slow at high orders
// — minutes at n = 200 on a 1000² map — hence the progress callback.
// (Separable SH transforms of equiangular grids: Driscoll & Healy 1994; Healy et al. 2003.)
// References: [8], [44] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "sh/env_map.h"

namespace prt::sh {

// Progress of a projection: called from the calling thread with the work done so far and the
// total, in units proportional to the expected time (0 ≤ done ≤ total, non-decreasing; the last
// call has done == total). Lat-long maps report a few hundred times; other layouts once per row,
// counting texels on the sphere.
using ProjectionProgress = std::function<void(std::uint64_t done, std::uint64_t total)>;

// What the projection saw. Only texels on the sphere count (not the empty cells of a cross or
// the corners of an angular map). Texels follow the policy of sh/env_check.h (screen_texel): a
// texel with any NaN component counts as NaN, otherwise any ±Inf as Inf, and such texels are
// skipped (they contribute nothing); otherwise a texel with a negative component counts as
// negative and is used with its negative components clamped to 0.
struct ProjectionStats {
  std::size_t nan_texels = 0, inf_texels = 0, negative_texels = 0;
  double solid_angle_sum = 0;  // solid angle of the texels used (4π when none were skipped)

  std::size_t skipped_texels() const { return nan_texels + inf_texels; }
};

// Projects the RGB radiance of env to order `order` (1 ≤ order ≤ kMaxOrder). Returns channel-major
// coefficients out[c·order² + k], c = 0, 1, 2 (r, g, b), or an empty vector for an invalid order,
// an empty map, rgb of the wrong size, or a size that does not fit the layout (lat-long maps of
// any W×H are accepted). Lat-long maps take the separable path, other layouts the direct sum.
// `progress` (optional) is called as described above.
std::vector<double> project(const EnvMap& env, int order, ProjectionStats* stats = nullptr,
                            const ProjectionProgress& progress = {});

// The plain direct sum over texels with sh::evaluate, for every layout (the reference path).
std::vector<double> project_direct(const EnvMap& env, int order, ProjectionStats* stats = nullptr,
                                   const ProjectionProgress& progress = {});

// Value of a channel-major expansion (coefficients[c·order² + k], c < channels) in direction dir
// (normalised internally; a zero or non-finite direction gives zeros): out[c] for c < channels.
void reconstruct(const double* coefficients, int channels, int order, const double dir[3],
                 double* out);

}  // namespace prt::sh
