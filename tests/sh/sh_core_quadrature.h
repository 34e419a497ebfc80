// tests/sh/sh_core_quadrature.h — exact product quadratures on the sphere for the SH tests.
//
// Gauss–Legendre in t = cos θ (about a chosen axis, over t ∈ [t0, t1]) times a uniform rule in
// φ. With nt nodes and nphi angles it integrates exactly every polynomial in (x, y, z) of
// degree ≤ min(2·nt − 1, nphi − 1) over the zone t0 ≤ ω·axis ≤ t1 (the φ rule is exact for
// trigonometric degree < nphi). The nodes are numerics/gauss_legendre.h's.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "numerics/gauss_legendre.h"
#include "sh/constants.h"

namespace sh_test {

struct Quadrature {
  std::vector<std::array<double, 3>> directions;
  std::vector<double> weights;
};

// Gauss–Legendre nodes and weights on [−1, 1] (numerics/gauss_legendre.h).
using prt::numerics::gauss_legendre;

// The product rule over the zone t0 ≤ ω·axis ≤ t1 (unit axis).
inline Quadrature make_zone_quadrature(int nt, int nphi, double t0 = -1.0, double t1 = 1.0,
                                       std::array<double, 3> axis = {0.0, 0.0, 1.0}) {
  // Orthonormal frame (u, v, axis).
  std::array<double, 3> helper =
      std::fabs(axis[2]) < 0.9 ? std::array<double, 3>{0, 0, 1} : std::array<double, 3>{1, 0, 0};
  std::array<double, 3> u = {helper[1] * axis[2] - helper[2] * axis[1],
                             helper[2] * axis[0] - helper[0] * axis[2],
                             helper[0] * axis[1] - helper[1] * axis[0]};
  const double nu = std::sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2]);
  for (double& c : u) c /= nu;
  const std::array<double, 3> v = {axis[1] * u[2] - axis[2] * u[1], axis[2] * u[0] - axis[0] * u[2],
                                   axis[0] * u[1] - axis[1] * u[0]};
  std::vector<double> nodes, weights;
  gauss_legendre(nt, &nodes, &weights);
  Quadrature q;
  const double pi = prt::sh::kPi;
  for (int i = 0; i < nt; ++i) {
    const double t = 0.5 * (t1 + t0) + 0.5 * (t1 - t0) * nodes[i];
    const double s = std::sqrt(std::fmax(0.0, 1.0 - t * t));
    for (int j = 0; j < nphi; ++j) {
      const double phi = 2.0 * pi * (j + 0.5) / nphi;
      const double a = s * std::cos(phi), b = s * std::sin(phi);
      q.directions.push_back({a * u[0] + b * v[0] + t * axis[0], a * u[1] + b * v[1] + t * axis[1],
                              a * u[2] + b * v[2] + t * axis[2]});
      q.weights.push_back(0.5 * (t1 - t0) * weights[i] * 2.0 * pi / nphi);
    }
  }
  return q;
}

}  // namespace sh_test
