// bake/src/cpca/row_metric.h (internal) — the metric of the CPCA compressor
// (CpcaOptions::row_metric): per channel c a symmetric positive definite n²×n² matrix G_c acting on
// the rows of the vertex's transfer matrices, the squared norm of an error δ being Σ_c tr(δ_cᵀ G_c
// δ_c). With W_c = G_c^{1/2} (symmetric, from the eigen-decomposition) that is the plain squared
// norm of W δ, so CPCA runs on W x and maps its means and vectors back by W⁻¹.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace prt::detail {

struct RowMetric {
  std::size_t channels = 0, n2 = 0;
  std::vector<double> g, w, w_inv;  // channels · n2 · n2 each, row-major per channel

  // Checks G (finite, symmetric to 1e-9 of its largest entry, positive definite: every
  // eigenvalue above 1e-12 of the largest) and factors it. Returns "" or the problem.
  std::string build(const std::vector<double>& metric, std::size_t channel_count,
                    std::size_t coefficients);

  // y_c = A_c x_c for one vertex's vector x (channels blocks of n2×n2, row-major), where
  // A is g, w or w_inv of this metric. x and y must not overlap.
  void apply(const std::vector<double>& a, const double* x, double* y) const;
  void apply(const std::vector<double>& a, const float* x, double* y) const;
};

}  // namespace prt::detail
