// sh/src/zonal.cpp — clamped-cosine factors, zonal convolution and zonal rotation.
#include "sh/zonal.h"

#include <cmath>

#include "sh/basis.h"
#include "sh/constants.h"

namespace prt::sh {

double clamped_cosine_band_factor(int l) noexcept {
  if (l < 0) return 0.0;
  if (l == 0) return kPi;
  if (l == 1) return 2.0 * kPi / 3.0;
  if (l % 2 == 1) return 0.0;
  // C(l, l/2)/2^l = Π_{j=1..l/2} (2j−1)/(2j); decreases like 1/√(πl/2), no overflow.
  double ratio = 1.0;
  for (int j = 1; j <= l / 2; ++j) ratio *= (2.0 * j - 1.0) / (2.0 * j);
  const double sign = (l / 2) % 2 == 1 ? 1.0 : -1.0;  // (−1)^(l/2 − 1)
  return 2.0 * kPi * sign / ((l + 2.0) * (l - 1.0)) * ratio;
}

double clamped_cosine_zonal_coefficient(int l) noexcept {
  if (l < 0) return 0.0;
  return clamped_cosine_band_factor(l) * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
}

namespace {
template <typename T>
void convolve_impl(int order, const double* band_factors, T* coefficients) {
  for (int l = 0; l < order; ++l) {
    for (int k = l * l; k < (l + 1) * (l + 1); ++k) {
      coefficients[k] = static_cast<T>(coefficients[k] * band_factors[l]);
    }
  }
}

template <typename T>
void rotate_zonal_impl(int order, const T* zonal, T x, T y, T z, T* out) {
  if (order < 1 || order > kMaxOrder) return;
  evaluate(order, x, y, z, out);
  for (int l = 0; l < order; ++l) {
    const double f = std::sqrt(4.0 * kPi / (2.0 * l + 1.0)) * static_cast<double>(zonal[l]);
    for (int k = l * l; k < (l + 1) * (l + 1); ++k) out[k] = static_cast<T>(out[k] * f);
  }
}
}  // namespace

void convolve_zonal(int order, const double* band_factors, double* coefficients) noexcept {
  convolve_impl(order, band_factors, coefficients);
}

void convolve_zonal(int order, const double* band_factors, float* coefficients) noexcept {
  convolve_impl(order, band_factors, coefficients);
}

void rotate_zonal(int order, const double* zonal, double x, double y, double z,
                  double* out) noexcept {
  rotate_zonal_impl(order, zonal, x, y, z, out);
}

void rotate_zonal(int order, const float* zonal, float x, float y, float z, float* out) noexcept {
  rotate_zonal_impl(order, zonal, x, y, z, out);
}

}  // namespace prt::sh
