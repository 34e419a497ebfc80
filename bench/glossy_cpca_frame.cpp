// glossy_cpca_frame — frame CPU time of glossy shading on a REAL bake, from files already written
// (no compression in the process, so it runs in seconds): a .prtg from `prt bake --glossy` and a
// .prtq from `prt compress` of it. For the uncompressed GlossyRelighter and for CpcaKernel with
// the first K vectors of every cluster (cpca_truncate, for each K of the list), prints the
// thread CPU milliseconds of one frame on the calling thread (prepare + shade of every vertex,
// b(ω_o) included; the median and the least of `repeats`), of CpcaKernel::prepare alone, and the
// relative RMS of the CPCA exit radiance against the uncompressed one (grace_probe at order 5, one
// eye point 2.5 bounding radii from the mesh's centre), so a change of the kernel can be checked
// for speed and accuracy at once; and the shading kernel alone through its AVX2 and AVX-512 paths
// (the frame uses KernelPath::Auto: AVX-512 where the CPU has it). Usage: [PRT_SHARED_DATA_DIR=DIR]
// glossy_cpca_frame FILE.prtg FILE.prtq [vectors=16,32,64]
//        [repeats=7]
// Run under `taskset -c 1` (figures in docs/GLOSSY_CPCA.md).
#include <time.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/glossy/cpca_kernel.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/kernel.h"
#include "prt/glossy/relighter.h"
#include "real_bake_bench_support.h"

namespace {

using namespace prt::bench;

struct Times {
  double median, min;
};

Times summary(std::vector<double> t) {
  std::sort(t.begin(), t.end());
  return {t[t.size() / 2], t[0]};
}

// Thread CPU ms of one frame (median and least of `repeats`); the last frame's exit radiance
// into out.
Times frame_ms(const prt::GlossyRelighter& r, const prt::ShLighting& light, const float eye[3],
               int repeats, std::vector<float>* out) {
  std::vector<double> t;
  out->assign(3 * r.vertex_count(), 0.f);
  prt::GlossyFrame frame;
  for (int i = 0; i < repeats; ++i) {
    const double t0 = thread_seconds();
    if (!r.prepare(light, &frame).ok() ||
        !r.shade(frame, eye, 0, r.vertex_count(), out->data()).ok())
      std::exit(1);
    t.push_back(1e3 * (thread_seconds() - t0));
  }
  return summary(t);
}

Times prepare_ms(const prt::CpcaTransfer& c, const prt::ShLighting& light, int repeats) {
  const prt::CpcaKernel k = require(prt::CpcaKernel::create(c));
  prt::CpcaFrame frame;
  std::vector<double> t;
  for (int i = 0; i < repeats; ++i) {
    const double t0 = thread_seconds();
    if (!k.prepare(light, &frame).ok()) std::exit(1);
    t.push_back(1e3 * (thread_seconds() - t0));
  }
  return summary(t);
}

// The CPCA shading kernel alone (CpcaKernel::shade_using over every vertex, grey b, the frame
// prepared once) through KernelPath::Avx2 and KernelPath::Avx512, alternating within each
// repeat so both see the same machine load; exits if the two disagree in any bit. avx512 is
// negative when the CPU lacks AVX-512F.
struct KernelTimes {
  Times avx2, avx512;
};

KernelTimes kernel_ms(const prt::CpcaTransfer& c, const prt::ShLighting& light, int repeats) {
  const prt::CpcaKernel k = require(prt::CpcaKernel::create(c));
  prt::CpcaFrame frame;
  if (!k.prepare(light, &frame).ok()) std::exit(1);
  const std::size_t n = k.vertex_count(), n2 = std::size_t(k.order()) * k.order();
  std::vector<float> b(n * n2), o2(3 * n), o512(3 * n);
  for (std::size_t i = 0; i < b.size(); ++i) b[i] = 1.0f / float(1 + i % n2);
  const bool wide = prt::CpcaKernel::avx512_path_available();
  std::vector<double> t2, t512;
  for (int i = 0; i < repeats; ++i) {
    double t0 = thread_seconds();
    if (!k.shade_using(prt::KernelPath::Avx2, frame, b.data(), 1, 0, n, o2.data()).ok())
      std::exit(1);
    t2.push_back(1e3 * (thread_seconds() - t0));
    if (!wide) continue;
    t0 = thread_seconds();
    if (!k.shade_using(prt::KernelPath::Avx512, frame, b.data(), 1, 0, n, o512.data()).ok())
      std::exit(1);
    t512.push_back(1e3 * (thread_seconds() - t0));
    if (std::memcmp(o2.data(), o512.data(), o2.size() * sizeof(float)) != 0) {
      std::fprintf(stderr, "the AVX2 and AVX-512 kernels differ\n");
      std::exit(1);
    }
  }
  return {summary(t2), wide ? summary(t512) : Times{-1, -1}};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: glossy_cpca_frame FILE.prtg FILE.prtq [vectors] [repeats]\n");
    return 2;
  }
  const prt::GlossyTransferData d = require(prt::read_glossy_transfer_file(argv[1]));
  const prt::CpcaTransfer cpca = require(prt::read_cpca_file(argv[2]));
  const std::vector<uint32_t> ks = list_arg(argc > 3 ? argv[3] : "16,32,64");
  const int repeats = argc > 4 ? std::max(1, std::atoi(argv[4])) : 7;
  const prt::ShLighting light = load_probe("grace_probe.hdr", int(d.order));
  const std::array<float, 3> first_eye = eye_points(d)[0];
  const float* eye = first_eye.data();
  const prt::GlossyRelighter full = require(prt::GlossyRelighter::create(d));
  std::vector<float> reference, out;
  const Times t_full = frame_ms(full, light, eye, repeats, &reference);
  std::printf("%s: %zu vertices, order %u; %s: %u clusters, %u vectors\n", argv[1],
              std::size_t(d.vertex_count), d.order, argv[2], cpca.cluster_count, cpca.vector_count);
  std::printf("uncompressed frame CPU ms, median (least) of %d: %.2f (%.2f)\n", repeats,
              t_full.median, t_full.min);
  std::printf(
      "| K | frame CPU ms, median (least) | prepare CPU ms, median (least) | relit rel. RMS vs "
      "uncompressed | kernel CPU ms AVX2 | kernel CPU ms AVX-512 |\n"
      "|---:|---:|---:|---:|---:|---:|\n");
  for (uint32_t k : ks) {
    if (k > cpca.vector_count) continue;
    const prt::CpcaTransfer c = prt::cpca_truncate(cpca, k);
    prt::GlossyTransferData geometry = d;
    geometry.matrices.clear();
    const prt::GlossyRelighter rel =
        require(prt::GlossyRelighter::create_cpca(std::move(geometry), c));
    const Times t = frame_ms(rel, light, eye, repeats, &out);
    const Times tp = prepare_ms(c, light, repeats);
    const KernelTimes tk = kernel_ms(c, light, repeats);
    std::printf("| %u | %.2f (%.2f) | %.2f (%.2f) | %.5f | %.2f (%.2f) | %.2f (%.2f) |\n", k,
                t.median, t.min, tp.median, tp.min, relative_rms(out, reference), tk.avx2.median,
                tk.avx2.min, tk.avx512.median, tk.avx512.min);
    std::fflush(stdout);
  }
  return 0;
}
