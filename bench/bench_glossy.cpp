// bench_glossy — one frame of glossy shading (prt/glossy/kernel.h) for 50,000 vertices at
// order 5: RGB lighting, grey transfer matrices, per-vertex b = B·y(ω_o) computed in the loop
// (frame change + SH evaluation + a 25×25 matrix–vector product, bench/glossy_bench_support.h),
// then the fused dot. Uncompressed and CPCA (64 clusters, 16 vectors; CpcaKernel::prepare
// included in every frame), AVX2 and portable paths.
// Run on one core: taskset -c 1 build/bench/bench_glossy  (figures in docs/BENCHMARKS.md).
#include <cstdio>
#include <memory>
#include <vector>

#include <benchmark/benchmark.h>

#include "bake/cpca/compressor.h"
#include "fixtures/synthetic_glossy.h"
#include "glossy_bench_support.h"
#include "prt/brdf/material.h"
#include "prt/glossy/cpca_kernel.h"
#include "prt/glossy/kernel.h"

namespace {

constexpr std::size_t kVertices = 50'000;
constexpr std::size_t kChunk = 512;  // vertices per b-then-shade step (b stays in L1/L2)
constexpr int kOrder = 5;

struct Fixture {
  prt::GlossyTransferData data;
  prt::GlossyKernel glossy;
  prt::CpcaKernel cpca;
  std::vector<float> bmat;
  prt::ShLighting light;
  float eye[3] = {0.5f, 3.0f, 7.0f};
};

const Fixture& fixture() {
  static const std::unique_ptr<Fixture> f = [] {
    auto x = std::make_unique<Fixture>();
    x->data = prt::fixtures::synthetic_glossy(kVertices, kOrder, 1, 256);
    x->glossy = std::move(prt::GlossyKernel::create(x->data).value());
    prt::CpcaOptions o;
    o.clusters = 64;
    o.vectors = 16;
    o.threads = 2;
    const prt::CpcaTransfer c = prt::cpca_compress(x->data, o).value();
    std::fprintf(stderr, "CPCA: %u clusters, %u vectors, %.1f bytes/vertex, rel. RMS %.4f\n",
                 c.cluster_count, c.vector_count, double(c.payload_bytes()) / kVertices,
                 prt::cpca_relative_rms_error(c, x->data.matrices.data()));
    x->cpca = std::move(prt::CpcaKernel::create(c).value());
    prt::brdf::Material m;
    m.model = prt::brdf::MaterialModel::kMicrofacet;
    m.diffuse = prt::brdf::grey(0.3);
    m.specular = prt::brdf::grey(0.04);
    m.alpha_x = m.alpha_y = 0.3;
    x->bmat = prt::bench::brdf_sh_matrix(*prt::brdf::make_brdf(m).value(), kOrder, 16);
    std::vector<double> l(3 * kOrder * kOrder);
    for (std::size_t i = 0; i < l.size(); ++i) l[i] = 1.0 / (1.0 + double(i % 25));
    x->light = prt::ShLighting::from_coefficients(kOrder, l.data()).value();
    return x;
  }();
  return *f;
}

void BM_GlossyB(benchmark::State& state) {
  const Fixture& f = fixture();
  std::vector<float> b(kChunk * 25);
  for (auto _ : state) {
    for (std::size_t first = 0; first < kVertices; first += kChunk) {
      const std::size_t n = std::min(kChunk, kVertices - first);
      prt::bench::compute_b(f.bmat, kOrder, f.data, f.eye, first, n, b.data());
      benchmark::DoNotOptimize(b.data());
    }
  }
}

void BM_GlossyUncompressed(benchmark::State& state) {
  const Fixture& f = fixture();
  const auto path = static_cast<prt::KernelPath>(state.range(0));
  std::vector<float> b(kChunk * 25), out(3 * kVertices);
  for (auto _ : state) {
    for (std::size_t first = 0; first < kVertices; first += kChunk) {
      const std::size_t n = std::min(kChunk, kVertices - first);
      prt::bench::compute_b(f.bmat, kOrder, f.data, f.eye, first, n, b.data());
      if (!f.glossy.shade_using(path, f.light, b.data(), 1, first, n, &out[3 * first]).ok()) {
        state.SkipWithError("shade failed");
        return;
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
}

void BM_GlossyCpca(benchmark::State& state) {
  const Fixture& f = fixture();
  const auto path = static_cast<prt::KernelPath>(state.range(0));
  std::vector<float> b(kChunk * 25), out(3 * kVertices);
  prt::CpcaFrame frame;
  for (auto _ : state) {
    if (!f.cpca.prepare(f.light, &frame).ok()) {
      state.SkipWithError("prepare failed");
      return;
    }
    for (std::size_t first = 0; first < kVertices; first += kChunk) {
      const std::size_t n = std::min(kChunk, kVertices - first);
      prt::bench::compute_b(f.bmat, kOrder, f.data, f.eye, first, n, b.data());
      if (!f.cpca.shade_using(path, frame, b.data(), 1, first, n, &out[3 * first]).ok()) {
        state.SkipWithError("shade failed");
        return;
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
}

void BM_CpcaPrepare(benchmark::State& state) {
  const Fixture& f = fixture();
  prt::CpcaFrame frame;
  for (auto _ : state) {
    if (!f.cpca.prepare(f.light, &frame).ok()) state.SkipWithError("prepare failed");
    benchmark::DoNotOptimize(frame.projected.data());
  }
}

constexpr int kAvx2 = static_cast<int>(prt::KernelPath::Avx2);
constexpr int kPortable = static_cast<int>(prt::KernelPath::Portable);

}  // namespace

BENCHMARK(BM_GlossyB)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlossyUncompressed)->Arg(kAvx2)->Arg(kPortable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_GlossyCpca)->Arg(kAvx2)->Arg(kPortable)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CpcaPrepare)->Unit(benchmark::kMillisecond);
BENCHMARK_MAIN();
