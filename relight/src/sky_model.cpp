// relight/src/sky_model.cpp — the analytic sky (model in relight/sky_model.h).
#include "relight/sky_model.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sh/constants.h"

namespace prt::relight {
namespace {

using sh::kPi;
constexpr double kDegree = kPi / 180.0;

double smoothstep(double edge0, double edge1, double x) {
  const double t = std::clamp((x - edge0) / (edge1 - edge0), 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

}  // namespace

std::array<double, 3> sun_direction(const SkyParams& params) {
  const double e = params.sun_elevation_deg * kDegree, a = params.sun_azimuth_deg * kDegree;
  return {std::cos(e) * std::cos(a), std::sin(e), std::cos(e) * std::sin(a)};
}

std::array<double, 3> sky_radiance(const SkyParams& params, const double dir[3]) {
  const double y = std::clamp(dir[1], -1.0, 1.0);
  // Sky and ground, blended over ±0.5° around the horizon.
  const double sky_weight = std::pow(std::max(y, 0.0), 0.4);
  const double ground_shade = 0.6 + 0.4 * std::pow(1.0 - std::abs(y), 4.0);
  const double horizon_blend = smoothstep(-std::sin(0.5 * kDegree), std::sin(0.5 * kDegree), y);
  std::array<double, 3> radiance;
  for (int c = 0; c < 3; ++c) {
    const double sky = params.horizon_colour[c] +
                       (params.zenith_colour[c] - params.horizon_colour[c]) * sky_weight;
    const double ground = params.ground_colour[c] * ground_shade;
    radiance[c] = ground + (sky - ground) * horizon_blend;
  }
  // Sun disc and glow, by the angle ρ to the sun's centre.
  const std::array<double, 3> s = sun_direction(params);
  const double cosine = std::clamp(dir[0] * s[0] + dir[1] * s[1] + dir[2] * s[2], -1.0, 1.0);
  // Angle via atan2 of |d × s| and d·s: accurate at small angles, unlike acos.
  const double cx = dir[1] * s[2] - dir[2] * s[1], cy = dir[2] * s[0] - dir[0] * s[2],
               cz = dir[0] * s[1] - dir[1] * s[0];
  const double rho = std::atan2(std::sqrt(cx * cx + cy * cy + cz * cz), cosine);
  const double radius = params.sun_radius_deg * kDegree;
  const double sigma = params.glow_width_deg * kDegree;
  double sun = 0.0;
  if (rho < radius) {
    const double q = rho / radius;
    sun = params.sun_radiance * (1.0 - 0.4 * (1.0 - std::sqrt(1.0 - q * q)));
  }
  const double glow =
      sigma > 0 ? params.glow_radiance * std::exp(-rho * rho / (2 * sigma * sigma)) : 0.0;
  for (int c = 0; c < 3; ++c) radiance[c] += params.sun_colour[c] * (sun + glow);
  return radiance;
}

sh::EnvMap make_procedural_sky(int width, int height, const SkyParams& params) {
  if (width <= 0 || height <= 0)
    throw std::invalid_argument("make_procedural_sky: the size must be positive");
  const int n = std::max(1, params.supersampling);
  sh::EnvMap env;
  env.layout = sh::EnvLayout::LatLong;
  env.width = width;
  env.height = height;
  env.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      double sum[3] = {0, 0, 0};
      for (int j = 0; j < n; ++j) {
        const double theta = kPi * (row + (j + 0.5) / n) / height;
        for (int i = 0; i < n; ++i) {
          const double phi = 2.0 * kPi * ((col + (i + 0.5) / n) / width - 0.5);
          const double dir[3] = {std::sin(theta) * std::cos(phi), std::cos(theta),
                                 std::sin(theta) * std::sin(phi)};
          const std::array<double, 3> radiance = sky_radiance(params, dir);
          for (int c = 0; c < 3; ++c) sum[c] += radiance[c];
        }
      }
      float* texel = &env.rgb[(static_cast<std::size_t>(row) * width + col) * 3];
      for (int c = 0; c < 3; ++c) texel[c] = static_cast<float>(sum[c] / (n * n));
    }
  }
  return env;
}

}  // namespace prt::relight
