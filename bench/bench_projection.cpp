// Environment projection benchmarks: a 1024×512 lat-long map projected to orders 3, 10, 200 and
// 1000 by the separable path (prt::sh::project) and to orders 3, 10 and 40 by the direct texel
// sum (prt::sh::project_direct), the change of polar axis alone (sh/polar_axis.h) at orders 200
// and 1024, plus a 1000×1000 angular map (direct sum with exact edge-integral solid angles).
// Results and the command line: docs/BENCHMARKS.md, "## Environment projection".
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "sh/env_map.h"
#include "sh/polar_axis.h"
#include "sh/projection.h"

namespace {

prt::sh::EnvMap make_random_map(prt::sh::EnvLayout layout, int width, int height) {
  prt::sh::EnvMap env;
  env.layout = layout;
  env.width = width;
  env.height = height;
  env.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> uniform(0.0f, 4.0f);
  for (float& value : env.rgb) value = uniform(random);
  return env;
}

const prt::sh::EnvMap& latlong_map() {
  static const prt::sh::EnvMap env = make_random_map(prt::sh::EnvLayout::LatLong, 1024, 512);
  return env;
}

void BM_ProjectLatLongSeparable(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(prt::sh::project(latlong_map(), order));
  state.SetItemsProcessed(state.iterations() * 1024 * 512);
}
BENCHMARK(BM_ProjectLatLongSeparable)
    ->Arg(3)
    ->Arg(10)
    ->Arg(200)
    ->Arg(1000)
    ->Unit(benchmark::kMillisecond);

void BM_ProjectLatLongDirect(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(prt::sh::project_direct(latlong_map(), order));
  state.SetItemsProcessed(state.iterations() * 1024 * 512);
}
BENCHMARK(BM_ProjectLatLongDirect)->Arg(3)->Arg(10)->Arg(40)->Unit(benchmark::kMillisecond);

void BM_PolarAxisChange(benchmark::State& state) {
  const int order = static_cast<int>(state.range(0));
  const std::size_t n = 3 * static_cast<std::size_t>(order) * order;
  std::vector<double> in(n, 0.5), out(n);
  for (auto _ : state) {
    prt::sh::polar_y_to_z(order, 3, in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
  }
}
BENCHMARK(BM_PolarAxisChange)->Arg(200)->Arg(1024)->Unit(benchmark::kMillisecond);

void BM_ProjectAngularDirect(benchmark::State& state) {
  static const prt::sh::EnvMap env = make_random_map(prt::sh::EnvLayout::Angular, 1000, 1000);
  for (auto _ : state) benchmark::DoNotOptimize(prt::sh::project(env, 3));
}
BENCHMARK(BM_ProjectAngularDirect)->Unit(benchmark::kMillisecond);

void BM_AngularSolidAngles(benchmark::State& state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(prt::sh::texel_solid_angles(prt::sh::EnvLayout::Angular, 1000, 1000));
}
BENCHMARK(BM_AngularSolidAngles)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
