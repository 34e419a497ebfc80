// sh/rotation.h — rotation of real SH coefficient vectors.
//
// Convention: the basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase, polar axis
// +z, index k = l(l+1) + m). 3×3 matrices are row-major, right-handed, act on column vectors
// (v' = M·v) and must be proper rotations (orthonormal, det +1); nothing checks this.
//
// Semantics: Rotation(order, M) maps the coefficients of f to those of g(ω) = f(Mᵀ·ω), i.e.
// f rotated by M (a lobe of f pointing along d points along M·d in g). Hence
// R(A)·R(B) = R(A·B), and R is block diagonal: one orthogonal (2l+1)×(2l+1) matrix per band,
// with rows/columns indexed by m = −l..l. Band 1 is M itself with axes reordered to (y, z, x),
// because Y1,−1 ∝ y, Y1,0 ∝ z, Y1,1 ∝ x.
//
// Method: the recurrence of J. Ivanic & K. Ruedenberg, "Rotation Matrices for Real Spherical
// Harmonics. Direct Determination by Recursion", J. Phys. Chem. 100(15):6342–6347, 1996, with
// the additions and corrections of J. Phys. Chem. A 102(45):9099–9100, 1998. The published V
// term for m < 0 still carries a sign error; here it reads
//   V(m < 0) = P(1, m+1)·(1 − δ_{m,−1}) + P(−1, −m−1)·√(1 + δ_{m,−1}).
// Band l is built from band l − 1 and band 1 in O(l²). Its error grows with l (about 100× per
// 20 bands in double); measured orthogonality error for a generic rotation: 5e-15 at l = 20,
// 1e-13 at l = 40, 4e-12 at l = 60. The tests require < 1e-10 up to l = 20.
//
// The constructor writes band 2 in closed form (its entries are quadratic in M: Y2n(Mᵀω) is a
// quadratic form in ω; see write_band2 in src/rotation.cpp) and runs the recurrence from
// l = 3; matrices of order ≤ kInlineRotationOrder live inside the object (no heap allocation).
// build_with_recurrence() runs the recurrence from l = 2 and is the tests' reference.
// References: [2], [5] of docs/REFERENCES.md.
#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include "sh/basis.h"

namespace prt::sh {

// Largest order a Rotation accepts (its matrices take order·(4·order²−1)/3 doubles).
inline constexpr int kMaxRotationOrder = 256;

// Rotations of order up to this keep their matrices inline (no heap allocation).
inline constexpr int kInlineRotationOrder = 6;

// M = Ry(yaw)·Rx(pitch)·Rz(roll), angles in degrees, each a right-handed rotation about the
// named axis of the scene frame (+Y up), row-major, acting on column vectors: roll is applied
// first, then pitch, then yaw (yaw turns about the up axis).
std::array<double, 9> rotation_from_yaw_pitch_roll(double yaw_deg, double pitch_deg,
                                                   double roll_deg) noexcept;

class Rotation {
 public:
  // Builds the band matrices of bands 0..order−1 for the 3×3 rotation m (row-major).
  // order is clamped to [1, kMaxRotationOrder]; accuracy is best below order ≈ 30 (see above).
  // If the matrices cannot be allocated, order() is 0, apply() writes nothing and
  // band_matrix() returns nullptr (sh/ never throws).
  Rotation(int order, const std::array<double, 9>& m) noexcept;

  // The same matrices built by the general recurrence alone (band 2 included, no unrolling, no
  // AVX2): the slow reference path for tests and benchmarks.
  static Rotation build_with_recurrence(int order, const std::array<double, 9>& m) noexcept;

  int order() const noexcept { return order_; }

  // out = R·in for order² coefficients (in and out must not overlap).
  void apply(const double* in, double* out) const noexcept;
  // Float version: reads/writes float, accumulates in double.
  void apply(const float* in, float* out) const noexcept;

  // Band l's (2l+1)×(2l+1) matrix, row-major, row/column i ↔ m = i − l; nullptr if l is out of
  // range.
  const double* band_matrix(int l) const noexcept;

 private:
  static constexpr std::size_t kInlineDoubles =
      std::size_t(kInlineRotationOrder) * (4 * kInlineRotationOrder * kInlineRotationOrder - 1) / 3;
  struct RecurrenceTag {};
  Rotation(int order, const std::array<double, 9>& m, RecurrenceTag) noexcept;
  // Sets order_ and allocates; returns the storage, or nullptr (order_ = 0) on failure.
  double* allocate(int order) noexcept;
  const double* data() const noexcept {
    return order_ <= kInlineRotationOrder ? inline_matrices_ : matrices_.data();
  }

  int order_;
  // Band l at offset l(4l²−1)/3: inline_matrices_ for order ≤ kInlineRotationOrder, else
  // matrices_.
  double inline_matrices_[kInlineDoubles];
  std::vector<double> matrices_;
};

// Largest order rotate_coefficients() serves with its zxzxz fast path (bands 0..order−1); above
// it, rotate_coefficients() builds a Rotation and applies it.
inline constexpr int kFastRotateOrder = 16;

// out = Rotation(order, m)·in for order² coefficients (same semantics, same convention), without
// building band matrices: M is split into ZYZ Euler angles, M = Rz(α)·Ry(β)·Rz(γ), read straight
// from M's entries (no trigonometric calls; exact at the gimbal poles β = 0 and β = π), and
// Ry(β) = Rx(−90°)·Rz(β)·Rx(+90°), so per band
//   R(M) = Z(α)·X(−90°)·Z(β)·X(+90°)·Z(γ),
// where Z(θ) mixes each pair (m, −m) by cos mθ, sin mθ (built by angle addition from cos θ,
// sin θ) and X(±90°) are constant band matrices (computed once, thread-safe, by Rotation).
// X(+90°) only connects m and m' of equal parity under x → −x with (l+m even) ⇔ (m' ≥ 0), so it
// is four dense square blocks holding about a quarter of its entries. Cost per band l ≈
// 2·(l² + l + 1) + 12·l multiply–adds (applying a built band matrix alone takes (2l+1)²).
// For one use it is several times faster than building a Rotation and applying it (timings:
// docs/BENCHMARKS.md, "SH library").
// References: J. Kautz, P.-P. Sloan, J. Snyder, "Fast, Arbitrary BRDF Shading for
// Low-Frequency Lighting Using Spherical Harmonics", EGWR 2002 (the zxzxz factorisation);
// P.-P. Sloan, "Stupid Spherical Harmonics (SH) Tricks", GDC 2008.
// order is clamped to [1, kMaxRotationOrder]; in and out must not overlap. Orders up to
// kFastRotateOrder allocate nothing. The float version reads/writes float and computes in double.
void rotate_coefficients(int order, const std::array<double, 9>& m, const double* in,
                         double* out) noexcept;
void rotate_coefficients(int order, const std::array<double, 9>& m, const float* in,
                         float* out) noexcept;

}  // namespace prt::sh
