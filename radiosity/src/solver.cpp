#include "radiosity/solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#include <immintrin.h>
#endif

#include "large_buffer.h"

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

// Patch radiance in three channel arrays, so that a row of K meets contiguous doubles.
struct Channels {
  std::vector<double> c[3];
  explicit Channels(const std::vector<glm::dvec3>& v) {
    for (int k = 0; k < 3; ++k) {
      c[k].resize(v.size());
      for (std::size_t i = 0; i < v.size(); ++i) c[k][i] = v[i][k];
    }
  }
  glm::dvec3 at(std::size_t i) const { return {c[0][i], c[1][i], c[2][i]}; }
  void set(std::size_t i, const glm::dvec3& v) {
    for (int k = 0; k < 3; ++k) c[k][i] = v[k];
  }
};

// out[j] = Σ_i K_ji L_i for rows [begin, end): four interleaved partial sums per channel (lane
// l adds the products of i ≡ l mod 4), added as (s0 + s1) + (s2 + s3) at the end. The AVX2
// version (four doubles per instruction, chosen at run time) does exactly these operations in
// this order, multiply then add (no fused multiply-add; the build is ISO C++, no contraction),
// so both give bit-identical sums.
void gather_rows_portable(const float* k, std::size_t n, std::size_t begin, std::size_t end,
                          const double* r, const double* g, const double* b, glm::dvec3* out) {
  for (std::size_t j = begin; j != end; ++j) {
    const float* __restrict row = k + j * n;
    double s0[4] = {0, 0, 0, 0}, s1[4] = {0, 0, 0, 0}, s2[4] = {0, 0, 0, 0};
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4)
      for (int l = 0; l < 4; ++l) {
        const double w = row[i + l];
        s0[l] += w * r[i + l];
        s1[l] += w * g[i + l];
        s2[l] += w * b[i + l];
      }
    for (int l = 0; i < n; ++i, ++l) {
      const double w = row[i];
      s0[l] += w * r[i];
      s1[l] += w * g[i];
      s2[l] += w * b[i];
    }
    out[j - begin] =
        glm::dvec3((s0[0] + s0[1]) + (s0[2] + s0[3]), (s1[0] + s1[1]) + (s1[2] + s1[3]),
                   (s2[0] + s2[1]) + (s2[2] + s2[3]));
  }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
__attribute__((target("avx2"))) void gather_rows_avx2(const float* k, std::size_t n,
                                                      std::size_t begin, std::size_t end,
                                                      const double* r, const double* g,
                                                      const double* b, glm::dvec3* out) {
  for (std::size_t j = begin; j != end; ++j) {
    const float* row = k + j * n;
    __m256d s0 = _mm256_setzero_pd(), s1 = _mm256_setzero_pd(), s2 = _mm256_setzero_pd();
    std::size_t i = 0;
    for (; i + 4 <= n; i += 4) {
      const __m256d w = _mm256_cvtps_pd(_mm_loadu_ps(row + i));
      s0 = _mm256_add_pd(s0, _mm256_mul_pd(w, _mm256_loadu_pd(r + i)));
      s1 = _mm256_add_pd(s1, _mm256_mul_pd(w, _mm256_loadu_pd(g + i)));
      s2 = _mm256_add_pd(s2, _mm256_mul_pd(w, _mm256_loadu_pd(b + i)));
    }
    alignas(32) double t0[4], t1[4], t2[4];
    _mm256_store_pd(t0, s0);
    _mm256_store_pd(t1, s1);
    _mm256_store_pd(t2, s2);
    for (int l = 0; i < n; ++i, ++l) {
      const double w = row[i];
      t0[l] += w * r[i];
      t1[l] += w * g[i];
      t2[l] += w * b[i];
    }
    out[j - begin] =
        glm::dvec3((t0[0] + t0[1]) + (t0[2] + t0[3]), (t1[0] + t1[1]) + (t1[2] + t1[3]),
                   (t2[0] + t2[1]) + (t2[2] + t2[3]));
  }
}
#endif

void gather_rows(const float* k, std::size_t n, std::size_t begin, std::size_t end, const double* r,
                 const double* g, const double* b, glm::dvec3* out) {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) return gather_rows_avx2(k, n, begin, end, r, g, b, out);
#endif
  gather_rows_portable(k, n, begin, end, r, g, b, out);
}

glm::dvec3 gather(const GatherMatrix& k, std::size_t j, const Channels& l) {
  glm::dvec3 out;
  gather_rows(k.k.data(), k.size, j, j + 1, l.c[0].data(), l.c[1].data(), l.c[2].data(), &out);
  return out;
}

// g = K·L, rows in parallel (each row by one thread: independent of the thread count).
std::vector<glm::dvec3> gather_all(const GatherMatrix& k, const Channels& l) {
  std::vector<glm::dvec3> g(k.size);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, k.size, 16),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      gather_rows(k.k.data(), k.size, range.begin(), range.end(), l.c[0].data(),
                                  l.c[1].data(), l.c[2].data(), &g[range.begin()]);
                    });
  return g;
}

// The residual of L given g = K·L: its unshot power Σ A Σ_c r, the most negative A·r, and the
// energy account under K.
struct Evaluation {
  double unshot = 0.0, most_negative = 0.0;
  EnergyAccount account;
};

Evaluation evaluate(const std::vector<Patch>& patches, const GatherMatrix& k,
                    const std::vector<glm::dvec3>& radiance, const std::vector<glm::dvec3>& g) {
  Evaluation e;
  for (std::size_t j = 0; j < patches.size(); ++j) {
    const Patch& p = patches[j];
    const glm::dvec3 r = p.emission + p.albedo * g[j] - radiance[j];
    e.unshot += p.area * channel_sum(r);
    e.most_negative = std::min({e.most_negative, p.area * r.x, p.area * r.y, p.area * r.z});
    const glm::dvec3 arrived = p.area * g[j];
    e.account.emitted += p.area * p.emission;
    e.account.escaped += p.area * radiance[j] * (1.0 - k.out[j]);
    e.account.absorbed += (glm::dvec3(1.0) - p.albedo) * arrived;
    e.account.unshot += p.area * (p.emission - radiance[j]) + p.albedo * arrived;
  }
  return e;
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

GatherMatrix make_gather_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f) {
  if (f.size != patches.size())
    throw std::invalid_argument("make_gather_matrix: one form-factor row per patch needed");
  const std::size_t n = f.size;
  GatherMatrix k;
  k.size = n;
  detail::assign_zeroed_large(&k.k, n * n);
  k.out.assign(n, 0.0);
  // Transposed in 64 × 64 tiles so that both F and K are read and written in cache lines.
  constexpr std::size_t kTile = 64;
  tbb::parallel_for(std::size_t(0), (n + kTile - 1) / kTile, [&](std::size_t tile) {
    const std::size_t j0 = tile * kTile, j1 = std::min(n, j0 + kTile);
    for (std::size_t i0 = 0; i0 < n; i0 += kTile) {
      const std::size_t i1 = std::min(n, i0 + kTile);
      for (std::size_t j = j0; j < j1; ++j) {
        if (!(patches[j].area > 0.0)) continue;
        for (std::size_t i = i0; i < i1; ++i)
          k.k[j * n + i] =
              static_cast<float>(patches[i].area * double(f.f[i * n + j]) / patches[j].area);
      }
    }
  });
  // out_i = Σ_j A_j K_ji / A_i, summed over j in order; blocks of i in parallel, each reading
  // its slice of every row of K.
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 1024),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t j = 0; j < n; ++j) {
                        const float* row = &k.k[j * n];
                        for (std::size_t i = range.begin(); i != range.end(); ++i)
                          k.out[i] += patches[j].area * double(row[i]);
                      }
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        k.out[i] = patches[i].area > 0.0 ? k.out[i] / patches[i].area : 0.0;
                    });
  return k;
}

Solution solve_matrix(const std::vector<Patch>& patches, const GatherMatrix& k,
                      const SolveOptions& options) {
  if (options.solver == SolverKind::Progressive || k.size != patches.size())
    throw std::invalid_argument("solve_matrix: Gauss–Seidel or Jacobi on a matching matrix");
  const std::size_t n = patches.size();
  const double emitted = emitted_power(patches);
  Solution s;
  s.radiance.resize(n);
  for (std::size_t i = 0; i < n; ++i) s.radiance[i] = patches[i].emission;
  Channels l(s.radiance);
  EnergyMonitor monitor(emitted);
  for (;;) {
    const std::vector<glm::dvec3> g = gather_all(k, l);
    const Evaluation e = evaluate(patches, k, s.radiance, g);
    monitor.step(e.unshot, e.most_negative, s.iterations);
    s.relative_unshot = emitted > 0.0 ? e.unshot / emitted : 0.0;
    s.unshot_history.push_back(s.relative_unshot);
    s.energy = e.account;
    if (s.relative_unshot <= options.tolerance) {
      s.converged = true;
      break;
    }
    if (s.iterations >= options.max_iterations) break;
    if (options.solver == SolverKind::Jacobi) {
      for (std::size_t j = 0; j < n; ++j) {
        s.radiance[j] = patches[j].emission + patches[j].albedo * g[j];
        l.set(j, s.radiance[j]);
      }
    } else {
      for (std::size_t j = 0; j < n; ++j) {
        s.radiance[j] = patches[j].emission + patches[j].albedo * gather(k, j, l);
        l.set(j, s.radiance[j]);
      }
    }
    ++s.iterations;
  }
  s.display_radiance = s.radiance;
  return s;
}

Solution solve_matrix(const std::vector<Patch>& patches, const FormFactorMatrix& f,
                      const SolveOptions& options) {
  if (options.solver == SolverKind::Progressive || f.size != patches.size())
    throw std::invalid_argument("solve_matrix: Gauss–Seidel or Jacobi on a matching matrix");
  return solve_matrix(patches, make_gather_matrix(patches, f), options);
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
