// The Haar relight's lighting (relight/haar_relight.h): an environment map rotated by resampling
// into a cube map.
#include <array>

#include <catch2/catch.hpp>

#include "prt/haar/cube_map.h"
#include "relight/haar_relight.h"
#include "sh/env_map.h"

TEST_CASE("Haar relight: rotating the environment by resampling preserves power and moves light") {
  // A lat-long map, black but for a bright patch toward +X at the horizon.
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = 128;
  env.height = 64;
  env.rgb.assign(3 * 128 * 64, 0.01f);
  for (int y = 30; y < 34; ++y)
    for (int x = 62; x < 66; ++x)  // u = 0.5: +X
      for (int c = 0; c < 3; ++c) env.rgb[3 * (y * 128 + x) + c] = 100.f;
  // Yaw 90° about +Y (rotation_from_yaw_pitch_roll convention) must carry +X to ±Z.
  const std::array<double, 9> m = {0, 0, 1, 0, 1, 0, -1, 0, 0};  // +X → −Z, +Z → +X
  const prt::CubeMap still = prt::relight::make_rotated_cube(env, 16, {1, 0, 0, 0, 1, 0, 0, 0, 1});
  const prt::CubeMap turned = prt::relight::make_rotated_cube(env, 16, m);
  double p0[3], p1[3];
  prt::cube_map_power(still, p0);
  prt::cube_map_power(turned, p1);
  // Tolerance 2%: the nearest-texel resampling of a 4×4-texel patch at 2N = 32 gains or loses
  // up to a fraction of its edge texels.
  CHECK(p1[0] == Approx(p0[0]).epsilon(0.02));
  auto face_power = [](const prt::CubeMap& c, int face) {
    double sum = 0;
    for (int i = 0; i < c.size * c.size; ++i) sum += c.rgb[3 * (face * c.size * c.size + i)];
    return sum;
  };
  CHECK(face_power(still, 0) > 10 * face_power(still, 5));    // +X lit, −Z not
  CHECK(face_power(turned, 5) > 10 * face_power(turned, 0));  // after: −Z lit, +X not
}
