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
// Lat-long maps take a separable path that gives the same sum (to rounding) much faster. Rows are
// circles of constant y, so the sum is first formed in a basis whose polar axis is +y — the
// functions Y_k(P d) with P(x, y, z) = (z, x, y) — where each basis function is
// Λ_l|m|(y)·{cos, sin}(|m|φ'): per row, Fourier sums of the row over columns with cos mφ', sin mφ'
// tabulated at column centres, combined with Λ_l|m|(cos θ_row) (the normalised associated
// Legendre factor incl. sin^|m| θ, taken from sh::evaluate so it shares the basis' conventions).
// The result c' relates to the wanted coefficients by c' = M c band by band, with
// M_jk = ∫ Y_j(P d) Y_k(d) dω orthogonal; M is computed exactly by a product Gauss–Legendre ×
// trapezoid rule that integrates band-l products exactly, and c = Mᵀ c'. This path is used up to
// order kSeparableMaxOrder (M costs O(order⁵)); larger orders use the direct sum.
// (Separable SH transforms of equiangular grids: Driscoll & Healy 1994; Healy et al. 2003.)
// References: [8] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <vector>

#include "sh/env_map.h"

namespace prt::sh {

// Orders above this project lat-long maps by the direct sum.
inline constexpr int kSeparableMaxOrder = 32;

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
// any W×H are accepted). Lat-long maps take the separable path up to kSeparableMaxOrder.
std::vector<double> project(const EnvMap& env, int order, ProjectionStats* stats = nullptr);

// The plain direct sum over texels with sh::evaluate, for every layout (the reference path).
std::vector<double> project_direct(const EnvMap& env, int order, ProjectionStats* stats = nullptr);

// Value of a channel-major expansion (coefficients[c·order² + k], c < channels) in direction dir
// (normalised internally; a zero or non-finite direction gives zeros): out[c] for c < channels.
void reconstruct(const double* coefficients, int channels, int order, const double dir[3],
                 double* out);

}  // namespace prt::sh
