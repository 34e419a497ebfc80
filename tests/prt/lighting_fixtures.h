// lighting_fixtures.h — reproducible random SH lighting for the prt tests.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/lighting/sh_lighting.h"

namespace prt::test {

// RGB lighting of `order` (order² coefficients a channel), each coefficient uniform in [−1, 1]
// from std::mt19937(seed).
inline ShLighting random_lighting(int order, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> c(3 * order * order);
  for (double& x : c) x = unit(rng);
  auto light = ShLighting::from_coefficients(order, c.data());
  REQUIRE(light.ok());
  return *light;
}

}  // namespace prt::test
