// sh/polar_axis.h — change of polar axis between the scene basis (polar axis +z, sh/basis.h) and
// the basis whose polar axis is the scene's +y, at every order up to kMaxOrder, in O(order³).
//
// The +y-polar basis is Y_k(P d) with P(x, y, z) = (z, x, y): its polar angle is measured from +y
// and its azimuth φ' from +z towards +x (the separable projection of lat-long maps sums in it,
// sh/projection.h). A function f = Σ_j c'_j Y_j(P ·) = Σ_k c_k Y_k has c = G(Pᵀ) c', where
// G(R) is the real SH rotation matrix of sh/rotation.h (coefficients of f(Rᵀ ω)); the inverse is
// c' = G(Pᵀ)ᵀ c. Band by band, with Pᵀ = Rz(π/2)·Ry(π/2)·Rz(π):
//     G(Pᵀ) = Gz(π/2) · Gy(π/2) · Gz(π),
// where Gz(α) is the z-rotation (b_m = cos(mα) a_m − sin(mα) a_−m, b_−m = sin(mα) a_m +
// cos(mα) a_−m for m > 0) and Gy(π/2) comes from the Wigner d-matrix at π/2,
// d_m'm = d^l_m'm(π/2) = ⟨l m'| exp(−i (π/2) J_y) |l m⟩ (Condon–Shortley phase on the complex
// harmonics, Edmonds' convention): for m, m' > 0, with s = (−1)^l,
//     cos block  Gy(m', m)   = d_m'm ((−1)^(m+m') + s)    Gy(0, m) = √2 (−1)^m d_0m
//     sin block  Gy(−m', −m) = d_m'm ((−1)^(m+m') − s)    Gy(m', 0) = d_m'0 ((−1)^m' + s)/√2
// and Gy(0, 0) = d_00; cosine-type (m ≥ 0) and sine-type (m < 0) functions do not mix. This
// follows from Y^m(R⁻¹ r) = Σ_m' D_m'm Y^m'(r) for the complex harmonics, real Y_l,±m =
// (−1)^m √2 {Re, Im} Y^m without the phase, and d_−m',m(π/2) = (−1)^(l+m) d_m'm(π/2).
//
// d^l(π/2) is built band by band with the recurrence of Trapani & Navaza (2006), eq. 9–12:
//     d^l_l0 = −√((2l−1)/(2l)) d^(l−1)_(l−1)0,
//     d^l_lm = √(l(2l−1) / (2(l+m)(l+m−1))) d^(l−1)_(l−1)(m−1)                (1 ≤ m ≤ l),
//     d^l_m'm = (2m d^l_(m'+1)m − √((l−m'−1)(l+m'+2)) d^l_(m'+2)m) / √((l−m')(l+m'+1)),
// the last for m' = l−1 down to m at fixed m (from the exponentially small corner into the
// oscillatory region, the stable direction), then d_m m' = (−1)^(m'−m) d_m'm. Band l costs
// O(l²) and needs only the top row of band l−1. Measured accuracy (tests/sh/test_polar_axis.cpp):
// the rows of d^l(π/2) are orthonormal to 7e-15 at l = 1023; at order 1024 a change of axis keeps
// each band's norm to 7e-15 relative, there and back returns O(1) coefficients to 2.4e-14, and a
// delta's coefficients Y_k(P d0) go to Y_k(d0) to 6e-14 (|Y| up to 9); below order 20 it equals
// sh::Rotation of Pᵀ to rounding.
// The smallest entry, d^l_ll = 2^−l, is subnormal only at l = 1023 (2^−1023, exact).
// References: [44] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace prt::sh {

// The Wigner d-matrix at π/2, band after band (one band at a time in memory).
class WignerHalfPi {
 public:
  // Starts at band 0 (d^0 = 1).
  WignerHalfPi();

  // Moves to band band() + 1.
  void next();

  int band() const noexcept { return band_; }

  // Row m of the upper triangle: upper_row(m)[m'] = d^l_m m'(π/2) for m ≤ m' ≤ l = band()
  // (0 ≤ m ≤ l; the other entries of the row are unspecified).
  const double* upper_row(int m) const noexcept {
    return upper_.data() + static_cast<std::size_t>(m) * (band_ + 1);
  }

  // d^l_m'm(π/2) for any −l ≤ m', m ≤ l (through the symmetries above); 0 outside.
  double operator()(int m_primed, int m) const noexcept;

 private:
  int band_ = 0;
  std::vector<double> upper_;                     // (l+1)² entries, upper triangle used
  std::vector<double> top_row_;                   // d^l_l,m for m = 0..l, kept for the next band
  std::vector<double> next_top_row_, inv_a_, b_;  // scratch of next()
};

// c = G(Pᵀ) c' for `channels` channel-major vectors of order² coefficients (in[ch·order² + k]):
// +y-polar coefficients in, scene (+z-polar) coefficients out. `in` and `out` must not overlap.
// order in [1, kMaxOrder] (otherwise nothing is written). band_done (optional) is called after
// each band with the band just finished (for progress reports). O(order³) time, O(order²) memory.
void polar_y_to_z(int order, int channels, const double* in, double* out,
                  const std::function<void(int band)>& band_done = {});

// The inverse, c' = G(Pᵀ)ᵀ c: scene coefficients in, +y-polar coefficients out.
void polar_z_to_y(int order, int channels, const double* in, double* out);

}  // namespace prt::sh
