// relight/sky_model.h — the project's own analytic sky: a deterministic lat-long HDR map with a
// blue gradient sky, a warm-grey ground and a small bright sun with a soft glow.
//
// Frame: glTF (right-handed, +Y up). The lat-long layout is sh/env_map.h's (row 0 = zenith,
// centre column +X, u = ¼ → −Z). The sun direction is
//     s = (cos e · cos a, sin e, cos e · sin a)
// for elevation e above the horizon and azimuth a = atan2(z, x) — the lat-long azimuth, so the
// sun sits at column u = ½ + a/360°, row v = ½ − e/180°. Default e = 40°, a = 45° (+X/+Z side:
// to the right of and behind a camera looking down −Z, so lit faces face the camera).
//
// Radiance (linear, arbitrary but consistent units; zenith sky ≈ 0.3–0.9 per channel):
//   sky (y > 0):    mix(horizon, zenith, y^0.4)      — brighter and whiter toward the horizon
//   ground (y < 0): ground · (0.6 + 0.4·(1 − |y|)^4)  — darker, warm grey, a little lighter at
//                   the horizon; a smoothstep over ±0.5° joins sky and ground
//   sun:            sun_colour · sun_radiance inside the disc (angle to s < sun radius), with
//                   limb darkening 1 − 0.4·(1 − √(1 − (ρ/R)²)) (ρ = angle from the sun centre);
//   glow:           sun_colour · glow_radiance · exp(−ρ²/(2 σ²)), σ = glow_width, everywhere.
// This is a plausible-looking, simple analytic model (not a physical sky model such as
// Preetham or Hosek–Wilkie). Each texel is the mean of supersampling² sub-samples on a regular
// (unjittered) grid, so the sun disc is antialiased and the output is deterministic.
#pragma once

#include <array>

#include "sh/env_map.h"

namespace prt::relight {

struct SkyParams {
  double sun_elevation_deg = 40.0;
  double sun_azimuth_deg = 45.0;
  double sun_radius_deg = 1.0;   // angular radius of the disc (the real sun: 0.27°)
  double sun_radiance = 6000.0;  // disc radiance: ~1.4e4x the zenith sky's luminance (0.43),
                                 // ~8000x the mean sky's; the disc gives ~60% of the sky's flux
  double glow_radiance = 8.0;    // peak of the Gaussian glow around the sun
  double glow_width_deg = 5.0;   // σ of the glow
  std::array<double, 3> sun_colour = {1.0, 0.93, 0.82};
  std::array<double, 3> zenith_colour = {0.25, 0.45, 0.95};
  std::array<double, 3> horizon_colour = {0.85, 0.92, 1.05};
  std::array<double, 3> ground_colour = {0.32, 0.28, 0.23};
  int supersampling = 4;  // sub-samples per texel along each axis
};

// Unit sun direction of the parameters (see the header comment).
std::array<double, 3> sun_direction(const SkyParams& params);

// Radiance of the sky in a unit direction (no supersampling).
std::array<double, 3> sky_radiance(const SkyParams& params, const double dir[3]);

// A width × height lat-long map of the sky (width = 2·height for a valid lat-long map; any
// positive size is rendered). Throws std::invalid_argument for non-positive sizes.
sh::EnvMap make_procedural_sky(int width, int height, const SkyParams& params);

}  // namespace prt::relight
