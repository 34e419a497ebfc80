// sh/zonal.h — zonal (axially symmetric) functions: the clamped cosine, convolution, and
// rotation of a zonal function onto an arbitrary axis.
//
// Convention: the basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase, polar axis
// +z, k = l(l+1) + m). A zonal function about +z has only m = 0 coefficients z_l.
//
// Funk–Hecke: convolving f with a zonal kernel k multiplies band l of f by
//   A_l = √(4π/(2l+1)) · k_l.
// For the clamped cosine max(cos θ, 0) (R. Ramamoorthi & P. Hanrahan, "An Efficient
// Representation for Irradiance Environment Maps", SIGGRAPH 2001, eq. 8–9):
//   A_0 = π, A_1 = 2π/3, A_l = 0 for odd l > 1, and for even l
//   A_l = 2π·(−1)^(l/2−1) / ((l+2)(l−1)) · l! / (2^l ((l/2)!)²),
// where the last ratio, C(l, l/2)/2^l, is computed by the product Π_{j=1..l/2} (2j−1)/(2j)
// (never with factorials), so the values are accurate at any l.
// References: [1] of docs/REFERENCES.md.
#pragma once

namespace prt::sh {

// A_l, the convolution factor of the clamped cosine for band l (0 for l < 0).
double clamped_cosine_band_factor(int l) noexcept;

// z_l = A_l·√((2l+1)/4π), the SH coefficient of max(cos θ, 0) about +z (0 for l < 0).
double clamped_cosine_zonal_coefficient(int l) noexcept;

// Multiplies every coefficient of band l (all m) by band_factors[l], for l < order, in place.
void convolve_zonal(int order, const double* band_factors, double* coefficients) noexcept;
void convolve_zonal(int order, const double* band_factors, float* coefficients) noexcept;

// Coefficients (order² of them) of the function symmetric about the unit axis (x, y, z) whose
// zonal coefficients about +z are zonal[0..order): out_lm = √(4π/(2l+1))·zonal[l]·Y_lm(axis).
// The axis must be unit length; an order outside [1, kMaxOrder] writes nothing.
void rotate_zonal(int order, const double* zonal, double x, double y, double z,
                  double* out) noexcept;
void rotate_zonal(int order, const float* zonal, float x, float y, float z, float* out) noexcept;

}  // namespace prt::sh
