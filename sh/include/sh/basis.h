// sh/basis.h — evaluation of the real spherical-harmonic basis.
//
// Convention (the same everywhere in prt; see README.md, "Conventions"):
//   * Real, orthonormal SH, ∫ Y_lm Y_l'm' dω = δ_ll' δ_mm', with NO Condon–Shortley phase.
//   * Functions of the unit vector (x, y, z) in the scene frame; the polar axis is +z.
//     (The scene frame itself is glTF's: right-handed, +Y up.)
//   * Order n means bands l = 0 .. n−1, i.e. n² coefficients; index k = l(l+1) + m.
//   * Y00 = 0.282095; Y1,−1 = 0.488603·y, Y1,0 = 0.488603·z, Y1,1 = 0.488603·x;
//     Y2,−2 = 1.092548·xy, Y2,−1 = 1.092548·yz, Y2,0 = 0.315392·(3z²−1),
//     Y2,1 = 1.092548·xz, Y2,2 = 0.546274·(x²−y²).
//   This is Ramamoorthi & Hanrahan's (2001) and most engines' convention.
//
// Evaluation uses a normalised three-term recurrence in z for the Legendre part and a
// complex-multiplication recurrence on (x + iy) for cos(mφ)·sin^m θ and sin(mφ)·sin^m θ,
// so there are no factorials, no atan2 and no division by sin θ: it is exact at the
// poles and stable to high order (tested to l = 200 in double).
// Reference: P.-P. Sloan, "Efficient Spherical Harmonic Evaluation", JCGT 2(2), 2013.
// References: [1], [7] of docs/REFERENCES.md.
#pragma once

namespace prt::sh {

// Number of coefficients of an order-n expansion (bands 0..n−1).
constexpr int coefficient_count(int order) noexcept {
  return order * order;
}

// Flat index of (l, m), −l ≤ m ≤ l.
constexpr int index(int l, int m) noexcept {
  return l * (l + 1) + m;
}

// Largest order the library accepts (bands 0..kMaxOrder−1).
inline constexpr int kMaxOrder = 1024;

// The convention above in one line: every JSON output of prt states it with this text, and
// `prt bake` writes it into the metadata of each coefficient file ("sh_basis"), so changing it
// changes the bytes of every file baked afterwards.
inline constexpr const char* kBasisConvention =
    "real orthonormal SH, no Condon-Shortley phase, index k = l(l+1)+m, Y(x,y,z) with polar "
    "axis +z, scene frame glTF (+Y up)";

// Evaluates all order² basis functions at the unit direction (x, y, z) into out[0 .. order²).
// The direction must be unit length; order must be in [1, kMaxOrder].
// Orders up to 6 take a hard-coded polynomial fast path that equals the recurrence.
// An order outside [1, kMaxOrder] writes nothing. A NaN component propagates to every output
// that depends on it (Y00 is a constant). Float: intermediate |Q_lm| exceed FLT_MAX beyond
// l ≈ 190, so keep float to moderate orders.
// No heap allocation; thread-safe (the recurrence tables are built once, on first use).
// Accuracy: double is tested to a relative 1e-10 at l = 200; float to l = 30 (see
// tests/sh/test_basis.cpp). Values whose true magnitude is below ~1e-200 (double) may flush
// to zero near the poles, where sin^m θ underflows.
void evaluate(int order, double x, double y, double z, double* out) noexcept;
void evaluate(int order, float x, float y, float z, float* out) noexcept;

// The general recurrence only, without the fast path (for tests and benchmarks).
// The float version computes in float (its tables are rounded from double).
void evaluate_recurrence(int order, double x, double y, double z, double* out) noexcept;
void evaluate_recurrence(int order, float x, float y, float z, float* out) noexcept;

}  // namespace prt::sh
