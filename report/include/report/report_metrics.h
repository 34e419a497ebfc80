// report/report_metrics.h — the error and cost statistics of `prt report`.
//
// Per-vertex error of exit radiance B (RGB, linear, the map's units) against a reference B_gt:
//   e_p = |B_p − B_gt,p|, |·| the Euclidean norm of the RGB vector.
//   relative RMS  = √(Σ_p e_p²) / √(Σ_p |B_gt,p|²)          (energy-weighted, the headline number)
//   per-vertex relative error r_p = e_p / max(|B_gt,p|, floor), floor = floor_fraction × RMS_p
//   |B_gt,p|
//     (default 5%: vertices much darker than average are judged against 5% of the average, so a
//     nearly black vertex cannot produce an unbounded ratio); p99 = the 99th percentile of r_p
//     (nearest-rank), max = its maximum.
// Image error: the same relative RMS over the pixels (RGB) inside `mask` (pixels that show the
// scene), comparing two renderings from the same camera.
// Pareto front of (cost, error) points: those no other point beats in both (≤ in both and < in
// one); ties keep the first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace prt::report {

struct VertexErrorStats {
  double relative_rms = 0;
  double p99 = 0;
  double max = 0;
  std::size_t max_vertex = 0;
};

inline constexpr double kDefaultRelativeErrorFloor = 0.05;

// b and reference: 3 values per vertex (same length). Non-finite values in b count as an error of
// +Inf (so they show up rather than vanish).
VertexErrorStats compute_vertex_errors(const std::vector<float>& b,
                                       const std::vector<double>& reference,
                                       double floor_fraction = kDefaultRelativeErrorFloor);
VertexErrorStats compute_vertex_errors(const std::vector<double>& b,
                                       const std::vector<double>& reference,
                                       double floor_fraction = kDefaultRelativeErrorFloor);

// Relative RMS of image `a` against `reference` (3 floats per pixel) over pixels where mask != 0
// (empty mask: all pixels). 0 when the reference is black there.
double relative_rms_image_error(const std::vector<float>& a, const std::vector<float>& reference,
                                const std::vector<uint8_t>& mask);

// Flags of the points on the Pareto front (minimise both); non-finite points are never on it.
std::vector<bool> pareto_front(const std::vector<double>& cost, const std::vector<double>& error);

// Index of the cheapest point with error ≤ threshold, or −1.
long cheapest_reaching(const std::vector<double>& cost, const std::vector<double>& error,
                       double threshold);

}  // namespace prt::report
