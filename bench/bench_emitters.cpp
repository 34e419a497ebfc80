// bench_emitters — relighting the emitters (prt/emitters/emitter_responses.h): the per-frame cost
// of L_v = Σ_e c_e ⊙ R_e,v (new colours checked and resolved by name, then the recombination), for
// a responses file written by `prt radiosity --per-emitter`, with its emitters replicated to
// E = 1, 2, 4, 8 (the cost depends on V and E only, not on the values).
// Usage: bench_emitters FILE.prte [Google Benchmark options]  (figures in docs/BENCHMARKS.md)
#include <cstdio>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include "prt/emitters/emitter_responses.h"

namespace {

prt::EmitterResponses g_file;

prt::EmitterResponses replicate(int emitters) {
  prt::EmitterResponses d = g_file;
  const std::size_t per_emitter = 3 * d.vertex_count();
  d.emitters.clear();
  d.responses.clear();
  for (int e = 0; e < emitters; ++e) {
    d.emitters.push_back({"emitter" + std::to_string(e), {1.f, 1.f, 1.f}});
    d.responses.insert(d.responses.end(), g_file.responses.begin(),
                       g_file.responses.begin() + std::ptrdiff_t(per_emitter));
  }
  return d;
}

// One frame: every emitter gets a new colour by name, then the radiance of every vertex.
void BM_RecombineFrame(benchmark::State& state) {
  const prt::EmitterResponses d = replicate(int(state.range(0)));
  std::vector<float> out(3 * d.vertex_count());
  std::vector<prt::EmitterColor> colors;
  for (const prt::EmitterInfo& e : d.emitters) colors.push_back({e.name, {2.f, 1.f, 0.5f}});
  for (auto _ : state) {
    colors[0].rgb[0] += 1e-3f;  // a new colour every frame
    const prt::Result<std::vector<float>> c = prt::emitter_colors(d, colors);
    if (!c.ok() || !prt::recombine_emitters(d, *c, out.data()).ok()) state.SkipWithError("failed");
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.counters["vertices"] = double(d.vertex_count());
  state.SetBytesProcessed(int64_t(state.iterations()) * int64_t(4 * d.responses.size()));
}
BENCHMARK(BM_RecombineFrame)->Arg(1)->Arg(2)->Arg(4)->Arg(8)->Unit(benchmark::kMicrosecond);

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') {
    std::fprintf(stderr, "usage: bench_emitters FILE.prte [benchmark options]\n");
    return 2;
  }
  prt::Result<prt::EmitterResponses> file = prt::read_emitter_responses(argv[1]);
  if (!file.ok()) {
    std::fprintf(stderr, "bench_emitters: %s\n", file.status().message().c_str());
    return 1;
  }
  g_file = std::move(file).value();
  std::printf("%s: %zu vertices, %zu triangles, %zu emitters\n", argv[1], g_file.vertex_count(),
              g_file.triangle_count(), g_file.emitter_count());
  argv[1] = argv[0];
  benchmark::Initialize(&--argc, argv + 1);
  benchmark::RunSpecifiedBenchmarks();
  return 0;
}
