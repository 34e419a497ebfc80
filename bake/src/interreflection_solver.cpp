// bake/src/interreflection_solver.cpp — Jacobi bounces and multi-column BiCGSTAB for
// (I − diag(ρ) H) T = D (see interreflection_solver.h).
//
// BiCGSTAB: van der Vorst, "Bi-CGSTAB: A Fast and Smoothly Converging Variant of Bi-CG for the
// Solution of Nonsymmetric Linear Systems", SIAM J. Sci. Stat. Comput. 13(2), 1992. All K
// columns iterate together (one pass over H per mat-vec serves every column) with their own
// scalars; a column stops updating once it meets the tolerance. Breakdown (ρ̂ or ω ≈ 0) and
// drift of the recursive residual are handled by restarting from the current iterate with
// the true residual.
#include "bake/interreflection_solver.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake/progress.h"
#include "huge_pages.h"
#include "prt/core/half.h"
#include "prt/core/memory_budget.h"

namespace prt::bake {
namespace {

constexpr std::size_t kReduceBlock = 512;  // rows per partial sum (fixed: determinism)

using Block = std::vector<double>;  // V × K, vertex-major

// Per-column dot products Σ_v a[v,k]·b[v,k], reduced deterministically.
std::vector<double> dot_columns(const double* a, const double* b, std::size_t rows, int k) {
  const std::size_t blocks = (rows + kReduceBlock - 1) / kReduceBlock;
  std::vector<double> partial(blocks * k, 0.0);
  tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
    double* acc = &partial[blk * k];
    const std::size_t end = std::min(rows, (blk + 1) * kReduceBlock);
    for (std::size_t r = blk * kReduceBlock; r < end; ++r)
      for (int c = 0; c < k; ++c) acc[c] += a[r * k + c] * b[r * k + c];
  });
  std::vector<double> sum(k, 0.0);
  for (std::size_t blk = 0; blk < blocks; ++blk)
    for (int c = 0; c < k; ++c) sum[c] += partial[blk * k + c];
  return sum;
}

// y = x − diag(rho) H x.
void apply_system(const GatherOperator& a, const double* x, int k, double* y) {
  a.apply(x, k, y);
  const std::size_t n = a.rows() * static_cast<std::size_t>(k);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t i = r.begin(); i != r.end(); ++i) y[i] = x[i] - y[i];
                    });
}

double max_abs_of(const double* v, std::size_t n) {
  double m = 0.0;
  for (std::size_t i = 0; i < n; ++i) m = std::max(m, std::fabs(v[i]));
  return m;
}

double max_abs(const Block& v) {
  return max_abs_of(v.data(), v.size());
}

// Row-parallel elementwise update: f(row, column) over all entries.
template <class F>
void for_each_entry(std::size_t rows, int k, F&& f) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 256),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      for (std::size_t v = r.begin(); v != r.end(); ++v)
                        for (int c = 0; c < k; ++c) f(v * k + c, c);
                    });
}

}  // namespace

namespace {

// Rows [begin, end) of y = diag(rho)·H·x: the solve's hot loop (~70% of an order-12
// interreflected bake). Cloned for AVX2 where the CPU has it (4 doubles per instruction),
// chosen at load time; the default clone is the baseline x86-64 build. The build is ISO C++
// (no floating-point contraction), so every clone adds the same products in the same order:
// results are bit-identical across CPUs and thread counts (test_transfer_interreflection).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__)
__attribute__((target_clones("avx2", "default")))
#endif
void gather_rows(const uint64_t* offsets, const uint32_t* columns, const float* weights,
                 const double* rho, const double* x, int k, std::size_t begin, std::size_t end,
                 double* acc, double* y) {
  for (std::size_t v = begin; v != end; ++v) {
    for (int c = 0; c < k; ++c) acc[c] = 0.0;
    for (uint64_t e = offsets[v]; e < offsets[v + 1]; ++e) {
      const double w = weights[e];
      const double* __restrict xs = x + static_cast<std::size_t>(columns[e]) * k;
      for (int c = 0; c < k; ++c) acc[c] += w * xs[c];
    }
    double* __restrict out = y + v * k;
    for (int c = 0; c < k; ++c) out[c] = rho[v] * acc[c];
  }
}

}  // namespace

SparseTransferMatrix column_block(const SparseTransferMatrix& h, uint64_t first, uint64_t count) {
  SparseTransferMatrix out;
  out.row_offsets.reserve(h.rows() + 1);
  for (std::size_t r = 0; r < h.rows(); ++r) {
    for (uint64_t e = h.row_offsets[r]; e < h.row_offsets[r + 1]; ++e) {
      if (h.columns[e] < first || h.columns[e] - first >= count) continue;
      out.columns.push_back(static_cast<uint32_t>(h.columns[e] - first));
      out.weights.push_back(h.weights[e]);
    }
    out.row_offsets.push_back(out.columns.size());
  }
  return out;
}

void multiply_gather(const SparseTransferMatrix& h, const std::vector<double>& rho, const double* x,
                     int columns, double* y) {
  const std::size_t rows = h.rows();
  const int k = columns;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 64),
                    [&](const tbb::blocked_range<std::size_t>& r) {
                      std::vector<double> acc(k);
                      gather_rows(h.row_offsets.data(), h.columns.data(), h.weights.data(),
                                  rho.data(), x, k, r.begin(), r.end(), acc.data(), y);
                    });
}

namespace {

// Jacobi bounces: T = Σ_i (ρH)^i D, each term from the previous one (t holds D on entry).
// Progress is shown when the bounces are the whole solve (options.bounces ≥ 0).
void add_jacobi_bounces(const GatherOperator& a, const double* d, int k, int jacobi, double* t,
                        const SolveOptions& options, ProgressSink* progress, SolveReport& report) {
  const std::size_t rows = a.rows();
  const std::size_t n = rows * static_cast<std::size_t>(k);
  Block term(d, d + n), next(n);
  if (progress && options.bounces >= 0) progress->start("bounces", jacobi);
  for (int i = 0; i < jacobi; ++i) {
    a.apply(term.data(), k, next.data());
    term.swap(next);
    for_each_entry(rows, k, [&](std::size_t e, int) { t[e] += term[e]; });
    report.bounce_energy.push_back(max_abs(term));
    if (progress && options.bounces >= 0) progress->advance(1, 0);
  }
  if (progress && options.bounces >= 0) progress->finish();
  report.jacobi_bounces = jacobi;
}

// After a fixed number of bounces: the largest relative residual over the columns, each against
// max(‖D_c‖, 1e-3·max‖D‖), and whether it meets the tolerance.
void report_bounce_residual(const GatherOperator& a, const double* d, int k, const double* t,
                            double tolerance, SolveReport& report) {
  const std::size_t rows = a.rows();
  const std::size_t n = rows * static_cast<std::size_t>(k);
  Block r(n);
  apply_system(a, t, k, r.data());
  for (std::size_t e = 0; e < n; ++e) r[e] = d[e] - r[e];
  const std::vector<double> rr = dot_columns(r.data(), r.data(), rows, k);
  const std::vector<double> bb = dot_columns(d, d, rows, k);
  double bmax = 0;
  for (double b : bb) bmax = std::max(bmax, std::sqrt(b));
  for (int c = 0; c < k; ++c) {
    const double scale = std::max(std::sqrt(bb[c]), 1e-3 * bmax);
    if (scale > 0)
      report.relative_residual = std::max(report.relative_residual, std::sqrt(rr[c]) / scale);
  }
  report.converged = report.relative_residual <= tolerance;
}

// BiCGSTAB on all K columns at once, from the iterate in t (updated in place). A column's
// residual is measured against scale[c]; a column stops updating once it meets tol.
class ColumnBiCgStab {
 public:
  ColumnBiCgStab(const GatherOperator& a, const double* d, int k, double* t,
                 std::vector<double> scale, double tol)
      : a_(a),
        d_(d),
        k_(k),
        t_(t),
        rows_(a.rows()),
        n_(rows_ * static_cast<std::size_t>(k)),
        scale_(std::move(scale)),
        tol_(tol),
        r_(n_),
        rhat_(n_),
        p_(n_),
        v_(n_),
        s_(n_),
        tt_(n_),
        active_(k, 1),
        rel_(k, 0.0) {}

  // The true residual r = D − (I − ρH)T: each column's relative residual and whether it is
  // still active. True when every column meets the tolerance.
  bool true_residual() {
    const std::size_t rows = rows_;
    const int k = k_;
    apply_system(a_, t_, k, r_.data());
    for_each_entry(rows, k, [&](std::size_t e, int) { r_[e] = d_[e] - r_[e]; });
    const std::vector<double> rr = dot_columns(r_.data(), r_.data(), rows, k);
    bool all = true;
    for (int c = 0; c < k; ++c) {
      rel_[c] = std::sqrt(rr[c]) / scale_[c];
      active_[c] = rel_[c] > tol_;
      all = all && !active_[c];
    }
    return all;
  }

  // BiCGSTAB is not monotone and can diverge on stiff non-normal systems (eigenvalues of ρH
  // spread around a circle of radius ~ρ): the iterate with the smallest true residual is kept,
  // so an unconverged solve never returns worse than its Jacobi warm-up. The current iterate
  // becomes the best so far.
  void remember_as_best() {
    best_t_.assign(t_, t_ + n_);
    best_rel_ = rel_;
  }
  // Keeps the current iterate if its true residual is the smallest so far.
  void keep_best() {
    if (*std::max_element(rel_.begin(), rel_.end()) <
        *std::max_element(best_rel_.begin(), best_rel_.end())) {
      std::copy(t_, t_ + n_, best_t_.begin());
      best_rel_ = rel_;
    }
  }
  // Returns to the best iterate when it is better than the current one.
  void restore_best_if_better() {
    if (*std::max_element(best_rel_.begin(), best_rel_.end()) <
        *std::max_element(rel_.begin(), rel_.end())) {
      std::copy(best_t_.begin(), best_t_.end(), t_);
      rel_ = best_rel_;
    }
  }
  double max_relative_residual() const { return *std::max_element(rel_.begin(), rel_.end()); }

  // One run from a (re)start (r̂ = r, p = 0, v = 0, ρ = α = ω = 1) until a breakdown, every
  // column meeting the recursive residual check, or *iterations reaching max_iterations.
  void run(int max_iterations, int* iterations, ProgressSink* progress);

 private:
  const GatherOperator& a_;
  const double* const d_;
  const int k_;
  double* const t_;
  const std::size_t rows_, n_;
  const std::vector<double> scale_;
  const double tol_;
  Block r_, rhat_, p_, v_, s_, tt_;
  std::vector<char> active_;
  std::vector<double> rel_;
  Block best_t_;
  std::vector<double> best_rel_;
};

void ColumnBiCgStab::run(int max_iterations, int* iterations, ProgressSink* progress) {
  const std::size_t rows = rows_;
  const int k = k_;
  Block &r = r_, &rhat = rhat_, &p = p_, &v = v_, &s = s_, &tt = tt_;
  std::vector<char>& active = active_;
  const std::vector<double>& scale = scale_;
  double* const t = t_;
  rhat = r;
  std::fill(p.begin(), p.end(), 0.0);
  std::fill(v.begin(), v.end(), 0.0);
  std::vector<double> rho_old(k, 1.0), alpha(k, 1.0), omega(k, 1.0);
  bool restart = false;
  while (!restart && *iterations < max_iterations) {
    ++*iterations;
    const std::vector<double> rho_new = dot_columns(rhat.data(), r.data(), rows, k);
    const std::vector<double> rhat2 = dot_columns(rhat.data(), rhat.data(), rows, k);
    const std::vector<double> r2 = dot_columns(r.data(), r.data(), rows, k);
    std::vector<double> beta(k, 0.0);
    for (int c = 0; c < k; ++c) {
      if (!active[c]) continue;
      // Breakdown: r̂ nearly orthogonal to r.
      if (std::fabs(rho_new[c]) <= 1e-14 * std::sqrt(rhat2[c] * r2[c])) restart = true;
      beta[c] = (rho_new[c] / rho_old[c]) * (alpha[c] / omega[c]);
    }
    if (restart) break;
    for_each_entry(rows, k, [&](std::size_t e, int c) {
      if (active[c]) p[e] = r[e] + beta[c] * (p[e] - omega[c] * v[e]);
    });
    apply_system(a_, p.data(), k, v.data());
    const std::vector<double> rv = dot_columns(rhat.data(), v.data(), rows, k);
    for (int c = 0; c < k; ++c) {
      if (!active[c]) continue;
      if (rv[c] == 0.0) restart = true;
      alpha[c] = rv[c] != 0.0 ? rho_new[c] / rv[c] : 0.0;
    }
    for_each_entry(rows, k, [&](std::size_t e, int c) {
      if (active[c]) s[e] = r[e] - alpha[c] * v[e];
    });
    apply_system(a_, s.data(), k, tt.data());
    const std::vector<double> ts = dot_columns(tt.data(), s.data(), rows, k);
    const std::vector<double> t2 = dot_columns(tt.data(), tt.data(), rows, k);
    for (int c = 0; c < k; ++c) {
      if (!active[c]) continue;
      omega[c] = t2[c] > 0 ? ts[c] / t2[c] : 0.0;
      if (omega[c] == 0.0) restart = true;
    }
    for_each_entry(rows, k, [&](std::size_t e, int c) {
      if (!active[c]) return;
      t[e] += alpha[c] * p[e] + omega[c] * s[e];
      r[e] = s[e] - omega[c] * tt[e];
    });
    rho_old = rho_new;
    if (progress) progress->advance(1, 0);
    // Recursive residual check; confirmed with the true residual (which may restart).
    const std::vector<double> rr = dot_columns(r.data(), r.data(), rows, k);
    bool all = true;
    for (int c = 0; c < k; ++c) {
      if (active[c] && std::sqrt(rr[c]) / scale[c] <= tol_) active[c] = 0;
      all = all && !active[c];
    }
    if (all || restart) break;
  }
}

}  // namespace

SolveReport solve_interreflection(const GatherOperator& a, const double* d, int columns, double* t,
                                  const SolveOptions& options, ProgressSink* progress) {
  SolveReport report;
  const std::size_t rows = a.rows();
  const int k = columns;
  const std::size_t n = rows * static_cast<std::size_t>(k);
  if (!options.start_from_t) std::copy(d, d + n, t);
  if (n == 0) return report;

  if (!options.start_from_t) {
    const int jacobi = options.bounces >= 0 ? options.bounces : std::max(0, options.warmup_bounces);
    add_jacobi_bounces(a, d, k, jacobi, t, options, progress, report);
  }
  if (options.bounces >= 0) {
    report_bounce_residual(a, d, k, t, options.tolerance, report);
    return report;
  }

  // BiCGSTAB on all columns. A column's residual is measured against max(‖D_c‖, 1e-3·max‖D‖):
  // coefficients that are numerically zero everywhere need not converge to machine precision.
  const std::vector<double> bb = dot_columns(d, d, rows, k);
  double bmax = 0;
  for (double b : bb) bmax = std::max(bmax, std::sqrt(b));
  std::vector<double> scale(k);
  for (int c = 0; c < k; ++c) scale[c] = std::max(std::sqrt(bb[c]), 1e-3 * bmax);
  if (bmax == 0) return report;

  ColumnBiCgStab solver(a, d, k, t, std::move(scale), options.tolerance);
  int iterations = 0;
  if (progress) progress->start("solve iterations", 0);
  bool done = solver.true_residual();
  solver.remember_as_best();
  while (!done && iterations < options.max_iterations) {
    solver.run(options.max_iterations, &iterations, progress);
    done = solver.true_residual();
    solver.keep_best();
  }
  if (!done) solver.restore_best_if_better();
  if (progress) progress->finish();
  report.krylov_iterations = iterations;
  report.relative_residual = solver.max_relative_residual();
  report.converged = report.relative_residual <= options.tolerance;
  return report;
}

void GatherOperator::apply_float(const float* x, int columns, float* y) const {
  const std::size_t n = rows() * static_cast<std::size_t>(columns);
  std::vector<double> xd(x, x + n), yd(n);
  apply(xd.data(), columns, yd.data());
  for (std::size_t i = 0; i < n; ++i) y[i] = static_cast<float>(yd[i]);
}

void GatherOperator::apply_half(const uint16_t* x, int columns, uint16_t* y) const {
  const std::size_t n = rows() * bounce_stride(columns);
  std::vector<float> xf(n), yf(n);
  convert_halves_to_floats(x, n, xf.data());
  apply_float(xf.data(), columns, yf.data());
  convert_floats_to_halves(yf.data(), n, y);
}

namespace {

// A bounce block: rows `stride` elements apart, in float or binary16.
void store_row(const double* in, int k, float* out, float*) {
  for (int c = 0; c < k; ++c) out[c] = static_cast<float>(in[c]);
}
void store_row(const double* in, int k, uint16_t* out, float* scratch) {
  for (int c = 0; c < k; ++c) scratch[c] = static_cast<float>(in[c]);
  convert_floats_to_halves(scratch, static_cast<std::size_t>(k), out);
}
const float* load_row(const float* in, int, float*) {
  return in;
}
const float* load_row(const uint16_t* in, int k, float* scratch) {
  convert_halves_to_floats(in, static_cast<std::size_t>(k), scratch);
  return scratch;
}
void apply_bounce(const GatherOperator& a, const float* x, int k, float* y) {
  a.apply_float(x, k, y);
}
void apply_bounce(const GatherOperator& a, const uint16_t* x, int k, uint16_t* y) {
  a.apply_half(x, k, y);
}

// Runs the bounces of solve_by_bounces with the bounce held in T (float or binary16): adds
// them to t, returns the bound e_n·q.
template <class T>
double run_bounces(const GatherOperator& a, double q, int k, double* t, double d_max, int limit,
                   bool fixed, double tolerance, SolveReport& report, ProgressSink* progress) {
  const std::size_t rows = a.rows(), ld = a.bounce_stride(k);
  std::vector<T> term_store, next_store;  // read at random by the gather: 2 MB pages asked for
  T* term = detail::resize_huge_aligned(term_store, rows * ld, 64);
  T* next = detail::resize_huge_aligned(next_store, rows * ld, 64);
  const auto rows_loop = [&](auto&& f) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, rows, 256),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        std::vector<float> scratch(static_cast<std::size_t>(k));
                        for (std::size_t v = r.begin(); v != r.end(); ++v) f(v, scratch.data());
                      });
  };
  rows_loop(
      [&](std::size_t v, float* scratch) { store_row(t + v * k, k, term + v * ld, scratch); });
  double e = d_max, bound = e * q;
  for (int i = 0; i < limit; ++i) {
    if (!fixed && e * q <= tolerance * d_max) break;
    apply_bounce(a, term, k, next);
    std::swap(term, next);
    std::vector<double> row_max(rows, 0.0);
    rows_loop([&](std::size_t v, float* scratch) {
      const float* x = load_row(term + v * ld, k, scratch);
      double m = 0.0;
      for (int c = 0; c < k; ++c) {
        t[v * k + c] += static_cast<double>(x[c]);
        m = std::max(m, static_cast<double>(std::fabs(x[c])));
      }
      row_max[v] = m;
    });
    e = 0.0;
    for (double m : row_max) e = std::max(e, m);
    report.bounce_energy.push_back(e);
    ++report.jacobi_bounces;
    bound = e * q;
    if (progress && fixed) progress->advance(1, 0);
  }
  return bound;
}

}  // namespace

SolveReport solve_by_bounces(const GatherOperator& a, double q,
                             const std::function<void(double*)>& fill_direct, int columns,
                             double* t, const SolveOptions& options, int max_bounces,
                             MemoryBudget* budget, ProgressSink* progress) {
  SolveReport report;
  const std::size_t rows = a.rows();
  const int k = columns;
  const std::size_t n = rows * static_cast<std::size_t>(k);
  fill_direct(t);
  const double d_max = max_abs_of(t, n);
  if (n == 0 || d_max == 0.0) return report;
  if (options.half_bounces && !(d_max <= kHalfMax))
    throw std::domain_error("the direct transfer reaches " + std::to_string(d_max) +
                            ", beyond binary16's largest value 65504: bounce in f32");
  const bool fixed = options.bounces >= 0;
  const int limit = fixed ? options.bounces : max_bounces;
  if (progress && fixed) progress->start("bounces", limit);
  const double bound = options.half_bounces
                           ? run_bounces<uint16_t>(a, q, k, t, d_max, limit, fixed,
                                                   options.tolerance, report, progress)
                           : run_bounces<float>(a, q, k, t, d_max, limit, fixed, options.tolerance,
                                                report, progress);
  if (progress && fixed) progress->finish();
  report.relative_residual = bound / d_max;
  report.converged = report.relative_residual <= options.tolerance;
  if (fixed || report.converged) return report;
  // Stiff: BiCGSTAB from the bounce iterate.
  const uint64_t krylov_bytes = 9ull * n * sizeof(double);
  if (budget) budget->charge(krylov_bytes, "the Krylov solve's blocks");
  Block d(n);
  fill_direct(d.data());
  SolveOptions krylov = options;
  krylov.start_from_t = true;
  const SolveReport k_report = solve_interreflection(a, d.data(), k, t, krylov, progress);
  if (budget) budget->release(krylov_bytes);
  report.krylov_iterations = k_report.krylov_iterations;
  report.relative_residual = k_report.relative_residual;
  report.converged = k_report.converged;
  return report;
}

SolveReport solve_interreflection(const SparseTransferMatrix& h, const std::vector<double>& rho,
                                  const double* d, int columns, double* t,
                                  const SolveOptions& options, ProgressSink* progress) {
  const CsrGatherOperator a(h, rho);
  return solve_interreflection(a, d, columns, t, options, progress);
}

}  // namespace prt::bake
