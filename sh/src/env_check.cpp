// sh/src/env_check.cpp — the texel policy applied to a whole map, and resolution against order
// (sh/env_check.h).
#include "sh/env_check.h"

#include <algorithm>

#include "sh/constants.h"

namespace prt::sh {

double EnvTexelReport::invalid_fraction() const {
  return invalid_solid_angle / (4.0 * kPi);
}

EnvTexelReport screen_env_map(EnvMap* env) {
  EnvTexelReport report;
  const std::vector<double> solid_angles = texel_solid_angles(env->layout, env->width, env->height);
  for (std::size_t texel = 0; texel < solid_angles.size(); ++texel) {
    float* rgb = &env->rgb[3 * texel];
    if (!(solid_angles[texel] > 0.0)) {  // off the sphere: carries nothing
      rgb[0] = rgb[1] = rgb[2] = 0.0f;
      continue;
    }
    const TexelClass kind = screen_texel(rgb, rgb);
    if (kind == TexelClass::NaN) ++report.nan_texels;
    if (kind == TexelClass::Inf) ++report.inf_texels;
    if (kind == TexelClass::Negative) ++report.negative_texels;
    if (kind == TexelClass::NaN || kind == TexelClass::Inf)
      report.invalid_solid_angle += solid_angles[texel];
    if (rgb[0] > 0.0f || rgb[1] > 0.0f || rgb[2] > 0.0f) report.all_black = false;
  }
  return report;
}

int great_circle_texels(const EnvMap& env) noexcept {
  switch (env.layout) {
    case EnvLayout::LatLong:
    case EnvLayout::Angular:
      return env.width;
    case EnvLayout::Cross:
      return 4 * (env.width / 3);
    case EnvLayout::Faces:
      return 4 * env.width;
  }
  return env.width;
}

int resolved_band(const EnvMap& env) noexcept {
  return std::max(0, great_circle_texels(env) / 2);
}

OrderFit order_fit(const EnvMap& env, int order) noexcept {
  const int band = order - 1;
  if (band > great_circle_texels(env)) return OrderFit::FarTooSmall;
  if (band > resolved_band(env)) return OrderFit::Aliasing;
  return OrderFit::Fine;
}

}  // namespace prt::sh
