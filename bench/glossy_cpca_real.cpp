// glossy_cpca_real — CPCA (prt/glossy/cpca_transfer.h) on a REAL glossy bake (a .prtg from prt bake
// --glossy): for each clusters × vectors setting,
//   * bytes per vertex of the compressed matrices (CpcaTransfer::payload_bytes) and of the
//     whole .prtq (with its source section), against the .prtg;
//   * the relative RMS matrix error;
//   * the relit error: relative RMS over every vertex and RGB of the exit radiance computed by
//     prt::GlossyRelighter — the path `prt relight` takes — from the .prtq (CpcaKernel) against
//     the .prtg (GlossyKernel), with the file's own materials, under light probes of
//     ../shared/data/probes projected to the file's order, toward three eye points around the
//     mesh (2.5 bounding radii from its centre); the worst of the 3 × 3 cases is printed;
//   * the thread CPU time of one frame on the calling thread (prepare + shade of every vertex,
//     b included): uncompressed GlossyKernel, the portable per-vertex loop, and CPCA; the
//     median of `repeats` frames.
//   * with OTHER.prtg (the same mesh baked with another --seed): the same errors between the two
//     uncompressed bakes — the Monte Carlo noise of the bake, a floor below which CPCA error is
//     not worth buying.
// Usage: [PRT_SHARED_DATA_DIR=DIR] glossy_cpca_real [--metric=matrix|relit[:FLOOR]] FILE.prtg
//        [threads=2]
//        [clusters=16,64,256] [vectors=4,8,16,32] [repeats=5] [OTHER.prtg]
// --metric=relit compresses under bake/cpca/relit_metric.h's metric (FLOOR: its floor; default: the
// plain matrix error);
// the table's matrix error stays the plain one.
// Run under `taskset -c 1` for the timings (figures in docs/GLOSSY_CPCA.md).
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bake/cpca/compressor.h"
#include "bake/cpca/relit_metric.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/glossy/relighter.h"
#include "real_bake_bench_support.h"

namespace {

using namespace prt::bench;

std::vector<prt::ShLighting> load_probes(int order) {
  std::vector<prt::ShLighting> out;
  for (const char* name : {"grace_probe.hdr", "stpeters_cross.hdr", "rnl_probe.hdr"})
    out.push_back(load_probe(name, order));
  return out;
}

std::vector<float> shade(const prt::GlossyRelighter& r, const prt::ShLighting& light,
                         const float eye[3]) {
  std::vector<float> out(3 * r.vertex_count());
  prt::GlossyFrame frame;
  if (!r.prepare(light, &frame).ok() || !r.shade(frame, eye, 0, r.vertex_count(), out.data()).ok())
    std::exit(1);
  return out;
}

// Median thread CPU milliseconds of one frame (prepare + shade of every vertex).
double frame_ms(const prt::GlossyRelighter& r, const prt::ShLighting& light, const float eye[3],
                int repeats) {
  std::vector<double> t;
  std::vector<float> out(3 * r.vertex_count());
  prt::GlossyFrame frame;
  for (int i = 0; i < repeats; ++i) {
    const double t0 = thread_seconds();
    if (!r.prepare(light, &frame).ok() ||
        !r.shade(frame, eye, 0, r.vertex_count(), out.data()).ok())
      std::exit(1);
    t.push_back(1e3 * (thread_seconds() - t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  bool relit_metric = false;
  prt::RelitMetricOptions metric_options;
  if (argc > 1 && std::string(argv[1]).rfind("--metric=", 0) == 0) {
    const std::string m = argv[1] + 9;
    if (m != "matrix" && m.rfind("relit", 0) != 0) {
      std::fprintf(stderr, "--metric: matrix, relit or relit:FLOOR, not %s\n", m.c_str());
      return 2;
    }
    relit_metric = m != "matrix";
    if (m.rfind("relit:", 0) == 0) metric_options.floor = std::atof(m.c_str() + 6);
    --argc;
    ++argv;
  }
  if (argc < 2) {
    std::fprintf(stderr,
                 "usage: glossy_cpca_real FILE.prtg [threads] [clusters] [vectors] [repeats]\n");
    return 2;
  }
  const std::string path = argv[1];
  const unsigned threads = argc > 2 ? unsigned(std::atoi(argv[2])) : 2;
  const int repeats = argc > 5 ? std::max(1, std::atoi(argv[5])) : 5;
  const prt::GlossyTransferData d = require(prt::read_glossy_transfer_file(path));
  const std::size_t n = d.vertex_count;
  const double raw = 4.0 * double(d.matrices.size()) / double(n);
  const double prtg_bytes = double(require(prt::encode_glossy_transfer_file(d, path)).size());
  const std::vector<prt::ShLighting> probes = load_probes(int(d.order));
  const std::vector<std::array<float, 3>> eyes = eye_points(d);
  const prt::GlossyRelighter full = require(prt::GlossyRelighter::create(d));
  const prt::GlossyRelighter portable = require(prt::GlossyRelighter::create(
      prt::GlossyTransferData(d), {}, prt::GlossyShadingPath::kPortable));
  std::vector<std::vector<float>> reference;
  for (const auto& light : probes)
    for (const auto& eye : eyes) reference.push_back(shade(full, light, eye.data()));
  const double t_full = frame_ms(full, probes[0], eyes[0].data(), repeats);
  const double t_portable = frame_ms(portable, probes[0], eyes[0].data(), repeats);
  std::printf(
      "%s: %zu vertices, order %u, %u channel(s), %zu material(s); matrices %.0f "
      "bytes/vertex, file %.1f bytes/vertex\n",
      path.c_str(), n, d.order, d.channels, d.materials.size(), raw, prtg_bytes / double(n));
  std::printf("frame CPU ms (median of %d): uncompressed kernel %.2f, portable loop %.2f\n\n",
              repeats, t_full, t_portable);
  if (argc > 6) {
    const prt::GlossyTransferData other = require(prt::read_glossy_transfer_file(argv[6]));
    if (other.vertex_count != n || other.matrices.size() != d.matrices.size()) {
      std::fprintf(stderr, "%s: not the same mesh and order as %s\n", argv[6], path.c_str());
      return 1;
    }
    double diff = 0, norm = 0;
    for (std::size_t e = 0; e < d.matrices.size(); ++e) {
      diff +=
          (double(other.matrices[e]) - d.matrices[e]) * (double(other.matrices[e]) - d.matrices[e]);
      norm += double(d.matrices[e]) * d.matrices[e];
    }
    const prt::GlossyRelighter r = require(prt::GlossyRelighter::create(other));
    double worst = 0, sum = 0;
    std::size_t i = 0;
    for (const auto& light : probes)
      for (const auto& eye : eyes) {
        const double e = relative_rms(shade(r, light, eye.data()), reference[i++]);
        worst = std::max(worst, e);
        sum += e;
      }
    std::printf(
        "bake noise (%s against it): matrix rel. RMS %.4f, relit rel. RMS worst %.4f "
        "(mean %.4f)\n\n",
        argv[6], std::sqrt(diff / norm), worst, sum / double(i));
  }
  std::printf(
      "| Q | K | matrix B/vertex | %% of matrices | .prtq %% of .prtg | matrix rel. RMS | "
      "relit rel. RMS worst (mean) | frame CPU ms | compress CPU s |\n"
      "|---:|---:|---:|---:|---:|---:|---|---:|---:|\n");
  for (uint32_t q : list_arg(argc > 3 ? argv[3] : "16,64,256")) {
    for (uint32_t k : list_arg(argc > 4 ? argv[4] : "4,8,16,32")) {
      prt::CpcaOptions o;
      o.clusters = q;
      o.vectors = k;
      o.threads = threads;
      if (relit_metric) o.row_metric = require(prt::cpca_relit_metric(d, metric_options));
      const std::clock_t c0 = std::clock();
      const prt::CpcaTransfer c = require(prt::cpca_compress(d, o));
      const double compress_s = double(std::clock() - c0) / CLOCKS_PER_SEC;
      const double file_bytes = double(require(prt::encode_cpca_file(c, d)).size());
      prt::GlossyTransferData geometry = d;
      geometry.matrices.clear();
      const prt::GlossyRelighter r =
          require(prt::GlossyRelighter::create_cpca(std::move(geometry), c));
      double worst = 0, sum = 0;
      std::size_t i = 0;
      for (const auto& light : probes)
        for (const auto& eye : eyes) {
          const double e = relative_rms(shade(r, light, eye.data()), reference[i++]);
          worst = std::max(worst, e);
          sum += e;
        }
      const double bytes = double(c.payload_bytes()) / double(n);
      std::printf("| %u | %u | %.1f | %.2f | %.2f | %.4f | %.4f (%.4f) | %.2f | %.1f |\n", q, k,
                  bytes, 100.0 * bytes / raw, 100.0 * file_bytes / prtg_bytes,
                  prt::cpca_relative_rms_error(c, d.matrices.data()), worst, sum / double(i),
                  frame_ms(r, probes[0], eyes[0].data(), repeats), compress_s);
      std::fflush(stdout);
    }
  }
  return 0;
}
