// tests/support/synthetic_glossy.h — physically plausible glossy transfer matrices without a
// baker, for the CPCA and kernel tests and benchmarks.
//
// Scene (analytic, scene frame +Y up): a ground plane y = 0, a unit sphere at (0, 1, 0) and a
// sphere of radius 0.5 at (1.7, 0.5, 0.6), both resting on the ground. Vertices: 40% on the
// big sphere (Fibonacci points), 20% on the small one, 40% on a disc of radius 3.5 of the
// ground (sunflower spiral). Per vertex, the shadowed transfer in the GLOBAL frame is the
// operator "multiply by the visibility V(ω)", T_ij = ∫ y_i y_j V dω = Σ_k V_k G_ijk with V_k
// V's SH coefficients up to order 2n − 1 (exact: y_i·y_j has no higher band) and G the
// triple-product integrals (Gauss–Legendre × uniform φ, exact for these degrees). V is 1 above
// the tangent plane where the ray p + tω misses both spheres and (for points above the ground)
// ω_y ≥ 0; V_k is a Fibonacci-sphere quadrature of `directions` rays. Then M = R·T with R the
// SH rotation into the vertex's tangent frame (Duff et al.'s frame from the normal), as in
// prt/glossy/transfer.h. No interreflection. channels = 3 scales M per channel by a smooth
// position-dependent gain (a stand-in for coloured bounce light, not a physical bounce).
#pragma once

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "prt/glossy/transfer.h"
#include "sh/basis.h"
#include "sh/rotation.h"

namespace prt::test {

// G[(i·n² + j)·K + k] = ∫ y_i y_j y_k dω, i, j < n², k < K = (2n − 1)².
inline std::vector<double> triple_products(int order) {
  const int n2 = order * order, big = 2 * order - 1, kk = big * big;
  const int nz = 2 * order + 2, nphi = 8 * order;
  std::vector<double> zx, zw, y(kk), g(std::size_t(n2) * n2 * kk, 0.0);
  numerics::append_gauss_legendre(nz, -1.0, 1.0, &zx, &zw);
  for (int a = 0; a < nz; ++a) {
    for (int b = 0; b < nphi; ++b) {
      const double phi = 2.0 * numerics::kPi * (b + 0.5) / nphi, s = std::sqrt(1.0 - zx[a] * zx[a]);
      sh::evaluate(big, s * std::cos(phi), s * std::sin(phi), zx[a], y.data());
      const double w = zw[a] * 2.0 * numerics::kPi / nphi;
      for (int i = 0; i < n2; ++i) {
        for (int j = 0; j < n2; ++j) {
          const double wij = w * y[i] * y[j];
          double* gij = &g[(std::size_t(i) * n2 + j) * kk];
          for (int k = 0; k < kk; ++k) gij[k] += wij * y[k];
        }
      }
    }
  }
  return g;
}

struct Sphere {
  double c[3], r;
};

inline bool hits_sphere(const double p[3], const double d[3], const Sphere& s) {
  const double o[3] = {p[0] - s.c[0], p[1] - s.c[1], p[2] - s.c[2]};
  const double b = o[0] * d[0] + o[1] * d[1] + o[2] * d[2];
  const double c = o[0] * o[0] + o[1] * o[1] + o[2] * o[2] - s.r * s.r;
  const double disc = b * b - c;
  if (disc < 0) return false;
  const double t = -b + std::sqrt(disc);  // the far root: enough when p is outside
  return t > 1e-9 && (-b - std::sqrt(disc) > 1e-9 || c < 0);
}

// Duff et al.'s orthonormal frame from a unit normal: rows tangent, bitangent, normal.
inline std::array<double, 9> frame_from_normal(const double n[3]) {
  const double sign = std::copysign(1.0, n[2]);
  const double a = -1.0 / (sign + n[2]), b = n[0] * n[1] * a;
  return {1.0 + sign * n[0] * n[0] * a,
          sign * b,
          -sign * n[0],
          b,
          sign + n[1] * n[1] * a,
          -n[1],
          n[0],
          n[1],
          n[2]};
}

inline GlossyTransferData synthetic_glossy(std::size_t count, int order, int channels,
                                           int directions = 1024) {
  GlossyTransferData d;
  d.order = static_cast<uint32_t>(order);
  d.channels = static_cast<uint32_t>(channels);
  d.vertex_count = count;
  const int n2 = order * order, big = 2 * order - 1, kk = big * big;
  const std::vector<double> g = triple_products(order);
  // Fibonacci directions and their basis values.
  std::vector<double> dirs(3 * std::size_t(directions)), ydir(std::size_t(directions) * kk);
  const double golden = numerics::kPi * (3.0 - std::sqrt(5.0));
  for (int s = 0; s < directions; ++s) {
    const double z = 1.0 - (2.0 * s + 1.0) / directions, r = std::sqrt(1.0 - z * z);
    dirs[3 * s] = r * std::cos(golden * s);
    dirs[3 * s + 1] = z;  // +Y up: rows of directions are spread evenly in height
    dirs[3 * s + 2] = r * std::sin(golden * s);
    sh::evaluate(big, dirs[3 * s], dirs[3 * s + 1], dirs[3 * s + 2], &ydir[std::size_t(s) * kk]);
  }
  const Sphere spheres[2] = {{{0.0, 1.0, 0.0}, 1.0}, {{1.7, 0.5, 0.6}, 0.5}};
  d.positions.resize(3 * count);
  d.normals.resize(3 * count);
  d.tangents.resize(4 * count);
  d.matrices.assign(count * channels * n2 * n2, 0.0f);
  std::vector<double> vk(kk), t(std::size_t(n2) * n2), col(n2), rcol(n2);
  for (std::size_t v = 0; v < count; ++v) {
    double p[3], n[3];
    const std::size_t big_n = count * 2 / 5, small_n = count / 5;
    if (v < big_n + small_n) {
      const bool first = v < big_n;
      const double i = static_cast<double>(first ? v : v - big_n);
      const double m = static_cast<double>(first ? big_n : small_n);
      const Sphere& s = spheres[first ? 0 : 1];
      const double z = 1.0 - (2.0 * i + 1.0) / m, r = std::sqrt(1.0 - z * z);
      n[0] = r * std::cos(golden * i);
      n[1] = z;
      n[2] = r * std::sin(golden * i);
      for (int e = 0; e < 3; ++e) p[e] = s.c[e] + s.r * n[e];
    } else {
      const double i = static_cast<double>(v - big_n - small_n);
      const double m = static_cast<double>(count - big_n - small_n);
      const double rad = 3.5 * std::sqrt((i + 0.5) / m);
      p[0] = rad * std::cos(golden * i);
      p[1] = 0.0;
      p[2] = rad * std::sin(golden * i);
      n[0] = 0.0;
      n[1] = 1.0;
      n[2] = 0.0;
    }
    const std::array<double, 9> f = frame_from_normal(n);
    for (int e = 0; e < 3; ++e) {
      d.positions[3 * v + e] = static_cast<float>(p[e]);
      d.normals[3 * v + e] = static_cast<float>(n[e]);
      d.tangents[4 * v + e] = static_cast<float>(f[e]);
    }
    d.tangents[4 * v + 3] = 1.0f;
    const double origin[3] = {p[0] + 1e-6 * n[0], p[1] + 1e-6 * n[1], p[2] + 1e-6 * n[2]};
    std::fill(vk.begin(), vk.end(), 0.0);
    for (int s = 0; s < directions; ++s) {
      const double* w = &dirs[3 * s];
      if (w[0] * n[0] + w[1] * n[1] + w[2] * n[2] <= 0.0) continue;
      if (p[1] > 1e-6 && w[1] < 0.0) continue;  // the ground
      if (hits_sphere(origin, w, spheres[0]) || hits_sphere(origin, w, spheres[1])) continue;
      const double* ys = &ydir[std::size_t(s) * kk];
      for (int k = 0; k < kk; ++k) vk[k] += ys[k];
    }
    for (int k = 0; k < kk; ++k) vk[k] *= 4.0 * numerics::kPi / directions;
    for (int i = 0; i < n2; ++i) {
      for (int j = 0; j < n2; ++j) {
        const double* gij = &g[(std::size_t(i) * n2 + j) * kk];
        double sum = 0.0;
        for (int k = 0; k < kk; ++k) sum += gij[k] * vk[k];
        t[std::size_t(i) * n2 + j] = sum;
      }
    }
    const sh::Rotation rot(order, f);
    for (int c = 0; c < channels; ++c) {
      const double gain = 1.0 - 0.12 * c * (0.5 + 0.5 * std::sin(3.0 * p[0] + 2.0 * p[2]));
      float* m = &d.matrices[(v * channels + c) * n2 * n2];
      for (int j = 0; j < n2; ++j) {
        for (int i = 0; i < n2; ++i) col[i] = t[std::size_t(i) * n2 + j];
        rot.apply(col.data(), rcol.data());
        for (int i = 0; i < n2; ++i) m[i * n2 + j] = static_cast<float>(gain * rcol[i]);
      }
    }
  }
  d.material_of_vertex.assign(count, 0);
  d.materials.resize(1);
  return d;
}

}  // namespace prt::test
