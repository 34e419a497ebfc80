// bench/haar_vs_sh.cpp — reproduces the central comparison of Ng, Ramamoorthi & Hanrahan,
// "All-Frequency Shadows Using Non-linear Wavelet Lighting Approximation" (SIGGRAPH 2003),
// Fig. 5/6: error of exit radiance against the number of lighting terms for SH, linear Haar and
// non-linear Haar, on a shadowed scene (the bunny on a ground plane) under an HDR park with an
// unclipped sun and under a small area light.
//
// Method (every approximation relights the *same* transfer, so only the lighting approximation
// differs, as in the paper):
//   * Transfer: a shadowed Haar bake at N = 32, unquantised, every term kept (bake/haar_baker.h).
//   * Reference: that transfer relit with every one of the 6N² lighting terms (= the texel sum).
//   * Haar, K terms: the same transfer with select_nonlinear / select_linear(K) lighting.
//   * SH, order n (n² terms): transfer and lighting projected onto SH from the same cube
//     (T_k = Σ_t T_t Y_k(ω_t), L_k = Σ_t L_t Y_k(ω_t) ω_t, exact solid angles): the converged
//     SH bake of this discrete transfer; B = Σ_k T_k L_k.
// Errors over vertices, RGB: L2 = √(Σ|B − B*|²/Σ|B*|²); max = max|B − B*| / max|B*|;
// H1 (discrete Sobolev, our definition): L2 with the gradient added as differences along mesh
// edges, H1² = (Σ_v|e_v|² + Σ_edges|e_a − e_b|²) / (Σ_v|B*_v|² + Σ_edges|B*_a − B*_b|²),
// e = B − B* (edge lengths are nearly uniform on these meshes, so they are not weighted).
//
// Writes docs/haar/comparison.csv, comparison.svg and comparison.png (rsvg-convert).
// Usage: haar_vs_sh [SHARED_DATA_DIR] [OUTPUT_DIR]
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <tbb/parallel_for.h>

#include "bake/haar_baker.h"
#include "haar_bench_scene.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transform.h"
#include "relight/image_io.h"
#include "report/plot_svg.h"
#include "scene/scene_loader.h"
#include "sh/basis.h"

namespace {

constexpr int kCube = 32;
constexpr int kMaxShOrder = 32;  // 1024 terms
const int kHaarTerms[] = {9, 25, 50, 100, 200, 400, 1000, 2000, 4000};
const int kShOrders[] = {3, 5, 7, 10, 14, 20, 25, 32};

struct Errors {
  double l2 = 0, max = 0, h1 = 0;
};

Errors compare(const std::vector<float>& b, const std::vector<float>& ref,
               const std::vector<std::pair<uint32_t, uint32_t>>& edges) {
  double e2 = 0, r2 = 0, emax = 0, rmax = 0, ge2 = 0, gr2 = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    const double e = double(b[i]) - ref[i];
    e2 += e * e;
    r2 += double(ref[i]) * ref[i];
    emax = std::max(emax, std::fabs(e));
    rmax = std::max(rmax, std::fabs(double(ref[i])));
  }
  for (const auto& [a, c] : edges)
    for (int ch = 0; ch < 3; ++ch) {
      const double ea = double(b[3 * a + ch]) - ref[3 * a + ch];
      const double ec = double(b[3 * c + ch]) - ref[3 * c + ch];
      const double g = double(ref[3 * a + ch]) - ref[3 * c + ch];
      ge2 += (ea - ec) * (ea - ec);
      gr2 += g * g;
    }
  return {std::sqrt(e2 / r2), emax / rmax, std::sqrt((e2 + ge2) / (r2 + gr2))};
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data = argc > 1 ? argv[1] : PRT_SHARED_DATA_DIR;
  const std::string out_dir = argc > 2 ? argv[2] : PRT_SOURCE_DIR "/docs/haar";
  const auto t0 = std::chrono::steady_clock::now();
  try {
    // Scene: the bunny on a ground plane.
    prt::scene::Scene scene = prt::bench::make_bunny_on_plane(data);
    const std::size_t V = scene.vertex_count();
    std::set<std::pair<uint32_t, uint32_t>> edge_set;
    for (const glm::uvec3& t : scene.triangles)
      for (int e = 0; e < 3; ++e) {
        const uint32_t a = t[e], b = t[(e + 1) % 3];
        edge_set.insert({std::min(a, b), std::max(a, b)});
      }
    const std::vector<std::pair<uint32_t, uint32_t>> edges(edge_set.begin(), edge_set.end());

    prt::bake::HaarBakeOptions o;
    o.cube_size = kCube;
    o.compression.quantization = prt::HaarQuantization::Float32;
    o.compression.relative_threshold = 0.0;
    const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, o);
    std::printf("baked %zu vertices at N = %d: %.2f Mrays/s, %.1f s\n", V, kCube,
                baked.stats.mrays_per_second(), baked.stats.seconds_total);
    const prt::HaarTransfer& transfer = baked.file.transfer;
    const prt::HaarRelighter relighter(transfer);

    // Dense transfer per vertex (wavelet → texel domain), for the SH projection.
    const std::size_t W = std::size_t(6) * kCube * kCube;
    std::vector<float> dense = prt::bench::dense_wavelet_coefficients(transfer, V, kCube);
    tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
      for (int f = 0; f < 6; ++f)
        prt::inverse_haar_2d(dense.data() + v * W + f * kCube * kCube, kCube);
    });
    // SH table at texel centres and the SH transfer T_k = Σ_t T_t Y_k(ω_t).
    const int K = kMaxShOrder * kMaxShOrder;
    std::vector<float> y(W * K);
    std::vector<double> omega(W);
    for (int f = 0; f < 6; ++f)
      for (int r = 0; r < kCube; ++r)
        for (int col = 0; col < kCube; ++col) {
          const std::size_t t = (std::size_t(f) * kCube + r) * kCube + col;
          double d[3];
          prt::cube_texel_direction(kCube, f, col, r, d);
          std::vector<double> yd(K);
          prt::sh::evaluate(kMaxShOrder, d[0], d[1], d[2], yd.data());
          for (int k = 0; k < K; ++k) y[t * K + k] = static_cast<float>(yd[k]);
          omega[t] = prt::cube_texel_solid_angle(kCube, col, r);
        }
    std::vector<float> t_sh(V * K, 0.f);
    tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
      std::vector<double> acc(K, 0.0);
      for (std::size_t t = 0; t < W; ++t) {
        const float x = dense[v * W + t];
        if (x == 0.f) continue;
        const float* yt = &y[t * K];
        for (int k = 0; k < K; ++k) acc[k] += double(x) * yt[k];
      }
      for (int k = 0; k < K; ++k) t_sh[v * K + k] = static_cast<float>(acc[k]);
    });
    std::printf("SH transfer projected to order %d (%.1f s)\n", kMaxShOrder,
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

    struct Light {
      std::string name;
      prt::sh::EnvMap env;
    };
    std::vector<Light> lights;
    lights.push_back({"park (rooitou, sun)",
                      prt::relight::read_environment(data + "/hdri/rooitou_park_1k.hdr",
                                                     prt::sh::EnvLayout::LatLong, nullptr)});
    lights.push_back({"small area light", prt::bench::make_area_light()});

    std::ofstream csv_tmp;
    std::string csv = "light,method,terms,l2,max,h1\n";
    prt::report::PlotSpec plot;
    plot.title = "Bunny on a plane, N = 32: relative L2 error of exit radiance vs terms";
    plot.x_label = "lighting terms";
    plot.y_label = "relative L2 error";
    plot.log_x = plot.log_y = true;
    plot.y_as_percent = true;
    plot.legend = prt::report::LegendCorner::BottomLeft;  // the data leave that corner empty
    const char* colors[3] = {"#d62728", "#2ca02c", "#1f77b4"};
    for (std::size_t li = 0; li < lights.size(); ++li) {
      const Light& light = lights[li];
      prt::Result<prt::CubeMap> cube = prt::resample_to_cube(light.env, kCube);
      if (!cube.ok()) throw std::runtime_error(cube.status().message());
      prt::Result<prt::WaveletCube> wl = prt::transform_cube(*cube);
      if (!wl.ok()) throw std::runtime_error(wl.status().message());
      std::vector<float> ref(3 * V), b(3 * V);
      if (!relighter.shade(prt::keep_all_terms(*wl), ref.data()).ok()) return 1;
      prt::report::PlotSeries series[3];
      const char* names[3] = {"SH", "linear Haar", "non-linear Haar"};
      for (int m = 0; m < 3; ++m) {
        series[m].label = light.name + ": " + names[m];
        series[m].color = colors[m];
        series[m].dashed = li == 1;
        series[m].marker = li == 0 ? prt::report::Marker::Circle : prt::report::Marker::Square;
      }
      auto record = [&](int m, int terms, const Errors& e) {
        char line[256];
        std::snprintf(line, sizeof line, "%s,%s,%d,%.6g,%.6g,%.6g\n", light.name.c_str(), names[m],
                      terms, e.l2, e.max, e.h1);
        csv += line;
        std::printf("%s", line);
        series[m].x.push_back(terms);
        series[m].y.push_back(e.l2);
      };
      // SH lighting: L_k = Σ_t L_t Y_k ω_t.
      std::vector<double> l_sh(3 * std::size_t(K), 0.0);
      for (std::size_t t = 0; t < W; ++t)
        for (int k = 0; k < K; ++k)
          for (int ch = 0; ch < 3; ++ch)
            l_sh[3 * k + ch] += cube->rgb[3 * t + ch] * double(y[t * K + k]) * omega[t];
      for (int n : kShOrders) {
        const int kn = n * n;
        for (std::size_t v = 0; v < V; ++v)
          for (int ch = 0; ch < 3; ++ch) {
            double s = 0;
            for (int k = 0; k < kn; ++k) s += double(t_sh[v * K + k]) * l_sh[3 * k + ch];
            b[3 * v + ch] = static_cast<float>(s);
          }
        record(0, kn, compare(b, ref, edges));
      }
      for (int terms : kHaarTerms) {
        if (!relighter.shade(prt::select_linear(*wl, terms), b.data()).ok()) return 1;
        record(1, terms, compare(b, ref, edges));
        if (!relighter.shade(prt::select_nonlinear(*wl, terms), b.data()).ok()) return 1;
        record(2, terms, compare(b, ref, edges));
      }
      for (auto& s : series) plot.series.push_back(s);
    }
    plot.reference_lines.push_back({0.01, "1%"});
    prt::report::write_text_file(out_dir + "/comparison.csv", csv);
    prt::report::write_text_file(out_dir + "/comparison.svg", prt::report::render_svg(plot));
    std::string why;
    if (!prt::report::convert_svg_to_png(out_dir + "/comparison.svg", out_dir + "/comparison.png",
                                         1.0, &why))
      std::fprintf(stderr, "haar_vs_sh: no PNG: %s\n", why.c_str());
    std::printf("total %.1f s\n",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "haar_vs_sh: %s\n", e.what());
    return 1;
  }
  return 0;
}
