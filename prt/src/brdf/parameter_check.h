// Parameter checks shared by the BRDF models' create() functions (internal header).
#pragma once

#include <cmath>
#include <cstdio>
#include <string>

#include "prt/brdf/vec3.h"
#include "prt/core/status.h"

namespace prt::brdf::detail {

inline std::string number_text(double v) {
  if (std::isnan(v)) return "NaN";
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

// Ok when lo <= v <= hi (and v is finite); otherwise "<model>: <what> is <v>, must be in [lo, hi]".
inline Status check_range(const char* model, const char* what, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return Status::Ok();
  return Status::Error(std::string(model) + ": " + what + " is " + number_text(v) +
                       ", must be in [" + number_text(lo) + ", " + number_text(hi) + "]");
}

inline Status check_rgb(const char* model, const char* what, const Rgb& c) {
  const double ch[3] = {c.r, c.g, c.b};
  const char* names[3] = {" (red)", " (green)", " (blue)"};
  for (int i = 0; i < 3; ++i) {
    const std::string label = std::string(what) + names[i];
    Status s = check_range(model, label.c_str(), ch[i], 0.0, 1.0);
    if (!s) return s;
  }
  return Status::Ok();
}

// Roughness α: finite, in [kMinRoughness, kMaxRoughness]. α → 0 is a mirror, which these
// models cannot represent as a function (it would be a delta distribution).
constexpr double kMinRoughness = 1e-3;
constexpr double kMaxRoughness = 1.0;

inline Status check_roughness(const char* model, const char* what, double alpha) {
  return check_range(model, what, alpha, kMinRoughness, kMaxRoughness);
}

}  // namespace prt::brdf::detail
