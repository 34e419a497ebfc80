// report/src/vertex_estimator.cpp — the per-vertex Monte Carlo passes of
// report/vertex_estimator.h.
#include "report/vertex_estimator.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bake/progress.h"
#include "bake/transfer_baker.h"

namespace prt::report {

using Clock = std::chrono::steady_clock;

struct VertexEstimator::State {
  VertexEstimatorOptions options;
  VertexSampler sampler;
  std::size_t vertex_count;
  // Per vertex: Σ x_c and Σ x_c² over its samples (c = R, G, B).
  std::vector<double> sum, sum_squares;
  uint64_t rays = 0;
  double seconds = 0;
};

void VertexEstimator::check_options(std::size_t vertex_count, const VertexEstimatorOptions& o,
                                    const std::string& what) {
  if (o.initial_samples < 1 || o.max_samples < o.initial_samples || !(o.target_relative_se > 0))
    throw bake::BakeError(what +
                          " needs 1 <= initial_samples <= max_samples and a positive target");
  for (uint32_t v : o.vertices)
    if (v >= vertex_count)
      throw bake::BakeError(what + ": vertex " + std::to_string(v) + " is out of range");
}

VertexEstimator::VertexEstimator(std::size_t vertex_count, const VertexEstimatorOptions& options,
                                 VertexSampler sampler, const std::string& what) {
  check_options(vertex_count, options, what);
  if (!sampler.sample || sampler.vertex_block == 0)
    throw bake::BakeError(what + ": no per-sample function");
  state_ = std::make_unique<State>(State{options, std::move(sampler), vertex_count,
                                         std::vector<double>(3 * vertex_count, 0.0),
                                         std::vector<double>(3 * vertex_count, 0.0)});
}

VertexEstimator::~VertexEstimator() = default;

void VertexEstimator::add_samples_up_to(int total, ProgressSink* progress) {
  if (total <= samples_) return;
  State& st = *state_;
  const auto t0 = Clock::now();
  std::optional<tbb::global_control> limit;
  if (st.options.threads > 0)
    limit.emplace(tbb::global_control::max_allowed_parallelism, st.options.threads);
  const std::vector<uint32_t>& subset = st.options.vertices;
  const std::size_t V = subset.empty() ? st.vertex_count : subset.size();
  const std::size_t block = st.sampler.vertex_block;
  const int first = samples_;
  if (progress)
    progress->start(st.sampler.label + " " + std::to_string(total) + " samples/vertex", V);
  std::atomic<uint64_t> pass_rays{0};
  tbb::parallel_for(std::size_t(0), (V + block - 1) / block, [&](std::size_t blk) {
    const std::size_t begin = blk * block, end = std::min(V, begin + block);
    uint64_t block_rays = 0;
    for (std::size_t i_v = begin; i_v < end; ++i_v) {
      const std::size_t v = subset.empty() ? i_v : subset[i_v];
      double s[3] = {0, 0, 0}, s2[3] = {0, 0, 0};
      for (int i = first; i < total; ++i) {
        double x[3];
        block_rays += st.sampler.sample(static_cast<uint32_t>(v), static_cast<uint64_t>(i), x);
        for (int c = 0; c < 3; ++c) s[c] += x[c], s2[c] += x[c] * x[c];
      }
      for (int c = 0; c < 3; ++c) st.sum[3 * v + c] += s[c], st.sum_squares[3 * v + c] += s2[c];
    }
    pass_rays += block_rays;
    if (progress) progress->advance(end - begin, block_rays);
  });
  if (progress) progress->finish();
  samples_ = total;
  st.rays += pass_rays.load();
  st.seconds += std::chrono::duration<double>(Clock::now() - t0).count();
}

void VertexEstimator::refine(double target, ProgressSink* progress, double budget_seconds) {
  state_->options.target_relative_se = target;
  if (samples_ == 0) add_samples_up_to(state_->options.initial_samples, progress);
  while (result().relative_rms_se > target &&
         static_cast<int64_t>(samples_) * 2 <= state_->options.max_samples &&
         state_->seconds * 2.0 <= budget_seconds)
    add_samples_up_to(samples_ * 2, progress);
}

GroundTruthResult VertexEstimator::result() const {
  const State& st = *state_;
  GroundTruthResult r;
  const std::size_t n = st.sum.size();
  r.radiance.assign(n, 0.0);
  r.standard_error.assign(n, 0.0);
  r.samples_per_vertex = samples_;
  r.rays = st.rays;
  r.seconds = st.seconds;
  r.skipped_texels = st.sampler.skipped_texels;
  r.target_relative_se = st.options.target_relative_se;
  if (samples_ == 0) return r;
  const double N = samples_;
  double se2 = 0, b2 = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double mean = st.sum[i] / N;
    const double var =
        samples_ > 1 ? std::max(0.0, (st.sum_squares[i] - N * mean * mean) / (N - 1)) : 0.0;
    r.radiance[i] = mean;
    r.standard_error[i] = std::sqrt(var / N);
    se2 += var / N;
    b2 += mean * mean;
  }
  r.relative_rms_se = b2 > 0 ? std::sqrt(se2 / b2) : (se2 > 0 ? INFINITY : 0.0);
  r.reached_target = r.relative_rms_se <= r.target_relative_se;
  return r;
}

}  // namespace prt::report
