// sh_lighting.cpp — SH lighting for the kernel; see prt/lighting/sh_lighting.h.
#include "prt/lighting/sh_lighting.h"

#include <cmath>
#include <new>
#include <string>

#include "sh/projection.h"
#include "sh/rotation.h"

namespace prt {
namespace {

bool order_in_range(int order) {
  return order >= 1 && order <= ShLighting::kMaxOrder;
}

Status order_error(int order) {
  return Status::Error("lighting: SH order " + std::to_string(order) + " is outside [1, " +
                       std::to_string(ShLighting::kMaxOrder) + "]");
}

template <class T>
bool all_finite(const T* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return false;
  }
  return true;
}

}  // namespace

ShLighting::ShLighting() : values_(3, 0.0), values_f_(3, 0.0f) {}

void ShLighting::refresh_float_copy() {
  values_f_.resize(values_.size());
  for (std::size_t i = 0; i < values_.size(); ++i) values_f_[i] = static_cast<float>(values_[i]);
}

const float* ShLighting::coefficients(int channel) const {
  return values_f_.data() + static_cast<std::size_t>(channel) * coefficient_count();
}

const double* ShLighting::coefficients_double(int channel) const {
  return values_.data() + static_cast<std::size_t>(channel) * coefficient_count();
}

Result<ShLighting> ShLighting::from_coefficients(int order, const float* rgb_channel_major) {
  if (!order_in_range(order)) return order_error(order);
  if (rgb_channel_major == nullptr) return Status::Error("lighting: coefficient pointer is null");
  try {
    const std::size_t n = 3 * static_cast<std::size_t>(order) * order;
    const std::vector<double> values(rgb_channel_major, rgb_channel_major + n);
    return from_coefficients(order, values.data());
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
}

Result<ShLighting> ShLighting::from_coefficients(int order, const double* rgb_channel_major) {
  if (!order_in_range(order)) return order_error(order);
  if (rgb_channel_major == nullptr) return Status::Error("lighting: coefficient pointer is null");
  const std::size_t n = 3 * static_cast<std::size_t>(order) * order;
  if (!all_finite(rgb_channel_major, n)) {
    return Status::Error("lighting: a coefficient is not finite");
  }
  try {
    ShLighting light;
    light.order_ = order;
    light.values_.assign(rgb_channel_major, rgb_channel_major + n);
    light.refresh_float_copy();
    return light;
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
}

Result<ShLighting> ShLighting::from_pixels(sh::EnvLayout layout, int width, int height,
                                           const float* rgb, int order) {
  if (!order_in_range(order)) return order_error(order);
  std::string why;
  if (!sh::validate_layout(layout, width, height, &why)) {
    return Status::Error(std::string("lighting: ") + sh::layout_name(layout) + " map " +
                         std::to_string(width) + "x" + std::to_string(height) + ": " + why);
  }
  if (rgb == nullptr) return Status::Error("lighting: pixel pointer is null");
  try {
    sh::EnvMap map;
    map.layout = layout;
    map.width = width;
    map.height = height;
    map.rgb.assign(rgb, rgb + 3 * static_cast<std::size_t>(width) * height);
    return from_env_map(map, order);
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
}

Result<ShLighting> ShLighting::from_env_map(const sh::EnvMap& map, int order) {
  if (!order_in_range(order)) return order_error(order);
  try {
    std::string why;
    if (!sh::validate_layout(map.layout, map.width, map.height, &why)) {
      return Status::Error(std::string("lighting: ") + sh::layout_name(map.layout) + " map " +
                           std::to_string(map.width) + "x" + std::to_string(map.height) + ": " +
                           why);
    }
    if (map.rgb.size() != 3 * static_cast<std::size_t>(map.width) * map.height) {
      return Status::Error("lighting: map holds " + std::to_string(map.rgb.size()) +
                           " floats, expected 3 per texel");
    }
    sh::ProjectionStats stats;
    const std::vector<double> coeffs = sh::project(map, order, &stats);
    if (coeffs.size() != 3 * static_cast<std::size_t>(order) * order) {
      return Status::Error("lighting: projection failed");
    }
    if (stats.nan_texels + stats.inf_texels > 0) {
      return Status::Error("lighting: the map has " +
                           std::to_string(stats.nan_texels + stats.inf_texels) +
                           " texels with NaN or Inf");
    }
    return from_coefficients(order, coeffs.data());
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
}

Status ShLighting::rotate(const std::array<double, 9>& m) {
  if (!all_finite(m.data(), 9)) return Status::Error("lighting: rotation matrix is not finite");
  // Orthonormal rows and det +1, to 1e-5.
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const double dot =
          m[3 * i] * m[3 * j] + m[3 * i + 1] * m[3 * j + 1] + m[3 * i + 2] * m[3 * j + 2];
      if (std::abs(dot - (i == j ? 1.0 : 0.0)) > 1e-5) {
        return Status::Error("lighting: matrix is not orthonormal");
      }
    }
  }
  const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) - m[1] * (m[3] * m[8] - m[5] * m[6]) +
                     m[2] * (m[3] * m[7] - m[4] * m[6]);
  if (std::abs(det - 1.0) > 1e-5) {
    return Status::Error("lighting: matrix is a reflection (determinant " + std::to_string(det) +
                         "), not a rotation");
  }
  try {
    std::vector<double> rotated(values_.size());
    const std::size_t n = coefficient_count();
    if (order_ <= sh::kFastRotateOrder) {
      // zxzxz path: no band matrices to build, cheaper than build + 3 applies at these orders.
      for (int c = 0; c < kChannels; ++c)
        sh::rotate_coefficients(order_, m, values_.data() + c * n, rotated.data() + c * n);
    } else {
      const sh::Rotation rotation(order_, m);
      for (int c = 0; c < kChannels; ++c)
        rotation.apply(values_.data() + c * n, rotated.data() + c * n);
    }
    values_.swap(rotated);
    refresh_float_copy();
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
  return Status::Ok();
}

}  // namespace prt

namespace prt {

Status ShLighting::apply_window(sh::Window window, double strength) {
  if (!std::isfinite(strength)) return Status::Error("lighting: window strength is not finite");
  try {
    if (window == sh::Window::Auto) {
      const sh::WindowChoice choice = sh::choose_window_auto(values_.data(), kChannels, order_);
      window = choice.window;
      strength = choice.strength;
    }
    const std::vector<double> factors = sh::window_band_factors(window, order_, strength);
    if (factors.size() != static_cast<std::size_t>(order_)) {
      return Status::Error("lighting: window factors unavailable");
    }
    const std::size_t n = coefficient_count();
    for (int c = 0; c < kChannels; ++c) {
      for (int l = 0; l < order_; ++l) {
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) values_[c * n + k] *= factors[l];
      }
    }
    refresh_float_copy();
  } catch (const std::bad_alloc&) {
    return Status::Error("lighting: out of memory");
  }
  return Status::Ok();
}

}  // namespace prt
