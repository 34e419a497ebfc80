// bench/bench_sh.cpp — SH library micro-benchmarks: evaluation per direction and rotation.
// Run: taskset -c 1 build-<name>/bench/bench_sh   (results in docs/BENCHMARKS.md, "SH library")
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/rotation.h"

namespace {

constexpr int kDirections = 1024;  // power of two: index with & (kDirections − 1)

template <typename T>
std::vector<std::array<T, 3>> random_directions() {
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> u(-1.0, 1.0), a(0.0, prt::sh::kTwoPi);
  std::vector<std::array<T, 3>> d(kDirections);
  for (auto& v : d) {
    const double z = u(rng), phi = a(rng), r = std::sqrt(1.0 - z * z);
    v = {T(r * std::cos(phi)), T(r * std::sin(phi)), T(z)};
  }
  return d;
}

// One direction per iteration (so the reported time is per direction).
template <typename T>
void evaluate_per_direction(benchmark::State& state) {
  const int order = int(state.range(0));
  const auto dirs = random_directions<T>();
  std::vector<T> out(order * order);
  int i = 0;
  for (auto _ : state) {
    const auto& d = dirs[i++ & (kDirections - 1)];
    prt::sh::evaluate(order, d[0], d[1], d[2], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

void evaluate_recurrence_per_direction(benchmark::State& state) {
  const int order = int(state.range(0));
  const auto dirs = random_directions<double>();
  std::vector<double> out(order * order);
  int i = 0;
  for (auto _ : state) {
    const auto& d = dirs[i++ & (kDirections - 1)];
    prt::sh::evaluate_recurrence(order, d[0], d[1], d[2], out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

std::vector<std::array<double, 9>> random_rotations() {
  std::vector<std::array<double, 9>> r;
  for (int i = 0; i < 64; ++i) {
    r.push_back(prt::sh::rotation_from_yaw_pitch_roll(37.0 * i, 11.0 * i - 80.0, 23.0 * i));
  }
  return r;
}

// Build the band matrices from a 3×3 matrix, then rotate one coefficient vector.
void rotate_build_and_apply(benchmark::State& state) {
  const int order = int(state.range(0));
  const auto rotations = random_rotations();
  std::vector<double> in(order * order, 0.5), out(order * order);
  int i = 0;
  for (auto _ : state) {
    const prt::sh::Rotation r(order, rotations[i++ & 63]);
    r.apply(in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// The same with the plain recurrence from band 2 (no closed-form band 2): the old path.
void rotate_build_recurrence_and_apply(benchmark::State& state) {
  const int order = int(state.range(0));
  const auto rotations = random_rotations();
  std::vector<double> in(order * order, 0.5), out(order * order);
  int i = 0;
  for (auto _ : state) {
    const prt::sh::Rotation r = prt::sh::Rotation::build_with_recurrence(order, rotations[i++ & 63]);
    r.apply(in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// Apply only (band matrices built once).
void rotate_apply_only(benchmark::State& state) {
  const int order = int(state.range(0));
  const prt::sh::Rotation r(order, prt::sh::rotation_from_yaw_pitch_roll(30.0, 20.0, 10.0));
  std::vector<double> in(order * order, 0.5), out(order * order);
  for (auto _ : state) {
    r.apply(in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

// The zxzxz fast path: Euler angles from the 3×3 matrix and one coefficient vector, no matrices.
template <typename T>
void rotate_coefficients(benchmark::State& state) {
  const int order = int(state.range(0));
  const auto rotations = random_rotations();
  std::vector<T> in(order * order, T(0.5)), out(order * order);
  int i = 0;
  for (auto _ : state) {
    prt::sh::rotate_coefficients(order, rotations[i++ & 63], in.data(), out.data());
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
}

}  // namespace

BENCHMARK_TEMPLATE(evaluate_per_direction, double)->Arg(3)->Arg(5)->Arg(10);
BENCHMARK_TEMPLATE(evaluate_per_direction, float)->Arg(3)->Arg(5)->Arg(10);
BENCHMARK(evaluate_recurrence_per_direction)->Arg(5)->Arg(10)->Arg(20);
BENCHMARK(rotate_build_and_apply)->Arg(2)->Arg(3)->Arg(5)->Arg(10)->Arg(16);
BENCHMARK(rotate_build_recurrence_and_apply)->Arg(3)->Arg(5);
BENCHMARK(rotate_apply_only)->Arg(3)->Arg(5)->Arg(10);
BENCHMARK_TEMPLATE(rotate_coefficients, double)->Arg(3)->Arg(5)->Arg(10)->Arg(16);
BENCHMARK_TEMPLATE(rotate_coefficients, float)->Arg(5);

BENCHMARK_MAIN();
