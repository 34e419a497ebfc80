// report/vertex_estimator.h — per-vertex Monte Carlo estimation with refinement: the sample
// bookkeeping every per-vertex ground truth shares (report/ground_truth.h,
// report/glossy_ground_truth.h). A ground truth supplies the per-sample function (one
// independent RGB estimate of its quantity at a vertex); the estimator runs it over the vertices
// in parallel passes, keeps per-vertex sums and sums of squares, and doubles the samples until
// the relative standard error reaches a target, a sample cap or a time budget.
//
// Standard error: every sample is an independent estimate of the vertex's value X_p (RGB);
// SE_p,c = the sample standard deviation / √N (N − 1 in the variance). The summary statistic is
// the relative RMS standard error
//     s = √(Σ_p Σ_c SE_p,c²) / √(Σ_p Σ_c X_p,c²)
// over the integrated vertices (∞ when every mean is 0 but not every SE; 0 when all are 0).
// Determinism: the estimator calls the per-sample function with (vertex, sample index) only and
// adds each vertex's samples of a pass in index order, so with a per-sample function that draws
// its random numbers from (seed, vertex, index) alone, the result is bit-identical for any thread
// count; another grouping of the same samples into passes changes the sums by rounding only.
// Errors: bad options throw BakeError naming the estimate.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace prt::bake {
class ProgressSink;
}  // namespace prt::bake

namespace prt::report {

using bake::ProgressSink;

// The sampling schedule of a per-vertex ground truth.
struct VertexEstimatorOptions {
  int initial_samples = 64;          // samples per vertex of the first pass
  int max_samples = 1 << 16;         // refine() stops doubling here
  double target_relative_se = 0.01;  // refine() target for s (see header)
  uint64_t seed = 1;                 // the per-sample function's random numbers derive from it
  int threads = 0;                   // 0 = all hardware threads
  // Only these vertices are integrated (empty: all). The others keep value and standard error
  // 0, so s covers the subset; a spot check of a large scene costs what the subset costs.
  std::vector<uint32_t> vertices;
};

struct GroundTruthResult {
  std::vector<double> radiance;        // 3 per vertex: the estimated value (RGB)
  std::vector<double> standard_error;  // 3 per vertex: its SE per channel
  int samples_per_vertex = 0;
  double relative_rms_se = 0;  // s of the header
  double target_relative_se = 0;
  bool reached_target = false;
  uint64_t rays = 0;            // total rays cast so far (as the per-sample function counts them)
  double seconds = 0;           // wall time of all passes so far
  uint64_t skipped_texels = 0;  // NaN, Inf or negative texels of the map (treated as black)

  double mrays_per_second() const {
    return seconds > 0 ? static_cast<double>(rays) / seconds * 1e-6 : 0.0;
  }
};

// What a ground truth plugs into the estimator.
struct VertexSampler {
  // One independent estimate of vertex v's value (sample `index`) into out (RGB); returns the
  // rays it cast. Called concurrently for different vertices: must be thread-safe.
  std::function<uint32_t(uint32_t v, uint64_t index, double out[3])> sample;
  std::string label;              // names the progress phase, e.g. "ground truth"
  std::size_t vertex_block = 32;  // vertices per parallel task
  uint64_t skipped_texels = 0;    // reported in every result
};

// The sampler whose per-sample function is paths->sample_vertex(v, index, out) (const,
// thread-safe); the sampler keeps `paths` alive.
template <class Paths>
VertexSampler make_vertex_sampler(std::shared_ptr<const Paths> paths, std::string label,
                                  std::size_t vertex_block, uint64_t skipped_texels) {
  VertexSampler sampler;
  sampler.sample = [paths](uint32_t v, uint64_t index, double out[3]) {
    return paths->sample_vertex(v, index, out);
  };
  sampler.label = std::move(label);
  sampler.vertex_block = vertex_block;
  sampler.skipped_texels = skipped_texels;
  return sampler;
}

class VertexEstimator {
 public:
  // Estimates over `vertex_count` vertices (or options.vertices). Throws BakeError for bad
  // options (check_options) or a sampler without a sample function.
  VertexEstimator(std::size_t vertex_count, const VertexEstimatorOptions& options,
                  VertexSampler sampler, const std::string& what);
  ~VertexEstimator();
  VertexEstimator(const VertexEstimator&) = delete;
  VertexEstimator& operator=(const VertexEstimator&) = delete;

  // Throws BakeError ("WHAT needs ...", "WHAT: vertex N is out of range"; `what` names the
  // scene and the estimate) unless 1 <= initial_samples <= max_samples, the target is positive
  // and every listed vertex is below vertex_count.
  static void check_options(std::size_t vertex_count, const VertexEstimatorOptions& options,
                            const std::string& what);

  // Adds samples until every integrated vertex has `total_samples` (no-op when it has that many
  // already).
  void add_samples_up_to(int total_samples, ProgressSink* progress = nullptr);
  // Sets the target, takes the first pass (initial_samples) if none was taken, then doubles the
  // samples per vertex until s ≤ target_relative_se, the next pass would exceed max_samples, or
  // it would end after `budget_seconds` of passes in all (a pass costs about all passes before
  // it, so the next is taken only while twice the time so far is within the budget).
  void refine(double target_relative_se, ProgressSink* progress = nullptr,
              double budget_seconds = std::numeric_limits<double>::infinity());

  GroundTruthResult result() const;
  int samples_per_vertex() const { return samples_; }

 private:
  struct State;
  std::unique_ptr<State> state_;
  int samples_ = 0;
};

}  // namespace prt::report
