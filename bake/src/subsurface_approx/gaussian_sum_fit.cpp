// The dipole profile as a sum of Gaussians (see bake/subsurface_approx/gaussian_sum_fit.h).
#include "bake/subsurface_approx/gaussian_sum_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "numerics/constants.h"

namespace prt::bake {
namespace {

using numerics::kPi;

double gaussian(double v, double r) {
  return std::exp(-r * r / (2 * v)) / (2 * kPi * v);
}

// Solves the n × n system a x = b in place (Gaussian elimination, partial pivoting); false when
// singular.
bool solve_dense(std::vector<double> a, std::vector<double> b, int n, std::vector<double>& x) {
  for (int col = 0; col < n; ++col) {
    int pivot = col;
    for (int r = col + 1; r < n; ++r)
      if (std::fabs(a[r * n + col]) > std::fabs(a[pivot * n + col])) pivot = r;
    if (std::fabs(a[pivot * n + col]) < 1e-300) return false;
    for (int k = 0; k < n; ++k) std::swap(a[col * n + k], a[pivot * n + k]);
    std::swap(b[col], b[pivot]);
    for (int r = col + 1; r < n; ++r) {
      const double f = a[r * n + col] / a[col * n + col];
      for (int k = col; k < n; ++k) a[r * n + k] -= f * a[col * n + k];
      b[r] -= f * b[col];
    }
  }
  x.assign(n, 0.0);
  for (int r = n - 1; r >= 0; --r) {
    double s = b[r];
    for (int k = r + 1; k < n; ++k) s -= a[r * n + k] * x[k];
    x[r] = s / a[r * n + r];
  }
  return true;
}

}  // namespace

double GaussianSum::evaluate(int channel, double r) const {
  double s = 0;
  for (std::size_t i = 0; i < variances.size(); ++i)
    s += weights[i][channel] * gaussian(variances[i], r);
  return s;
}

double GaussianSum::total(int channel) const {
  double s = 0;
  for (const auto& w : weights) s += w[channel];
  return s;
}

double fit_gaussian_weights(const std::vector<double>& radii, const std::vector<double>& targets,
                            const std::vector<double>& variances, std::vector<double>& weights) {
  const int k = static_cast<int>(variances.size());
  const std::size_t m = radii.size();
  // Normal equations of the columns r·G(v_i, r), accumulated once.
  std::vector<double> gram(k * k, 0.0), rhs(k, 0.0), column(k);
  for (std::size_t s = 0; s < m; ++s) {
    for (int i = 0; i < k; ++i) column[i] = radii[s] * gaussian(variances[i], radii[s]);
    for (int i = 0; i < k; ++i) {
      rhs[i] += column[i] * targets[s];
      for (int j = 0; j < k; ++j) gram[i * k + j] += column[i] * column[j];
    }
  }
  double yy = 0;
  for (double y : targets) yy += y * y;
  // Exact NNLS: the best unconstrained solution over every subset whose weights are all ≥ 0.
  double best = std::numeric_limits<double>::infinity();
  weights.assign(k, 0.0);
  for (unsigned mask = 1; mask < (1u << k); ++mask) {
    std::vector<int> idx;
    for (int i = 0; i < k; ++i)
      if (mask & (1u << i)) idx.push_back(i);
    const int n = static_cast<int>(idx.size());
    std::vector<double> a(n * n), b(n), x;
    for (int i = 0; i < n; ++i) {
      b[i] = rhs[idx[i]];
      for (int j = 0; j < n; ++j) a[i * n + j] = gram[idx[i] * k + idx[j]];
    }
    if (!solve_dense(a, b, n, x)) continue;
    if (std::any_of(x.begin(), x.end(), [](double w) { return w < 0; })) continue;
    double xb = 0;  // residual² = yy − 2 xᵀb + xᵀGx = yy − xᵀb at the subset's optimum
    for (int i = 0; i < n; ++i) xb += x[i] * b[i];
    const double residual = yy - xb;
    if (residual < best) {
      best = residual;
      std::fill(weights.begin(), weights.end(), 0.0);
      for (int i = 0; i < n; ++i) weights[idx[i]] = x[i];
    }
  }
  return std::sqrt(std::max(best, 0.0));
}

GaussianSum fit_gaussian_sum(const subsurface::DipoleMaterial& material, int count) {
  count = std::clamp(count, 1, 8);
  double r_max = 0, r_min = std::numeric_limits<double>::infinity();
  for (const subsurface::DipoleProfile& p : material.channels) {
    r_max = std::max(r_max, p.radius_for_tail(1e-4));
    r_min = std::min(r_min, p.z_r());
  }
  std::vector<double> radii(kFitSamples);
  for (int s = 0; s < kFitSamples; ++s) radii[s] = r_max * (s + 0.5) / kFitSamples;
  std::array<std::vector<double>, 3> targets;
  std::array<double, 3> norms{};
  for (int c = 0; c < 3; ++c) {
    for (double r : radii) targets[c].push_back(r * material.channels[c].profile(r));
    for (double y : targets[c]) norms[c] += y * y;
    norms[c] = std::sqrt(norms[c]);
  }
  GaussianSum best;
  double best_score = std::numeric_limits<double>::infinity();
  // v_0 from (r_min/8)² up by factors of 2; q from 2 to 8 (the series must reach r_max²/9).
  for (double v0 = r_min * r_min / 64; v0 < r_max * r_max / 9; v0 *= 2) {
    for (double q = 2.0; q <= 8.0; q *= std::sqrt(2.0)) {
      std::vector<double> variances(count);
      for (int i = 0; i < count; ++i) variances[i] = v0 * std::pow(q, i);
      GaussianSum candidate;
      candidate.variances = variances;
      candidate.weights.assign(count, {0, 0, 0});
      double score = 0;
      for (int c = 0; c < 3; ++c) {
        std::vector<double> w;
        const double residual = fit_gaussian_weights(radii, targets[c], variances, w);
        for (int i = 0; i < count; ++i) candidate.weights[i][c] = w[i];
        candidate.relative_residual[c] = residual / norms[c];
        score += candidate.relative_residual[c];
      }
      if (score < best_score) {
        best_score = score;
        best = candidate;
      }
    }
  }
  for (int c = 0; c < 3; ++c) {
    best.fitted_total[c] = best.total(c);
    const double scale =
        best.fitted_total[c] > 0 ? material.channels[c].total() / best.fitted_total[c] : 0.0;
    for (auto& w : best.weights) w[c] *= scale;
  }
  return best;
}

}  // namespace prt::bake
