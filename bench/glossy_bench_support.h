// bench/glossy_bench_support.h — the per-vertex b vector of glossy shading for the CPCA
// benchmarks: b_i(ω_o) = ∫ y_i(ω_i) f(ω_i, ω_o) cos⁺θ_i dω_i (prt/glossy/transfer.h), taken
// as B·y(ω_o) with B the BRDF's n²×n² SH matrix (projected once; b is then exact to the
// order-n projection in ω_o), as an engine does it: per vertex one frame change, one SH
// evaluation and one n²×n² matrix–vector product.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "prt/brdf/brdf.h"
#include "prt/glossy/transfer.h"
#include "sh/basis.h"

namespace prt::bench {

// Column-major B, columns padded with zeros to a multiple of 8 floats (stride S):
// B[j·S + i] = ∫∫ y_i(ω_i) f̄(ω_i, ω_o) cos θ_i y_j(ω_o) dω_i dω_o over the
// upper hemispheres (f̄ = mean of the RGB channels), by Gauss–Legendre in cos θ × uniform φ.
inline std::vector<float> brdf_sh_matrix(const prt::brdf::Brdf& f, int order, int n_theta) {
  const int n2 = order * order, n_phi = 2 * n_theta;
  std::vector<double> gx, gw;
  prt::numerics::append_gauss_legendre(n_theta, -1.0, 1.0, &gx, &gw);
  struct Node {
    prt::brdf::Vec3 w;
    double weight;
    std::vector<double> y;
  };
  std::vector<Node> nodes;
  for (int a = 0; a < n_theta; ++a) {
    const double z = 0.5 * (gx[a] + 1.0), s = std::sqrt(1.0 - z * z);
    for (int b = 0; b < n_phi; ++b) {
      const double phi = 2.0 * prt::numerics::kPi * (b + 0.5) / n_phi;
      Node nd{{s * std::cos(phi), s * std::sin(phi), z},
              0.5 * gw[a] * 2.0 * prt::numerics::kPi / n_phi,
              {}};
      nd.y.resize(n2);
      sh::evaluate(order, nd.w.x, nd.w.y, nd.w.z, nd.y.data());
      nodes.push_back(std::move(nd));
    }
  }
  std::vector<double> bm(std::size_t(n2) * n2, 0.0), inner(n2);
  for (const Node& o : nodes) {
    std::fill(inner.begin(), inner.end(), 0.0);
    for (const Node& i : nodes) {
      const prt::brdf::Rgb v = f.eval(i.w, o.w);
      const double fc = (v.r + v.g + v.b) / 3.0 * i.w.z * i.weight;
      for (int k = 0; k < n2; ++k) inner[k] += fc * i.y[k];
    }
    for (int j = 0; j < n2; ++j) {
      for (int k = 0; k < n2; ++k) bm[std::size_t(j) * n2 + k] += inner[k] * o.y[j] * o.weight;
    }
  }
  const int stride = (n2 + 7) / 8 * 8;
  std::vector<float> padded(std::size_t(n2) * stride, 0.0f);
  for (int j = 0; j < n2; ++j) {
    for (int i = 0; i < n2; ++i)
      padded[std::size_t(j) * stride + i] = float(bm[std::size_t(j) * n2 + i]);
  }
  return padded;
}

// out[i] = Σ_j B[j·S + i]·y[j], i < S (S = stride, a multiple of 8): plain loops.
inline void b_rows_scalar(const float* bmat, int n2, int stride, const float* y, float* out) {
  for (int i = 0; i < stride; ++i) out[i] = 0.0f;
  for (int j = 0; j < n2; ++j) {
    for (int i = 0; i < stride; ++i) out[i] += bmat[std::size_t(j) * stride + i] * y[j];
  }
}

#if defined(__x86_64__)
// The same with AVX2 + FMA, four vectors of rows at a time (the bench's own b: contraction is
// fine here; only the library's kernels must round like their portable twins).
__attribute__((target("avx2,fma"))) inline void b_rows_avx2(const float* bmat, int n2, int stride,
                                                            const float* y, float* out) {
  for (int i0 = 0; i0 < stride; i0 += 32) {
    const int vecs = std::min(4, (stride - i0) / 8);
    __m256 a0 = _mm256_setzero_ps(), a1 = a0, a2 = a0, a3 = a0;
    for (int j = 0; j < n2; ++j) {
      const float* col = bmat + std::size_t(j) * stride + i0;
      const __m256 yj = _mm256_broadcast_ss(y + j);
      a0 = _mm256_fmadd_ps(_mm256_loadu_ps(col), yj, a0);
      if (vecs > 1) a1 = _mm256_fmadd_ps(_mm256_loadu_ps(col + 8), yj, a1);
      if (vecs > 2) a2 = _mm256_fmadd_ps(_mm256_loadu_ps(col + 16), yj, a2);
      if (vecs > 3) a3 = _mm256_fmadd_ps(_mm256_loadu_ps(col + 24), yj, a3);
    }
    _mm256_storeu_ps(out + i0, a0);
    if (vecs > 1) _mm256_storeu_ps(out + i0 + 8, a1);
    if (vecs > 2) _mm256_storeu_ps(out + i0 + 16, a2);
    if (vecs > 3) _mm256_storeu_ps(out + i0 + 24, a3);
  }
}
#endif

// b of vertices [first, first + count) (grey: n² floats each) for an eye at `eye` (scene
// frame): ω_o = (eye − p)/|eye − p| in the vertex's tangent frame, y(ω_o), b = B·y.
inline void compute_b(const std::vector<float>& bmat, int order, const GlossyTransferData& d,
                      const float eye[3], std::size_t first, std::size_t count, float* b) {
  const int n2 = order * order, stride = (n2 + 7) / 8 * 8;
#if defined(__x86_64__)
  static const bool avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#else
  constexpr bool avx2 = false;
#endif
  float y[256], rows[256];
  for (std::size_t r = 0; r < count; ++r) {
    const std::size_t v = first + r;
    const float* p = &d.positions[3 * v];
    const float* n = &d.normals[3 * v];
    const float* t = &d.tangents[4 * v];
    float w[3] = {eye[0] - p[0], eye[1] - p[1], eye[2] - p[2]};
    const float inv = 1.0f / std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (float& x : w) x *= inv;
    const float bt[3] = {t[3] * (n[1] * t[2] - n[2] * t[1]), t[3] * (n[2] * t[0] - n[0] * t[2]),
                         t[3] * (n[0] * t[1] - n[1] * t[0])};
    const float lx = t[0] * w[0] + t[1] * w[1] + t[2] * w[2];
    const float ly = bt[0] * w[0] + bt[1] * w[1] + bt[2] * w[2];
    const float lz = n[0] * w[0] + n[1] * w[1] + n[2] * w[2];
    sh::evaluate(order, lx, ly, lz, y);
#if defined(__x86_64__)
    if (avx2) {
      b_rows_avx2(bmat.data(), n2, stride, y, rows);
    } else {
      b_rows_scalar(bmat.data(), n2, stride, y, rows);
    }
#else
    b_rows_scalar(bmat.data(), n2, stride, y, rows);
#endif
    std::copy(rows, rows + n2, b + r * n2);
  }
}

}  // namespace prt::bench
