#include "radiosity/solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace prt::radiosity {
namespace {

double channel_sum(const glm::dvec3& v) {
  return v.x + v.y + v.z;
}

double emitted_power(const std::vector<Patch>& patches) {
  double total = 0.0;
  for (const Patch& p : patches) total += p.area * channel_sum(p.emission);
  return total;
}

// Checks one step: no residual below −rounding, unshot power not above the previous step's.
class EnergyMonitor {
 public:
  explicit EnergyMonitor(double emitted) : emitted_(emitted) {}
  void step(double unshot, double most_negative, std::size_t step_index) {
    const double slack = 1e-9 * emitted_ + 1e-300;
    if (most_negative < -slack)
      throw std::logic_error("radiosity: a residual went negative at step " +
                             std::to_string(step_index) + " (the solver overshot)");
    if (unshot > previous_ * (1.0 + 1e-9) + slack)
      throw std::logic_error("radiosity: unshot power grew at step " + std::to_string(step_index) +
                             " (" + std::to_string(previous_) + " → " + std::to_string(unshot) +
                             "): energy was created");
    previous_ = unshot;
  }

 private:
  double emitted_;
  double previous_ = 1e300;
};

// K_ji = A_i F_ij / A_j, row j contiguous (float, like F).
std::vector<float> gather_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f) {
  const std::size_t n = f.size;
  std::vector<float> k(n * n, 0.f);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
    if (!(patches[j].area > 0.0)) return;
    for (std::size_t i = 0; i < n; ++i)
      k[j * n + i] = static_cast<float>(patches[i].area * double(f.f[i * n + j]) / patches[j].area);
  });
  return k;
}

glm::dvec3 gather(const std::vector<float>& k, std::size_t n, std::size_t j,
                  const std::vector<glm::dvec3>& radiance) {
  glm::dvec3 sum(0.0);
  const float* row = &k[j * n];
  for (std::size_t i = 0; i < n; ++i)
    if (row[i] != 0.f) sum += double(row[i]) * radiance[i];
  return sum;
}

// Residual r = E + ρKL − L: returns the unshot power Σ A Σ_c r and the most negative r.
std::pair<double, double> residual(const std::vector<Patch>& patches, const std::vector<float>& k,
                                   const std::vector<glm::dvec3>& radiance) {
  const std::size_t n = patches.size();
  std::vector<glm::dvec3> r(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
    r[j] = patches[j].emission + patches[j].albedo * gather(k, n, j, radiance) - radiance[j];
  });
  double unshot = 0.0, most_negative = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    unshot += patches[j].area * channel_sum(r[j]);
    most_negative = std::min({most_negative, patches[j].area * r[j].x, patches[j].area * r[j].y,
                              patches[j].area * r[j].z});
  }
  return {unshot, most_negative};
}

void sweep(const std::vector<Patch>& patches, const std::vector<float>& k, SolverKind kind,
           std::vector<glm::dvec3>* radiance) {
  const std::size_t n = patches.size();
  if (kind == SolverKind::GaussSeidel) {
    for (std::size_t j = 0; j < n; ++j)
      (*radiance)[j] = patches[j].emission + patches[j].albedo * gather(k, n, j, *radiance);
    return;
  }
  std::vector<glm::dvec3> next(n);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t j) {
    next[j] = patches[j].emission + patches[j].albedo * gather(k, n, j, *radiance);
  });
  radiance->swap(next);
}

// Ambient radiance of [25] for the unshot radiance `unshot`.
glm::dvec3 ambient(const std::vector<Patch>& patches, const std::vector<glm::dvec3>& unshot) {
  glm::dvec3 weighted(0.0), albedo(0.0);
  double area = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    weighted += patches[i].area * unshot[i];
    albedo += patches[i].area * patches[i].albedo;
    area += patches[i].area;
  }
  if (!(area > 0.0)) return glm::dvec3(0.0);
  glm::dvec3 out(0.0);
  for (int c = 0; c < 3; ++c)
    if (albedo[c] / area < 1.0) out[c] = weighted[c] / area / (1.0 - albedo[c] / area);
  return out;
}

// Computes the missing row of `shooter` and, in parallel with it, those of the next patches by
// unshot power that have none yet (they are likely to shoot soon). A row does not depend on
// which others are computed, so the result does not depend on the batch or the thread count.
std::size_t compute_rows(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                         const FormFactorOptions& ff_options, const std::vector<glm::dvec3>& unshot,
                         std::size_t shooter, std::vector<std::vector<float>>* rows) {
  constexpr std::size_t kBatch = 16;
  std::vector<std::pair<double, std::size_t>> waiting;
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (i != shooter && (*rows)[i].empty() && channel_sum(unshot[i]) > 0.0)
      waiting.emplace_back(-patches[i].area * channel_sum(unshot[i]), i);
  const std::size_t extra = std::min(kBatch - 1, waiting.size());
  std::partial_sort(waiting.begin(), waiting.begin() + static_cast<std::ptrdiff_t>(extra),
                    waiting.end());
  std::vector<std::size_t> batch{shooter};
  for (std::size_t k = 0; k < extra; ++k) batch.push_back(waiting[k].second);
  tbb::parallel_for(std::size_t(0), batch.size(), [&](std::size_t k) {
    form_factor_row(patches, caster, static_cast<uint32_t>(batch[k]), ff_options,
                    &(*rows)[batch[k]]);
  });
  return batch.size();
}

}  // namespace

double EnergyAccount::balance_error() const {
  double worst = 0.0;
  for (int c = 0; c < 3; ++c)
    if (emitted[c] > 0.0)
      worst =
          std::max(worst, std::abs(emitted[c] - absorbed[c] - escaped[c] - unshot[c]) / emitted[c]);
  return worst;
}

EnergyAccount energy_account(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                             const std::vector<glm::dvec3>& radiance) {
  const std::size_t n = patches.size();
  EnergyAccount account;
  std::vector<glm::dvec3> arrived(n, glm::dvec3(0.0));
  for (std::size_t i = 0; i < n; ++i) {
    const glm::dvec3 leaving = patches[i].area * radiance[i];
    account.emitted += patches[i].area * patches[i].emission;
    account.escaped += leaving * (1.0 - f.row_sum(i));
    for (std::size_t j = 0; j < n; ++j)
      if (f.f[i * n + j] != 0.f) arrived[j] += double(f.f[i * n + j]) * leaving;
  }
  for (std::size_t j = 0; j < n; ++j) {
    account.absorbed += (glm::dvec3(1.0) - patches[j].albedo) * arrived[j];
    // r_j = E_j + ρ_j·arrived_j/A_j − L_j, weighted by A_j
    account.unshot +=
        patches[j].area * (patches[j].emission - radiance[j]) + patches[j].albedo * arrived[j];
  }
  return account;
}

Solution solve_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                      const SolveOptions& options) {
  if (options.solver == SolverKind::Progressive || f.size != patches.size())
    throw std::invalid_argument("solve_matrix: Gauss–Seidel or Jacobi on a matching matrix");
  const std::vector<float> k = gather_matrix(patches, f);
  const double emitted = emitted_power(patches);
  Solution s;
  s.radiance.resize(patches.size());
  for (std::size_t i = 0; i < patches.size(); ++i) s.radiance[i] = patches[i].emission;
  EnergyMonitor monitor(emitted);
  for (;;) {
    const auto [unshot, most_negative] = residual(patches, k, s.radiance);
    monitor.step(unshot, most_negative, s.iterations);
    s.relative_unshot = emitted > 0.0 ? unshot / emitted : 0.0;
    s.unshot_history.push_back(s.relative_unshot);
    if (s.relative_unshot <= options.tolerance) {
      s.converged = true;
      break;
    }
    if (s.iterations >= options.max_iterations) break;
    sweep(patches, k, options.solver, &s.radiance);
    ++s.iterations;
  }
  s.display_radiance = s.radiance;
  s.energy = energy_account(patches, f, s.radiance);
  return s;
}

Solution solve_progressive(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                           const FormFactorOptions& ff_options, const SolveOptions& options) {
  const std::size_t n = patches.size();
  const double emitted = emitted_power(patches);
  Solution s;
  s.radiance.resize(n);
  std::vector<glm::dvec3> unshot(n);
  for (std::size_t i = 0; i < n; ++i) {
    s.radiance[i] = unshot[i] = patches[i].emission;
    s.energy.emitted += patches[i].area * patches[i].emission;
  }
  std::vector<std::vector<float>> rows(n);
  std::vector<double> row_sums(n, -1.0);  // −1: not summed yet
  EnergyMonitor monitor(emitted);
  for (;;) {
    double total = 0.0, best = -1.0;
    std::size_t shooter = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double power = patches[i].area * channel_sum(unshot[i]);
      total += power;
      if (power > best) best = power, shooter = i;
    }
    monitor.step(total, 0.0, s.iterations);
    s.relative_unshot = emitted > 0.0 ? total / emitted : 0.0;
    s.unshot_history.push_back(s.relative_unshot);
    if (s.relative_unshot <= options.tolerance) {
      s.converged = true;
      break;
    }
    if (s.iterations >= options.max_iterations) break;
    if (rows[shooter].empty())
      s.rows_computed += compute_rows(patches, caster, ff_options, unshot, shooter, &rows);
    if (row_sums[shooter] < 0.0) {
      row_sums[shooter] = 0.0;
      for (float v : rows[shooter]) row_sums[shooter] += v;
    }
    const glm::dvec3 power = patches[shooter].area * unshot[shooter];
    unshot[shooter] = glm::dvec3(0.0);
    s.energy.escaped += power * (1.0 - row_sums[shooter]);
    const std::vector<float>& row = rows[shooter];
    for (std::size_t j = 0; j < n; ++j) {
      if (row[j] == 0.f) continue;
      const glm::dvec3 arrived = double(row[j]) * power;
      s.energy.absorbed += (glm::dvec3(1.0) - patches[j].albedo) * arrived;
      const glm::dvec3 reflected = patches[j].albedo * arrived / patches[j].area;
      unshot[j] += reflected;
      s.radiance[j] += reflected;
    }
    ++s.iterations;
  }
  for (std::size_t i = 0; i < n; ++i) s.energy.unshot += patches[i].area * unshot[i];
  const glm::dvec3 l_ambient = ambient(patches, unshot);
  s.display_radiance.resize(n);
  for (std::size_t i = 0; i < n; ++i)
    s.display_radiance[i] = s.radiance[i] + patches[i].albedo * l_ambient;
  return s;
}

}  // namespace prt::radiosity
