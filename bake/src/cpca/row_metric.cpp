// row_metric.cpp — see row_metric.h.
#include "row_metric.h"

#include <algorithm>
#include <cmath>

#include "pca.h"

namespace prt::detail {
namespace {

template <typename T>
void multiply(const std::vector<double>& a, std::size_t channels, std::size_t n2, const T* x,
              double* y) {
  for (std::size_t c = 0; c < channels; ++c) {
    const double* ac = a.data() + c * n2 * n2;
    const T* xc = x + c * n2 * n2;
    double* yc = y + c * n2 * n2;
    for (std::size_t i = 0; i < n2; ++i) {
      double* row = yc + i * n2;
      std::fill_n(row, n2, 0.0);
      for (std::size_t k = 0; k < n2; ++k) {
        const double aik = ac[i * n2 + k];
        if (aik == 0.0) continue;
        const T* xk = xc + k * n2;
        for (std::size_t j = 0; j < n2; ++j) row[j] += aik * double(xk[j]);
      }
    }
  }
}

}  // namespace

std::string RowMetric::build(const std::vector<double>& metric, std::size_t channel_count,
                             std::size_t coefficients) {
  channels = channel_count;
  n2 = coefficients;
  const std::size_t block = n2 * n2;
  if (metric.size() != channels * block) {
    return std::to_string(metric.size()) +
           " metric values, expected channels · n⁴ = " + std::to_string(channels * block);
  }
  g = metric;
  w.assign(channels * block, 0.0);
  w_inv.assign(channels * block, 0.0);
  for (std::size_t c = 0; c < channels; ++c) {
    const double* gc = g.data() + c * block;
    double largest = 0.0;
    for (std::size_t e = 0; e < block; ++e) {
      if (!std::isfinite(gc[e])) return "a metric value is not finite";
      largest = std::max(largest, std::fabs(gc[e]));
    }
    for (std::size_t i = 0; i < n2; ++i) {
      for (std::size_t j = 0; j < i; ++j) {
        if (std::fabs(gc[i * n2 + j] - gc[j * n2 + i]) > 1e-9 * largest) {
          return "the metric is not symmetric";
        }
      }
    }
    std::vector<double> a(gc, gc + block), values, vectors;
    jacobi_eigen(n2, a, values, vectors);  // descending; eigenvectors are columns
    if (!(values.front() > 0.0) || !(values.back() > 1e-12 * values.front())) {
      return "the metric is not positive definite";
    }
    for (std::size_t i = 0; i < n2; ++i) {
      for (std::size_t j = 0; j < n2; ++j) {
        double s = 0.0, s_inv = 0.0;
        for (std::size_t k = 0; k < n2; ++k) {
          const double vv = vectors[i * n2 + k] * vectors[j * n2 + k];
          s += vv * std::sqrt(values[k]);
          s_inv += vv / std::sqrt(values[k]);
        }
        w[c * block + i * n2 + j] = s;
        w_inv[c * block + i * n2 + j] = s_inv;
      }
    }
  }
  return "";
}

void RowMetric::apply(const std::vector<double>& a, const double* x, double* y) const {
  multiply(a, channels, n2, x, y);
}
void RowMetric::apply(const std::vector<double>& a, const float* x, double* y) const {
  multiply(a, channels, n2, x, y);
}

}  // namespace prt::detail
