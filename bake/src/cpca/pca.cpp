// pca.cpp — see pca.h.
#include "pca.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "numerics/rng.h"

namespace prt::detail {
namespace {

// Oversampling of the subspace iteration: p = k + kOversample columns.
constexpr std::size_t kOversample = 8;

// A deterministic pseudo-random value in [-1, 1) for (seed, row, column).
double hash_uniform(uint64_t seed, std::size_t row, std::size_t col) {
  using numerics::splitmix64;
  const uint64_t h = splitmix64(seed ^ splitmix64(row * 0x100000001b3ull + col));
  return 2.0 * numerics::unit_double_from_bits(h) - 1.0;
}

// The centred members y_i = x_i − μ, made a block of kRows at a time (never all m × d), so that a
// cluster's PCA holds O(kRows · d) however many members it has.
constexpr std::size_t kRows = 256;

struct CentredRows {
  const PcaInput& in;
  const std::vector<double>& mean;
  std::vector<double> y;  // kRows · d

  // Rows [i0, i1) into y (row i at y[(i − i0)·d]).
  void fill(std::size_t i0, std::size_t i1) {
    const std::size_t d = in.d;
    y.resize(kRows * d);
    for (std::size_t i = i0; i < i1; ++i) {
      const float* x = in.x + static_cast<std::size_t>(in.members[i]) * d;
      double* yi = &y[(i - i0) * d];
      for (std::size_t e = 0; e < d; ++e) yi[e] = x[e] - mean[e];
    }
  }
};

// z[i·p + j] = y_i · q_j for every member; and, when w is given, w_j = Σ_i z[i·p + j] · y_i
// (rows of w are vectors in R^d), members in order: the sums run in the order of the whole-matrix
// products, so blocking changes no bit.
void times_rows_and_columns(CentredRows& rows, std::size_t m, const double* q, std::size_t p,
                            std::vector<double>& z, std::vector<double>* w) {
  const std::size_t d = rows.in.d;
  z.assign(m * p, 0.0);
  if (w != nullptr) w->assign(p * d, 0.0);
  for (std::size_t i0 = 0; i0 < m; i0 += kRows) {
    const std::size_t i1 = std::min(m, i0 + kRows);
    rows.fill(i0, i1);
    for (std::size_t i = i0; i < i1; ++i) {
      const double* yi = &rows.y[(i - i0) * d];
      for (std::size_t j = 0; j < p; ++j) z[i * p + j] = dot(yi, q + j * d, d);
      if (w == nullptr) continue;
      for (std::size_t j = 0; j < p; ++j) {
        const double s = z[i * p + j];
        double* wj = &(*w)[j * d];
        for (std::size_t e = 0; e < d; ++e) wj[e] += s * yi[e];
      }
    }
  }
}

}  // namespace

double dot(const double* a, const double* b, std::size_t n) {
  double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < n; ++i) s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

void jacobi_eigen(std::size_t p, std::vector<double>& a, std::vector<double>& values,
                  std::vector<double>& vectors) {
  std::vector<double> v(p * p, 0.0);
  for (std::size_t i = 0; i < p; ++i) v[i * p + i] = 1.0;
  double total = 0.0;
  for (double x : a) total += x * x;
  for (int sweep = 0; sweep < 60; ++sweep) {
    double off = 0.0;
    for (std::size_t i = 0; i < p; ++i) {
      for (std::size_t j = i + 1; j < p; ++j) off += a[i * p + j] * a[i * p + j];
    }
    if (off <= 1e-30 * total || off == 0.0) break;
    for (std::size_t i = 0; i < p; ++i) {
      for (std::size_t j = i + 1; j < p; ++j) {
        const double aij = a[i * p + j];
        if (aij == 0.0) continue;
        // Rotation annihilating a[i][j] (Golub & Van Loan, the symmetric Schur decomposition).
        const double tau = (a[j * p + j] - a[i * p + i]) / (2.0 * aij);
        const double t = (tau >= 0 ? 1.0 : -1.0) / (std::fabs(tau) + std::sqrt(1.0 + tau * tau));
        const double c = 1.0 / std::sqrt(1.0 + t * t), s = t * c;
        for (std::size_t r = 0; r < p; ++r) {  // columns i, j
          const double ari = a[r * p + i], arj = a[r * p + j];
          a[r * p + i] = c * ari - s * arj;
          a[r * p + j] = s * ari + c * arj;
        }
        for (std::size_t r = 0; r < p; ++r) {  // rows i, j
          const double air = a[i * p + r], ajr = a[j * p + r];
          a[i * p + r] = c * air - s * ajr;
          a[j * p + r] = s * air + c * ajr;
        }
        for (std::size_t r = 0; r < p; ++r) {
          const double vri = v[r * p + i], vrj = v[r * p + j];
          v[r * p + i] = c * vri - s * vrj;
          v[r * p + j] = s * vri + c * vrj;
        }
      }
    }
  }
  std::vector<std::size_t> order(p);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t x, std::size_t y) { return a[x * p + x] > a[y * p + y]; });
  values.assign(p, 0.0);
  vectors.assign(p * p, 0.0);
  for (std::size_t k = 0; k < p; ++k) {
    values[k] = a[order[k] * p + order[k]];
    for (std::size_t r = 0; r < p; ++r) vectors[r * p + k] = v[r * p + order[k]];
  }
}

std::size_t orthonormalize_rows(std::size_t rows, std::size_t d, double* q) {
  std::size_t kept = 0;
  for (std::size_t r = 0; r < rows; ++r) {
    double* row = q + r * d;
    const double before = std::sqrt(dot(row, row, d));
    for (int pass = 0; pass < 2; ++pass) {
      for (std::size_t s = 0; s < r; ++s) {
        const double* other = q + s * d;
        const double c = dot(row, other, d);
        if (c != 0.0) {
          for (std::size_t e = 0; e < d; ++e) row[e] -= c * other[e];
        }
      }
    }
    const double after = std::sqrt(dot(row, row, d));
    if (!(after > 1e-9 * before) || after == 0.0) {
      std::fill(row, row + d, 0.0);
      continue;
    }
    for (std::size_t e = 0; e < d; ++e) row[e] /= after;
    ++kept;
  }
  return kept;
}

void cluster_pca(const PcaInput& in, std::vector<double>* mean, std::vector<double>* basis) {
  const std::size_t d = in.d, m = in.member_count, k = in.k;
  mean->assign(d, 0.0);
  basis->assign(k * d, 0.0);
  if (m == 0) return;
  for (std::size_t i = 0; i < m; ++i) {
    const float* x = in.x + static_cast<std::size_t>(in.members[i]) * d;
    for (std::size_t e = 0; e < d; ++e) (*mean)[e] += x[e];
  }
  for (std::size_t e = 0; e < d; ++e) (*mean)[e] /= static_cast<double>(m);
  if (k == 0) return;
  CentredRows rows{in, *mean, {}};
  const std::size_t p = std::min({k + kOversample, d, m});
  // Start: the previous round's vectors, then pseudo-random rows.
  std::vector<double> q(p * d);
  const bool warm = in.warm != nullptr && in.warm->size() == k * d;
  for (std::size_t j = 0; j < p; ++j) {
    const bool from_warm = warm && j < k && dot(&(*in.warm)[j * d], &(*in.warm)[j * d], d) > 0.5;
    for (std::size_t e = 0; e < d; ++e) {
      q[j * d + e] = from_warm ? (*in.warm)[j * d + e] : hash_uniform(in.seed, j, e);
    }
  }
  std::vector<double> z, w;
  const unsigned iterations = in.power_iterations + (warm ? 0u : 4u);
  if (p == d) {
    orthonormalize_rows(p, d, q.data());  // a basis of all of R^d: exact already
  } else {
    for (unsigned it = 0; it < std::max(1u, iterations); ++it) {
      times_rows_and_columns(rows, m, q.data(), p, z, &w);
      q.swap(w);
      orthonormalize_rows(p, d, q.data());
    }
  }
  // Rayleigh–Ritz: the eigenvectors of B = (Y Qᵀ)ᵀ(Y Qᵀ) rotate Q into principal vectors.
  times_rows_and_columns(rows, m, q.data(), p, z, nullptr);
  std::vector<double> b(p * p, 0.0), values, vectors;
  for (std::size_t i = 0; i < m; ++i) {
    for (std::size_t r = 0; r < p; ++r) {
      for (std::size_t c = 0; c < p; ++c) b[r * p + c] += z[i * p + r] * z[i * p + c];
    }
  }
  jacobi_eigen(p, b, values, vectors);
  const std::size_t kept = std::min(k, p);
  for (std::size_t c = 0; c < kept; ++c) {
    double* u = &(*basis)[c * d];
    for (std::size_t r = 0; r < p; ++r) {
      const double s = vectors[r * p + c];
      for (std::size_t e = 0; e < d; ++e) u[e] += s * q[r * d + e];
    }
  }
  // Re-orthonormalize (rows built from zeroed rows of Q drop out).
  orthonormalize_rows(kept, d, basis->data());
}

}  // namespace prt::detail
