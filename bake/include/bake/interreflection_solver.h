// bake/interreflection_solver.h — the diffuse interreflection system of Sloan, Kautz & Snyder,
// "Precomputed Radiance Transfer for Real-Time Rendering in Dynamic, Low-Frequency Lighting
// Environments", SIGGRAPH 2002, §6 (interreflected transfer), solved per colour channel c:
//
//     (I − diag(ρ_c) H) T_c = D_c
//
// T_c, D_c: V × K blocks (V vertices, K = order² SH coefficients), vertex-major (row v holds
// the K coefficients of vertex v). D = shadowed (direct) transfer, which already includes the
// receiver's albedo/π. H is the sparse "gather" matrix built by the baker: row p holds, for
// every cosine-distributed sample ray of p that hits a front face, the hit triangle's vertex
// indices with weights b_i / N (Embree barycentrics over N samples), duplicates merged.
// Row sums of H are the hit fraction of p, ≤ 1, so with ρ_max < 1 the max-norm of ρH is ≤ ρ_max
// and the Neumann series (Jacobi bounces) contracts by at least ρ_max per bounce.
//
// Memory: CSR, 4-byte column + 4-byte weight = 8 bytes per stored entry (≤ 3 per hit ray before
// merging), plus 8 bytes per row. The Krylov solver holds 7 V × K double blocks.
// Determinism: row-parallel mat-vecs; dot products reduce fixed 512-row blocks in block order,
// so results are bit-identical for any thread count.
// References: [2], [16] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

namespace prt {
class MemoryBudget;
}  // namespace prt

namespace prt::bake {

class ProgressSink;

// Compressed sparse rows of H (see above).
struct SparseTransferMatrix {
  std::vector<uint64_t> row_offsets{0};  // rows + 1 entries
  std::vector<uint32_t> columns;
  std::vector<float> weights;

  std::size_t rows() const { return row_offsets.size() - 1; }
  std::size_t entries() const { return columns.size(); }
  std::size_t bytes() const {
    return row_offsets.size() * sizeof(uint64_t) + columns.size() * sizeof(uint32_t) +
           weights.size() * sizeof(float);
  }
};

struct SolveOptions {
  int bounces = -1;           // ≥ 0: exactly that many Jacobi bounces; −1: Krylov to tolerance
  double tolerance = 1e-4;    // relative residual target of the Krylov solve
  int warmup_bounces = 3;     // Jacobi bounces that seed the Krylov solve
  int max_iterations = 2000;  // BiCGSTAB iteration cap (per channel)
  // `t` already holds an iterate (for example the end of a bounce loop): no copy of D, no
  // warm-up; BiCGSTAB starts from it.
  bool start_from_t = false;
  // solve_by_bounces: the bounce the gather reads held in binary16 (apply_half) instead of float.
  bool half_bounces = false;
};

struct SolveReport {
  int jacobi_bounces = 0;     // Jacobi bounces run (explicit or warm-up)
  int krylov_iterations = 0;  // BiCGSTAB iterations (0 for explicit bounces)
  double relative_residual = 0;  // max over columns of ‖D − A T‖₂ / ‖D‖₂ (see .cpp for floor)
  bool converged = true;  // false when the iteration cap was hit first
  // Max-norm of the radiance each Jacobi bounce adds, ‖(ρH)^i D‖_max, i = 1 .. bounces.
  std::vector<double> bounce_energy;
};

// Columns [first, first + count) of H, renumbered from 0 (H with the albedo kept apart holds one
// V-column block per colour channel, bake/transfer_baker.h).
SparseTransferMatrix column_block(const SparseTransferMatrix& h, uint64_t first, uint64_t count);

// y = diag(rho) · H · x for V × K blocks (rho has V entries).
void multiply_gather(const SparseTransferMatrix& h, const std::vector<double>& rho, const double* x,
                     int columns, double* y);

// y = diag(ρ)·H·x for V × K blocks, whatever stores H (CSR here, bake/compact_gather.h).
class GatherOperator {
 public:
  virtual ~GatherOperator() = default;
  virtual std::size_t rows() const = 0;
  virtual void apply(const double* x, int columns, double* y) const = 0;
  // Row stride, in elements, of the x and y blocks of apply_float and apply_half (≥ columns; a
  // row's entries past `columns` are padding: not read in x, not written in y).
  virtual std::size_t bounce_stride(int columns) const { return static_cast<std::size_t>(columns); }
  // The same with x and y in float (sums still in double); by default through apply().
  virtual void apply_float(const float* x, int columns, float* y) const;
  // The same with x and y in binary16 (prt/core/half.h; sums in double, each y rounded to the
  // nearest half once); by default through apply_float().
  virtual void apply_half(const uint16_t* x, int columns, uint16_t* y) const;
};

// The CSR matrix with its row albedo (multiply_gather).
class CsrGatherOperator final : public GatherOperator {
 public:
  CsrGatherOperator(const SparseTransferMatrix& h, const std::vector<double>& rho)
      : h_(h), rho_(rho) {}
  std::size_t rows() const override { return h_.rows(); }
  void apply(const double* x, int columns, double* y) const override {
    multiply_gather(h_, rho_, x, columns, y);
  }

 private:
  const SparseTransferMatrix& h_;
  const std::vector<double>& rho_;
};

// Solves (I − A) T = D for one channel, A = diag(ρ)H given as an operator; `t` (V × K)
// receives the solution (and holds the starting iterate with SolveOptions::start_from_t).
SolveReport solve_interreflection(const GatherOperator& a, const double* d, int columns, double* t,
                                  const SolveOptions& options, ProgressSink* progress = nullptr);

// Neumann bounces in bounded memory: T = Σ_{i ≤ n} A^i D, A = diag(ρ)H with ‖A‖_max ≤ q < 1
// (q: the largest ρ_p·(row sum of H)_p, CompactGather::max_weighted_row_sum). The residual
// D − (I − A)T_n is A^{n+1}D, so its max-norm is ≤ e_n·q, e_n = ‖A^n D‖_max, and the error
// ‖T_n − T‖_max ≤ e_n·q/(1 − q). options.bounces ≥ 0 runs exactly that many bounces; −1 bounces
// until the residual bound e_n·q ≤ options.tolerance·‖D‖_max (the max-norm form of the Krylov
// solve's relative residual): at most log(tol)/log q bounces whatever V is, one pass over H
// each. Stiff systems (more than max_bounces bounces) finish with BiCGSTAB from the bounce
// iterate (its 9 V × K blocks charged to `budget` first when it is not null). fill_direct(block)
// writes D (V × K) into a block; `t` receives the solution. Holds T (double) and the current and
// next bounce in float (apply_float: each bounce rounded to float, 2^-24 relative; T sums them
// in double), rows a.bounce_stride(K) apart, 64-byte aligned: 8 + 2·4·stride/K bytes per
// coefficient. With options.half_bounces the two bounces are binary16 (apply_half: each bounce
// rounded to half, ≤ 2^-11 relative, or 2^-25 absolute below 2^-14; docs/BENCHMARKS.md derives
// the bound on T): 8 + 2·2·stride/K bytes; it throws std::domain_error when ‖D‖_max exceeds the
// largest half (65504; the bounces only shrink: ‖A‖_max ≤ q < 1). The report's relative_residual
// is the bound e_n·q/‖D‖_max (after BiCGSTAB: its own 2-norm residual).
SolveReport solve_by_bounces(const GatherOperator& a, double q,
                             const std::function<void(double*)>& fill_direct, int columns,
                             double* t, const SolveOptions& options, int max_bounces,
                             MemoryBudget* budget, ProgressSink* progress = nullptr);

// Solves (I − diag(rho) H) T = D for one channel; `t` (V × K) receives the solution.
SolveReport solve_interreflection(const SparseTransferMatrix& h, const std::vector<double>& rho,
                                  const double* d, int columns, double* t,
                                  const SolveOptions& options, ProgressSink* progress = nullptr);

}  // namespace prt::bake
