// bake/adaptive/sample_allocation.h — how many samples each vertex gets so that the relative RMS
// sampling error over the whole scene meets a budget at the least total cost.
//
// Model (i.i.d. Monte Carlo, conservative for the baker's scrambled Sobol' points): vertex v's
// estimate has error variance a_v² / n_v with n_v samples, a_v = its weighted standard deviation
// (bake/transfer_baker.h: albedo × lighting-weighted occlusion spread). The scene's squared
// error is Σ_v a_v² / n_v, to be ≤ budget. Minimising the cost Σ_v n_v under that constraint
// (Lagrange) gives n_v ∝ a_v — Neyman allocation (J. Neyman, "On the two different aspects of
// the representative method", J. Roy. Stat. Soc. 97(4), 1934), here with per-vertex bounds
// n_min ≤ n_v ≤ n_max: n_v = clamp(λ·a_v, n_min, n_max) with the smallest λ that meets the
// budget (bisection; the error is non-increasing in λ). Against a per-vertex stop rule that
// gives every vertex the same standard error (n_v ∝ a_v²), this spends less on the few
// high-variance vertices that dominate the cost and whose error the RMS shares with all others.
// References: [15] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

namespace prt::bake {

struct SampleAllocation {
  std::vector<uint32_t> samples;  // n_v, multiples of `packet`
  double predicted_error2 = 0;    // Σ a_v² / n_v with those counts
  bool budget_met = false;        // false: every vertex at n_max and still over budget
};

// a: per-vertex standard deviations (≥ 0); vertices with n_max == 0 are not sampled (n_v = 0).
// n_min[v] ≤ n_max[v]; both multiples of `packet`. budget: the allowed Σ a_v² / n_v (> 0).
// cost (optional, one per vertex, > 0): the cost of one sample of v; the cost Σ c_v·n_v is then
// minimised instead of Σ n_v, which gives n_v ∝ a_v/√c_v (the same Lagrange argument).
SampleAllocation allocate_samples(const std::vector<double>& a, const std::vector<uint32_t>& n_min,
                                  const std::vector<uint32_t>& n_max, double budget,
                                  uint32_t packet, const std::vector<double>& cost = {});

}  // namespace prt::bake
