// bench_relight — the runtime relighting kernel (prt/diffuse/relighter.h) against memcpy bandwidth,
// per-frame lighting work (projection + rotation at order 5), and the file checksum.
// Run on one core: taskset -c 1 ./bench_relight  (figures in docs/BENCHMARKS.md).
#include <chrono>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "prt/diffuse/relighter.h"
#include "prt/formats/crc32c.h"
#include "prt/lighting/sh_lighting.h"
#include "sh/rotation.h"

namespace {

constexpr std::size_t kVertices = 1'000'000;
constexpr int kOrder = 5;
constexpr int kChannels = 3;

prt::Relighter make_relighter(prt::Precision storage) {
  prt::TransferData d;
  d.order = kOrder;
  d.channels = kChannels;
  d.vertex_count = kVertices;
  d.coefficients.resize(kVertices * kChannels * kOrder * kOrder);
  std::mt19937 rng(1);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  for (float& x : d.coefficients) x = unit(rng);
  return std::move(prt::Relighter::create(d, storage).value());
}

prt::ShLighting make_lighting() {
  std::vector<double> c(3 * kOrder * kOrder);
  for (std::size_t i = 0; i < c.size(); ++i) c[i] = std::cos(static_cast<double>(i));
  return std::move(prt::ShLighting::from_coefficients(kOrder, c.data()).value());
}

// Best-of-5 time of memcpy of `bytes` bytes (buffers touched beforehand).
double seconds_to_copy(std::size_t bytes) {
  std::vector<unsigned char> src(bytes, 1), dst(bytes, 0);
  double best = 1e30;
  for (int i = 0; i < 5; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    std::memcpy(dst.data(), src.data(), bytes);
    benchmark::DoNotOptimize(dst.data());
    benchmark::ClobberMemory();
    const auto t1 = std::chrono::steady_clock::now();
    best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
  }
  return best;
}

// Shades all 1M vertices per iteration. Counters:
//   vertices/s; coeff_GB/s = coefficient bytes read per second;
//   copy_ratio = (time of a memcpy of the same number of coefficient bytes) / (shade time),
//   so 1.0 means shading streams the coefficients as fast as memcpy copies them.
void relight(benchmark::State& state, prt::Precision storage, prt::KernelPath path) {
  const prt::Relighter r = make_relighter(storage);
  const prt::ShLighting light = make_lighting();
  const std::size_t coeff_bytes =
      kVertices * kChannels * kOrder * kOrder * (storage == prt::Precision::F16 ? 2 : 4);
  const double copy_seconds = seconds_to_copy(coeff_bytes);
  std::vector<float> out(3 * kVertices);
  const auto start = std::chrono::steady_clock::now();
  for (auto _ : state) {
    if (!r.shade_using(path, light, 0, kVertices, out.data()).ok()) {
      state.SkipWithError("shade failed");
      break;
    }
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  const double iterations = static_cast<double>(state.iterations());
  const double shade_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() / iterations;
  state.counters["vertices/s"] =
      benchmark::Counter(iterations * kVertices, benchmark::Counter::kIsRate);
  state.counters["coeff_GB/s"] = benchmark::Counter(
      iterations * static_cast<double>(coeff_bytes) * 1e-9, benchmark::Counter::kIsRate);
  state.counters["memcpy_GB/s"] = static_cast<double>(coeff_bytes) * 1e-9 / copy_seconds;
  state.counters["copy_ratio"] = copy_seconds / shade_seconds;
}

void BM_RelightF32(benchmark::State& s) {
  relight(s, prt::Precision::F32, prt::KernelPath::Auto);
}
void BM_RelightF16(benchmark::State& s) {
  relight(s, prt::Precision::F16, prt::KernelPath::Auto);
}
void BM_RelightF32Portable(benchmark::State& s) {
  relight(s, prt::Precision::F32, prt::KernelPath::Portable);
}
void BM_RelightF16Portable(benchmark::State& s) {
  relight(s, prt::Precision::F16, prt::KernelPath::Portable);
}
BENCHMARK(BM_RelightF32)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RelightF16)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RelightF32Portable)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_RelightF16Portable)->Unit(benchmark::kMillisecond)->UseRealTime();

// Display output: shade + exposure + sRGB encode for 1M vertices (f16).
void BM_RelightRgba8F16(benchmark::State& state) {
  const prt::Relighter r = make_relighter(prt::Precision::F16);
  const prt::ShLighting light = make_lighting();
  std::vector<uint8_t> out(4 * kVertices);
  for (auto _ : state) {
    if (!r.shade_rgba8(light, 0, kVertices, 0.0f, out.data()).ok()) state.SkipWithError("fail");
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["vertices/s"] = benchmark::Counter(
      static_cast<double>(state.iterations()) * kVertices, benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RelightRgba8F16)->Unit(benchmark::kMillisecond)->UseRealTime();

// Per-frame lighting work: project a 1024×512 lat-long map to order 5, then rotate it.
std::vector<float> make_sky(int w, int h) {
  std::vector<float> p(3 * static_cast<std::size_t>(w) * h);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      for (int c = 0; c < 3; ++c) {
        p[(static_cast<std::size_t>(y) * w + x) * 3 + c] =
            static_cast<float>(1.0 + 0.5 * std::sin(0.01 * x * (c + 1)) * std::cos(0.02 * y));
      }
    }
  }
  return p;
}

void BM_ProjectLatLong1024(benchmark::State& state) {
  const std::vector<float> sky = make_sky(1024, 512);
  for (auto _ : state) {
    auto light =
        prt::ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, 1024, 512, sky.data(), kOrder);
    benchmark::DoNotOptimize(light);
  }
}
BENCHMARK(BM_ProjectLatLong1024)->Unit(benchmark::kMillisecond);

void BM_RotateOrder5(benchmark::State& state) {
  prt::ShLighting light = make_lighting();
  double yaw = 0;
  for (auto _ : state) {
    yaw += 1.0;
    (void)light.rotate(prt::sh::rotation_from_yaw_pitch_roll(yaw, 10, 0));
    benchmark::DoNotOptimize(light);
  }
}
BENCHMARK(BM_RotateOrder5)->Unit(benchmark::kMicrosecond);

void BM_ProjectAndRotate1024(benchmark::State& state) {
  const std::vector<float> sky = make_sky(1024, 512);
  double yaw = 0;
  for (auto _ : state) {
    auto light =
        prt::ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, 1024, 512, sky.data(), kOrder);
    yaw += 1.0;
    (void)light->rotate(prt::sh::rotation_from_yaw_pitch_roll(yaw, 0, 0));
    benchmark::DoNotOptimize(light);
  }
}
BENCHMARK(BM_ProjectAndRotate1024)->Unit(benchmark::kMillisecond);

// The file checksum over 64 MiB.
void crc(benchmark::State& state, bool portable) {
  std::vector<unsigned char> data(64u << 20);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = static_cast<unsigned char>(i * 131);
  for (auto _ : state) {
    const uint32_t c = portable ? prt::crc32c_portable(data.data(), data.size())
                                : prt::crc32c(data.data(), data.size());
    benchmark::DoNotOptimize(c);
  }
  state.SetBytesProcessed(static_cast<int64_t>(state.iterations()) *
                          static_cast<int64_t>(data.size()));
}
void BM_Crc32c(benchmark::State& s) {
  crc(s, false);
}
void BM_Crc32cPortable(benchmark::State& s) {
  crc(s, true);
}
BENCHMARK(BM_Crc32c)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Crc32cPortable)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
