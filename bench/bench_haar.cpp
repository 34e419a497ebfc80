// Benchmarks of the Haar-wavelet (all-frequency) runtime: sparse relighting and transforms.
//
// Relighting: 50k vertices, RGB transfer quantised to 16 bits, N = 32 (6·32² = 6144 wavelet
// indices), K = 200 lighting terms chosen non-linearly (area-weighted) from a synthetic sky +
// sun. Synthetic transfer sparsity: every vertex keeps each wavelet index with probability
// 7.5% ("uniform"), or additionally keeps all of levels ≤ 1 (q < 16 on every face, as real
// transfer tends to: "coarse_dense", the harder case for the lists the lighting picks).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "numerics/rng.h"
#include "prt/haar/approximation.h"
#include "prt/haar/relighter.h"

namespace {

constexpr int kSize = 32;
constexpr int64_t kVertices = 50000;
constexpr int kTerms = 200;

using Rng = prt::numerics::SplitMix64;

prt::HaarTransfer make_synthetic_transfer(bool coarse_dense) {
  prt::HaarTransferBuilder builder(kSize, 3, prt::HaarQuantization::Bits16);
  Rng rng{1};
  const uint32_t n2 = kSize * kSize, total = 6 * n2;
  prt::SparseVertexTransfer v;
  for (int64_t vertex = 0; vertex < kVertices; ++vertex) {
    v.index.clear();
    v.values.clear();
    for (uint32_t i = 0; i < total; ++i) {
      const bool coarse = (i % n2) < 16;
      if (!(coarse_dense && coarse) && rng.uniform() >= 0.075) continue;
      v.index.push_back(i);
      for (int c = 0; c < 3; ++c) v.values.push_back(static_cast<float>(rng.uniform() - 0.3));
    }
    if (!builder.add_vertex(v).ok()) std::abort();
  }
  return std::move(*builder.finish());
}

prt::SparseLighting make_lighting(int64_t terms) {
  // Sky gradient (brighter towards +Y) plus a 1-texel sun.
  prt::CubeMap cube = prt::make_black_cube_map(kSize);
  for (int face = 0; face < 6; ++face)
    for (int row = 0; row < kSize; ++row)
      for (int col = 0; col < kSize; ++col) {
        double d[3];
        prt::cube_texel_direction(kSize, face, col, row, d);
        float* px = &cube.rgb[3 * ((static_cast<size_t>(face) * kSize + row) * kSize + col)];
        const float sky = static_cast<float>(0.2 + 0.8 * std::max(0.0, d[1]));
        px[0] = 0.6f * sky;
        px[1] = 0.8f * sky;
        px[2] = sky;
      }
  float* sun = &cube.rgb[3 * ((static_cast<size_t>(2) * kSize + 9) * kSize + 20)];
  sun[0] = sun[1] = sun[2] = 5000.0f;
  return prt::select_nonlinear(*prt::transform_cube(cube), terms);
}

// Arg 0: uniform / coarse_dense data; arg 1: 0 = HaarRelighter::shade (vertex-blocked, dense
// columns), 1 = prt::shade_index_lists (the plain per-index list walk it replaced).
void BM_HaarRelight(benchmark::State& state) {
  const bool coarse_dense = state.range(0) != 0;
  const bool lists = state.range(1) != 0;
  static const prt::HaarRelighter* relighters[2] = {nullptr, nullptr};
  if (!relighters[coarse_dense]) {
    relighters[coarse_dense] = new prt::HaarRelighter(make_synthetic_transfer(coarse_dense));
  }
  const prt::HaarRelighter& relighter = *relighters[coarse_dense];
  const prt::SparseLighting lighting = make_lighting(kTerms);
  uint64_t touched = 0;
  for (uint32_t i : lighting.index)
    touched += relighter.transfer().offsets[i + 1] - relighter.transfer().offsets[i];
  std::vector<float> out(3 * kVertices);
  for (auto _ : state) {
    const prt::Status s = lists ? prt::shade_index_lists(relighter.transfer(), lighting, out.data())
                                : relighter.shade(lighting, out.data());
    if (!s.ok()) state.SkipWithError("shade failed");
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetLabel(std::string(coarse_dense ? "coarse_dense" : "uniform") +
                 (lists ? " lists" : " blocked"));
  state.counters["entries_touched"] = static_cast<double>(touched);
  state.counters["entries_stored"] = static_cast<double>(relighter.transfer().entry_count());
  state.counters["stored_MB"] = static_cast<double>(relighter.transfer().stored_bytes()) / 1e6;
  state.counters["blocked_MB"] = static_cast<double>(relighter.blocked_bytes()) / 1e6;
  state.counters["dense_MB"] = static_cast<double>(relighter.transfer().dense_bytes()) / 1e6;
  state.counters["entries/s"] = benchmark::Counter(static_cast<double>(touched),
                                                   benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_HaarRelight)
    ->Args({0, 0})
    ->Args({0, 1})
    ->Args({1, 0})
    ->Args({1, 1})
    ->Unit(benchmark::kMillisecond);

prt::CubeMap make_random_cube(int n) {
  prt::CubeMap cube = prt::make_black_cube_map(n);
  Rng rng{12345};
  for (float& v : cube.rgb) v = static_cast<float>(rng.uniform());
  return cube;
}

// Forward transform of a whole RGB cube (6 faces × 3 channels), including the copy.
void BM_HaarTransformCube(benchmark::State& state) {
  const prt::CubeMap cube = make_random_cube(static_cast<int>(state.range(0)));
  for (auto _ : state) {
    prt::Result<prt::WaveletCube> w = prt::transform_cube(cube);
    benchmark::DoNotOptimize(w);
  }
}
BENCHMARK(BM_HaarTransformCube)->Arg(32)->Arg(128)->Unit(benchmark::kMicrosecond);

// The same, in place on one channel of all six faces (the per-vertex transfer case).
void BM_HaarForwardInPlace(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  prt::CubeMap cube = make_random_cube(n);
  std::vector<float> grey(6 * static_cast<size_t>(n) * n);
  for (size_t i = 0; i < grey.size(); ++i) grey[i] = cube.rgb[3 * i];
  for (auto _ : state) {
    for (int f = 0; f < 6; ++f) prt::forward_haar_2d(grey.data() + f * n * n, n);
    benchmark::ClobberMemory();
  }
}
BENCHMARK(BM_HaarForwardInPlace)->Arg(32)->Arg(128)->Unit(benchmark::kMicrosecond);

// Non-linear selection of K = 200 from a 6×32² cube.
void BM_HaarSelectNonlinear(benchmark::State& state) {
  const prt::WaveletCube w = *prt::transform_cube(make_random_cube(kSize));
  for (auto _ : state) {
    prt::SparseLighting s = prt::select_nonlinear(w, kTerms);
    benchmark::DoNotOptimize(s);
  }
}
BENCHMARK(BM_HaarSelectNonlinear)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
