// bench/haar_bytes_per_vertex.cpp — bytes per vertex of Haar transfer at a given error (1% by
// default), against SH.
//
// Scene: the bunny on a ground plane of bench/haar_vs_sh.cpp (grey albedo 0.8, so one channel).
// Reference: a shadowed Haar bake at N = 32, unquantised (Float32), every term kept, relit with
// every lighting term (= the exact texel sum of the discretised transfer). Each setting
// re-truncates and re-quantises the reference's per-vertex wavelet coefficients exactly as the
// baker does (prt::truncate_vertex_coefficients, then prt::HaarTransferBuilder), so only the
// compression differs. Settings: relative threshold 0.3 … 1e-4 and top-M per vertex 16 … 1024, each
// at 8 and 16 bits. Error: relative RMS over vertices of RGB exit radiance,
//   e = √(Σ_v |B_v − B*_v|² / Σ_v |B*_v|²),
// (a) all lighting terms kept (the transfer compression alone) and (b) K = 200 non-linear
// lighting terms (what a user sees at runtime). Bytes per vertex: HaarTransfer::stored_bytes()
// / V (offsets, vertex indices 4 B/entry, values 1 or 2 B/entry, per-vertex step).
// Lights: rooitou_park_1k.hdr (unclipped sun) and the small area light of haar_vs_sh.
// Writes OUTPUT_DIR/bytes_per_vertex.csv; prints a table and the 1% crossings.
// Usage: haar_bytes_per_vertex [SHARED_DATA_DIR] [OUTPUT_DIR]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bake/haar_baker.h"
#include "haar_bench_scene.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transform.h"
#include "relight/image_io.h"
#include "report/plot_svg.h"
#include "scene/scene_loader.h"

namespace {

constexpr int kCube = 32;
constexpr int kRuntimeTerms = 200;

double relative_rms(const std::vector<float>& b, const std::vector<float>& ref) {
  double e2 = 0, r2 = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double e = double(b[i]) - ref[i];
    e2 += e * e;
    r2 += double(ref[i]) * ref[i];
  }
  return r2 > 0 ? std::sqrt(e2 / r2) : 0.0;
}

struct Setting {
  const char* mode;  // "threshold" or "top-M"
  double threshold;
  int64_t top;
  prt::HaarQuantization bits;
};

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : PRT_SHARED_DATA_DIR;
  const std::string out_dir = argc > 2 ? argv[2] : ".";
  try {
    prt::scene::Scene scene = prt::bench::make_bunny_on_plane(data);
    const std::size_t V = scene.vertex_count();

    prt::bake::HaarBakeOptions o;
    o.cube_size = kCube;
    o.compression.quantization = prt::HaarQuantization::Float32;
    o.compression.relative_threshold = 0.0;
    const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, o);
    const prt::HaarTransfer& full = baked.file.transfer;
    if (full.channels != 1) throw std::runtime_error("expected grey transfer");
    std::printf("bunny + plane: %zu vertices, N = %d, reference %.0f B/vertex (float, all terms)\n",
                V, kCube, double(full.stored_bytes()) / double(V));
    const prt::HaarRelighter reference(full);

    // Per-vertex wavelet coefficients (vertex-major), to re-truncate.
    const std::size_t W = std::size_t(6) * kCube * kCube;
    const std::vector<float> coeffs = prt::bench::dense_wavelet_coefficients(full, V, kCube);

    struct Light {
      std::string name;
      prt::WaveletCube wavelets;
      std::vector<float> ref;
    };
    std::vector<Light> lights;
    const prt::sh::EnvMap park = prt::relight::read_environment(
        data + "/hdri/rooitou_park_1k.hdr", prt::sh::EnvLayout::LatLong, nullptr);
    for (auto& [name, env] : std::vector<std::pair<std::string, prt::sh::EnvMap>>{
             {"park", park}, {"area light", prt::bench::make_area_light()}}) {
      prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, kCube);
      if (!cube.ok()) throw std::runtime_error(cube.status().message());
      prt::Result<prt::WaveletCube> w = prt::transform_cube(*cube);
      if (!w.ok()) throw std::runtime_error(w.status().message());
      Light l{name, std::move(*w), std::vector<float>(3 * V)};
      if (!reference.shade(prt::keep_all_terms(l.wavelets), l.ref.data()).ok()) return 1;
      lights.push_back(std::move(l));
    }

    std::vector<Setting> settings;
    for (prt::HaarQuantization q : {prt::HaarQuantization::Bits8, prt::HaarQuantization::Bits16}) {
      for (double t :
           {0.3, 0.1, 0.05, 0.03, 0.02, 0.01, 0.005, 0.003, 0.002, 0.001, 7e-4, 5e-4, 3e-4, 1e-4})
        settings.push_back({"threshold", t, 0, q});
      for (int64_t m : {16, 32, 64, 128, 256, 512, 1024, 1536, 2048})
        settings.push_back({"top-M", 0, m, q});
    }
    std::string csv =
        "mode,threshold,top_m,bits,bytes_per_vertex,terms_per_vertex,"
        "park_all_terms,park_k200,area_all_terms,area_k200\n";
    std::printf("%-9s %8s %5s %4s %9s %8s | %-22s | %-22s\n", "mode", "thresh", "M", "bits",
                "B/vertex", "terms/v", "park: all / K=200", "area: all / K=200");
    std::vector<float> b(3 * V);
    for (const Setting& s : settings) {
      prt::HaarTransferOptions opt;
      opt.quantization = s.bits;
      opt.relative_threshold = s.threshold;
      opt.max_terms_per_vertex = s.top;
      prt::HaarTransferBuilder builder(kCube, 1, s.bits);
      for (std::size_t v = 0; v < V; ++v) {
        const prt::SparseVertexTransfer sv =
            prt::truncate_vertex_coefficients(&coeffs[v * W], kCube, 1, opt);
        if (!builder.add_vertex(sv).ok()) throw std::runtime_error("add_vertex failed");
      }
      prt::Result<prt::HaarTransfer> t = builder.finish();
      if (!t.ok()) throw std::runtime_error(t.status().message());
      const double bpv = double(t->stored_bytes()) / double(V);
      const double tpv = double(t->entry_count()) / double(V);
      const prt::HaarRelighter r(std::move(*t));
      double err[2][2];
      for (int li = 0; li < 2; ++li) {
        if (!r.shade(prt::keep_all_terms(lights[li].wavelets), b.data()).ok()) return 1;
        err[li][0] = relative_rms(b, lights[li].ref);
        if (!r.shade(prt::select_nonlinear(lights[li].wavelets, kRuntimeTerms), b.data()).ok())
          return 1;
        err[li][1] = relative_rms(b, lights[li].ref);
      }
      const int bits = static_cast<int>(s.bits);
      char line[512];
      std::snprintf(line, sizeof line, "%s,%g,%lld,%d,%.1f,%.1f,%.6g,%.6g,%.6g,%.6g\n", s.mode,
                    s.threshold, static_cast<long long>(s.top), bits, bpv, tpv, err[0][0],
                    err[0][1], err[1][0], err[1][1]);
      csv += line;
      std::printf("%-9s %8g %5lld %4d %9.1f %8.1f | %9.3f%% / %8.3f%% | %9.3f%% / %8.3f%%\n",
                  s.mode, s.threshold, static_cast<long long>(s.top), bits, bpv, tpv,
                  100 * err[0][0], 100 * err[0][1], 100 * err[1][0], 100 * err[1][1]);
    }
    prt::report::write_text_file(out_dir + "/bytes_per_vertex.csv", csv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "haar_bytes_per_vertex: %s\n", e.what());
    return 1;
  }
  return 0;
}
