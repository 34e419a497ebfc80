// bake/src/adaptive/sample_allocation.cpp — Neyman allocation with bounds (sample_allocation.h).
#include "bake/adaptive/sample_allocation.h"

#include <algorithm>
#include <cmath>

namespace prt::bake {
namespace {

uint32_t round_up(double n, uint32_t packet) {
  const double p = static_cast<double>(packet);
  return static_cast<uint32_t>(std::ceil(n / p - 1e-9) * p);
}

uint32_t count_for(double lambda, double a, uint32_t lo, uint32_t hi, uint32_t packet) {
  if (hi == 0) return 0;
  const double want = lambda * a;  // a: a_v/√c_v when costs are given
  if (!(want > lo)) return lo;     // also NaN-safe
  if (want >= hi) return hi;
  return std::min(hi, std::max(lo, round_up(want, packet)));
}

double error2(const std::vector<double>& a, const std::vector<uint32_t>& n) {
  double e = 0.0;
  for (std::size_t v = 0; v < a.size(); ++v)
    if (n[v] > 0) e += a[v] * a[v] / static_cast<double>(n[v]);
  return e;
}

}  // namespace

SampleAllocation allocate_samples(const std::vector<double>& a, const std::vector<uint32_t>& n_min,
                                  const std::vector<uint32_t>& n_max, double budget,
                                  uint32_t packet, const std::vector<double>& cost) {
  const std::size_t V = a.size();
  SampleAllocation r;
  r.samples.assign(V, 0);
  // n_v ∝ a_v/√c_v: the λ search runs on the cost-scaled spreads.
  std::vector<double> scaled = a;
  if (!cost.empty())
    for (std::size_t v = 0; v < V; ++v)
      scaled[v] = cost[v] > 0.0 ? a[v] / std::sqrt(cost[v]) : a[v];
  auto fill = [&](double lambda) {
    for (std::size_t v = 0; v < V; ++v)
      r.samples[v] = count_for(lambda, scaled[v], n_min[v], n_max[v], packet);
    return error2(a, r.samples);
  };
  // λ = 0: everyone at n_min. λ = ∞: everyone at n_max.
  double e = fill(0.0);
  if (e <= budget) {
    r.predicted_error2 = e, r.budget_met = true;
    return r;
  }
  double hi_lambda = 0.0;
  for (std::size_t v = 0; v < V; ++v)
    if (scaled[v] > 0.0 && n_max[v] > 0)
      hi_lambda = std::max(hi_lambda, static_cast<double>(n_max[v]) / scaled[v]);
  e = fill(hi_lambda);
  if (e > budget) {
    r.predicted_error2 = e;
    return r;
  }
  // Bisection on log λ between a λ that misses the budget and one that meets it.
  double lo = hi_lambda, hi = hi_lambda;
  for (std::size_t v = 0; v < V; ++v)
    if (scaled[v] > 0.0 && n_max[v] > 0)
      lo = std::min(lo, static_cast<double>(n_min[v]) / scaled[v]);
  lo = std::max(lo, 1e-300);
  for (int it = 0; it < 100 && hi / lo > 1.0 + 1e-9; ++it) {
    const double mid = std::sqrt(lo * hi);
    if (fill(mid) <= budget)
      hi = mid;
    else
      lo = mid;
  }
  r.predicted_error2 = fill(hi);
  r.budget_met = r.predicted_error2 <= budget;
  return r;
}

}  // namespace prt::bake
