// glossy_cpca_rd — the rate–distortion curve of CPCA (prt/glossy/cpca_transfer.h) on glossy
// transfer: bytes per vertex of the compressed form against
//   * the relative RMS matrix error, and
//   * the relit error: relative RMS over visible vertices and RGB of the exit radiance
//     Σ_i b_i L'_i (double references of prt/glossy/kernel.h), CPCA against uncompressed,
//     under light probes of ../shared/data/probes projected to SH order 5.
// Matrices: fixtures/synthetic_glossy.h (shadowed transfer of an analytic scene; no
// baker). BRDF: GGX α = 0.3, Schlick F0 = 0.04, plus a Lambert layer 0.3 (grey b).
// Usage: [PRT_SHARED_DATA_DIR=DIR] glossy_cpca_rd [vertices=20000] [threads=2]
//        [clusters=16,64,256] [vectors=2,4,8,16,24,32]
// (figures in docs/GLOSSY_CPCA.md)
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bake/cpca/compressor.h"
#include "fixtures/synthetic_glossy.h"
#include "glossy_bench_support.h"
#include "prt/brdf/material.h"
#include "prt/glossy/kernel.h"
#include "prt/glossy/reference.h"
#include "relight/image_io.h"

namespace {

struct Probe {
  std::string name;
  prt::ShLighting light;
};

// ../shared/data beside the checkout, or $PRT_SHARED_DATA_DIR.
std::string shared_data_dir() {
  const char* env = std::getenv("PRT_SHARED_DATA_DIR");
  return env != nullptr ? env : PRT_SHARED_DATA_DIR;
}

std::vector<Probe> load_probes() {
  std::vector<Probe> probes;
  for (const char* name : {"grace_probe.hdr", "stpeters_cross.hdr", "rnl_probe.hdr"}) {
    const std::string path = shared_data_dir() + "/probes/" + name;
    try {
      const prt::sh::EnvMap map = prt::relight::read_environment(path, std::nullopt);
      auto light = prt::ShLighting::from_env_map(map, 5);
      if (light.ok()) probes.push_back({name, *light});
    } catch (const std::exception& e) {
      std::fprintf(stderr, "skipping %s: %s\n", path.c_str(), e.what());
    }
  }
  return probes;
}

// Exit radiance of every vertex facing the eye (3 doubles each; others stay 0), from the
// uncompressed matrices or (cpca != null) from the CPCA form.
std::vector<double> exit_radiance(const prt::GlossyTransferData& d, const prt::CpcaTransfer* cpca,
                                  const prt::ShLighting& light, const std::vector<float>& b,
                                  const std::vector<char>& visible) {
  std::vector<double> e(3 * d.vertex_count, 0.0);
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    if (!visible[v]) continue;
    const float* bv = b.data() + v * 25;
    prt::Status s = cpca ? prt::cpca_shade_reference(*cpca, light, bv, 1, v, &e[3 * v])
                         : prt::glossy_shade_reference(d, light, bv, 1, v, &e[3 * v]);
    if (!s.ok()) {
      std::fprintf(stderr, "%s\n", s.message().c_str());
      std::exit(1);
    }
  }
  return e;
}

// "1,2,3" -> {1, 2, 3}.
std::vector<uint32_t> list_arg(const char* text) {
  std::vector<uint32_t> out;
  for (const char* p = text; *p != 0;) {
    char* end = nullptr;
    out.push_back(static_cast<uint32_t>(std::strtoul(p, &end, 10)));
    p = *end == ',' ? end + 1 : end;
    if (end == p && *p != 0) break;
  }
  return out;
}

double relative_rms(const std::vector<double>& a, const std::vector<double>& ref) {
  double err = 0, norm = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    err += (a[i] - ref[i]) * (a[i] - ref[i]);
    norm += ref[i] * ref[i];
  }
  return std::sqrt(err / norm);
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoul(argv[1], nullptr, 10) : 20000;
  const unsigned threads = argc > 2 ? static_cast<unsigned>(std::atoi(argv[2])) : 2;
  auto t0 = std::chrono::steady_clock::now();
  const prt::GlossyTransferData d = prt::fixtures::synthetic_glossy(n, 5, 1, 1024);
  auto seconds = [](auto a) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
  };
  std::printf("synthetic matrices: %zu vertices, order 5, grey, %.1f s\n", n, seconds(t0));
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kMicrofacet;
  m.diffuse = prt::brdf::grey(0.3);
  m.specular = prt::brdf::grey(0.04);
  m.alpha_x = m.alpha_y = 0.3;
  auto brdf = prt::brdf::make_brdf(m);
  if (!brdf.ok()) {
    std::fprintf(stderr, "%s\n", brdf.status().message().c_str());
    return 1;
  }
  const std::vector<float> bmat = prt::bench::brdf_sh_matrix(**brdf, 5, 24);
  const float eye[3] = {0.5f, 3.0f, 7.0f};
  std::vector<float> b(n * 25);
  prt::bench::compute_b(bmat, 5, d, eye, 0, n, b.data());
  std::vector<char> visible(n);
  for (std::size_t v = 0; v < n; ++v) {
    const float* p = &d.positions[3 * v];
    const float* nv = &d.normals[3 * v];
    visible[v] = (eye[0] - p[0]) * nv[0] + (eye[1] - p[1]) * nv[1] + (eye[2] - p[2]) * nv[2] > 0;
  }
  const std::vector<Probe> probes = load_probes();
  if (probes.empty()) {
    std::fprintf(stderr, "no light probes under %s/probes\n", shared_data_dir().c_str());
    return 1;
  }
  std::vector<std::vector<double>> reference;
  for (const Probe& p : probes) reference.push_back(exit_radiance(d, nullptr, p.light, b, visible));
  const double raw_bytes = 4.0 * 625;
  std::printf("uncompressed: %.0f bytes/vertex\n\n", raw_bytes);
  std::printf("| clusters | K | bytes/vertex | %% of raw | matrix rel. RMS | relit rel. RMS (");
  for (const Probe& p : probes)
    std::printf("%s%s", p.name.c_str(), &p == &probes.back() ? "" : ", ");
  std::printf(") | compress s |\n|---|---|---|---|---|---|---|\n");
  for (uint32_t clusters : list_arg(argc > 3 ? argv[3] : "16,64,256")) {
    for (uint32_t k : list_arg(argc > 4 ? argv[4] : "2,4,8,16,24,32")) {
      prt::CpcaOptions o;
      o.clusters = clusters;
      o.vectors = k;
      o.threads = threads;
      auto t1 = std::chrono::steady_clock::now();
      auto c = prt::cpca_compress(d, o);
      const double secs = seconds(t1);
      if (!c.ok()) {
        std::fprintf(stderr, "%s\n", c.status().message().c_str());
        return 1;
      }
      const double bytes = static_cast<double>(c->payload_bytes()) / static_cast<double>(n);
      std::printf("| %u | %u | %.1f | %.1f | %.4f | ", clusters, k, bytes,
                  100.0 * bytes / raw_bytes, prt::cpca_relative_rms_error(*c, d.matrices.data()));
      for (std::size_t i = 0; i < probes.size(); ++i) {
        const double e =
            relative_rms(exit_radiance(d, &*c, probes[i].light, b, visible), reference[i]);
        std::printf("%.4f%s", e, i + 1 == probes.size() ? "" : ", ");
      }
      std::printf(" | %.1f |\n", secs);
      std::fflush(stdout);
    }
  }
  return 0;
}
