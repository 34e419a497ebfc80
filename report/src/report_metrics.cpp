// report/src/report_metrics.cpp — see report_metrics.h.
#include "report/report_metrics.h"

#include <algorithm>
#include <cmath>

namespace prt::report {
namespace {

template <typename T>
VertexErrorStats vertex_errors(const std::vector<T>& b, const std::vector<double>& ref,
                               double floor_fraction) {
  VertexErrorStats s;
  const std::size_t n = std::min(b.size(), ref.size()) / 3;
  if (n == 0) return s;
  double e2 = 0, r2 = 0;
  std::vector<double> err(n), mag(n);
  for (std::size_t p = 0; p < n; ++p) {
    double d2 = 0, m2 = 0;
    for (int c = 0; c < 3; ++c) {
      const double bv = static_cast<double>(b[3 * p + c]);
      const double d = std::isfinite(bv) ? bv - ref[3 * p + c] : INFINITY;
      d2 += d * d;
      m2 += ref[3 * p + c] * ref[3 * p + c];
    }
    err[p] = std::sqrt(d2);
    mag[p] = std::sqrt(m2);
    e2 += d2;
    r2 += m2;
  }
  s.relative_rms = r2 > 0 ? std::sqrt(e2 / r2) : (e2 > 0 ? INFINITY : 0.0);
  const double floor = floor_fraction * std::sqrt(r2 / static_cast<double>(n));
  std::vector<double> rel(n);
  for (std::size_t p = 0; p < n; ++p) {
    const double denom = std::max(mag[p], floor);
    rel[p] = denom > 0 ? err[p] / denom : (err[p] > 0 ? INFINITY : 0.0);
    if (rel[p] > s.max || (std::isinf(rel[p]) && !std::isinf(s.max))) {
      s.max = rel[p];
      s.max_vertex = p;
    }
  }
  // Nearest-rank 99th percentile: the smallest value with at least 99% of values ≤ it.
  const std::size_t rank = static_cast<std::size_t>(std::ceil(0.99 * static_cast<double>(n)));
  std::nth_element(rel.begin(), rel.begin() + static_cast<long>(rank - 1), rel.end());
  s.p99 = rel[rank - 1];
  return s;
}

}  // namespace

VertexErrorStats compute_vertex_errors(const std::vector<float>& b,
                                       const std::vector<double>& reference,
                                       double floor_fraction) {
  return vertex_errors(b, reference, floor_fraction);
}

VertexErrorStats compute_vertex_errors(const std::vector<double>& b,
                                       const std::vector<double>& reference,
                                       double floor_fraction) {
  return vertex_errors(b, reference, floor_fraction);
}

double relative_rms_image_error(const std::vector<float>& a, const std::vector<float>& reference,
                                const std::vector<uint8_t>& mask) {
  const std::size_t n = std::min(a.size(), reference.size()) / 3;
  double e2 = 0, r2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!mask.empty() && (i >= mask.size() || mask[i] == 0)) continue;
    for (int c = 0; c < 3; ++c) {
      const double d = static_cast<double>(a[3 * i + c]) - reference[3 * i + c];
      e2 += std::isfinite(d) ? d * d : INFINITY;
      r2 += static_cast<double>(reference[3 * i + c]) * reference[3 * i + c];
    }
  }
  return r2 > 0 ? std::sqrt(e2 / r2) : 0.0;
}

std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error) {
  const std::size_t n = std::min(cost.size(), error.size());
  std::vector<bool> front(n, false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j) {
      if (j == i || !std::isfinite(cost[j]) || !std::isfinite(error[j])) continue;
      const bool no_worse = cost[j] <= cost[i] && error[j] <= error[i];
      const bool better = cost[j] < cost[i] || error[j] < error[i];
      const bool tie_before = cost[j] == cost[i] && error[j] == error[i] && j < i;
      dominated = (no_worse && better) || tie_before;
    }
    front[i] = !dominated;
  }
  return front;
}

long cheapest_reaching(const std::vector<double>& cost, const std::vector<double>& error,
                       double threshold) {
  long best = -1;
  for (std::size_t i = 0; i < std::min(cost.size(), error.size()); ++i)
    if (std::isfinite(cost[i]) && error[i] <= threshold &&
        (best < 0 || cost[i] < cost[static_cast<std::size_t>(best)]))
      best = static_cast<long>(i);
  return best;
}

}  // namespace prt::report
