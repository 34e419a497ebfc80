// `prt report` pieces: error metrics against hand-computed values, the Pareto front and cheapest
// selection against brute force, SVG plot scales and ticks, and an end-to-end report on a tiny
// procedural scene whose files must be complete and self-consistent.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/glb_writer.h"
#include "bake/procedural_mesh.h"
#include "relight/image_io.h"
#include "relight/plot_svg.h"
#include "relight/report.h"
#include "relight/report_metrics.h"
#include "support/test_data.h"

using namespace prt::relight;

TEST_CASE("vertex error statistics match hand-computed values") {
  // Reference |B_gt| = 1, 2 (two vertices, red only); B off by 0.1 and 0.4 (red) → e = 0.1, 0.4.
  const std::vector<double> ref = {1, 0, 0, 2, 0, 0};
  const std::vector<float> b = {1.1f, 0, 0, 1.6f, 0, 0};
  const VertexErrorStats s = compute_vertex_errors(b, ref);
  // relative RMS = √(0.01 + 0.16)/√(1 + 4).
  CHECK(s.relative_rms == Approx(std::sqrt(0.17 / 5.0)).epsilon(1e-6));
  // Per-vertex relative: 0.1/1, 0.4/2 = 0.2 → max 0.2 at vertex 1; p99 of two values (rank 2) =
  // 0.2.
  CHECK(s.max == Approx(0.2).epsilon(1e-6));
  CHECK(s.max_vertex == 1);
  CHECK(s.p99 == Approx(0.2).epsilon(1e-6));
  // The floor: a black reference vertex is judged against 5% of the RMS magnitude.
  const std::vector<double> ref2 = {0, 0, 0, 2, 0, 0, 2, 0, 0};
  const std::vector<double> b2 = {0.1, 0, 0, 2, 0, 0, 2, 0, 0};
  const VertexErrorStats s2 = compute_vertex_errors(b2, ref2);
  const double rms = std::sqrt(8.0 / 3.0);
  CHECK(s2.max == Approx(0.1 / (0.05 * rms)).epsilon(1e-9));
  // Non-finite output is an infinite error, never hidden.
  std::vector<float> bad = b;
  bad[0] = NAN;
  CHECK(std::isinf(compute_vertex_errors(bad, ref).relative_rms));
}

TEST_CASE("p99 is the nearest-rank percentile") {
  std::vector<double> ref, b;
  for (int i = 0; i < 200; ++i) {
    ref.insert(ref.end(), {1.0, 0.0, 0.0});
    b.insert(b.end(), {1.0 + 0.001 * i, 0.0, 0.0});  // relative errors 0, 0.001, ..., 0.199
  }
  const VertexErrorStats s = compute_vertex_errors(b, ref);
  CHECK(s.p99 == Approx(0.197).epsilon(1e-9));  // rank ⌈0.99·200⌉ = 198 → value 0.197
  CHECK(s.max == Approx(0.199).epsilon(1e-9));
}

TEST_CASE("image error counts only masked pixels") {
  const std::vector<float> ref = {1, 1, 1, 5, 5, 5};
  const std::vector<float> a = {1.5f, 1, 1, 0, 0, 0};
  CHECK(relative_rms_image_error(a, ref, {1, 0}) == Approx(std::sqrt(0.25 / 3.0)).epsilon(1e-6));
  CHECK(relative_rms_image_error(a, ref, {}) > 0.9);
}

TEST_CASE("Pareto front and cheapest setting agree with brute force") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.01, 10.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<double> c(30), e(30);
    for (int i = 0; i < 30; ++i) c[i] = u(rng), e[i] = u(rng);
    if (trial == 0) c[5] = INFINITY;  // a failed setting is never on the front
    const std::vector<bool> front = pareto_front(c, e);
    for (int i = 0; i < 30; ++i) {
      bool dominated = !std::isfinite(c[i]);
      for (int j = 0; j < 30; ++j)
        if (std::isfinite(c[j]) && c[j] <= c[i] && e[j] <= e[i] && (c[j] < c[i] || e[j] < e[i]))
          dominated = true;
      REQUIRE(front[i] == !dominated);
    }
    const long k = cheapest_reaching(c, e, 3.0);
    double best = INFINITY;
    for (int i = 0; i < 30; ++i)
      if (e[i] <= 3.0 && std::isfinite(c[i])) best = std::min(best, c[i]);
    if (std::isinf(best)) {
      REQUIRE(k == -1);
    } else {
      REQUIRE(k >= 0);
      REQUIRE(c[k] == best);
      // And the cheapest setting reaching a target is on the front.
      REQUIRE(front[k]);
    }
  }
}

TEST_CASE("plot axes: decade ranges, ticks and labels") {
  double lo, hi;
  choose_axis_range({0.013, 0.4, 2.5}, true, &lo, &hi);
  CHECK(lo == Approx(0.01));
  CHECK(hi == Approx(10.0));
  const std::vector<double> t = major_ticks(lo, hi, true);
  REQUIRE(t.size() == 4);
  CHECK(t[0] == Approx(0.01));
  CHECK(t[3] == Approx(10.0));
  CHECK(minor_ticks(1, 10, true).size() == 8);
  CHECK(format_tick(0.01, true, true) == "1%");
  CHECK(format_tick(100, true, false) == "100");
  CHECK(format_tick(1e-6, true, false) == "1e-6");
  // Linear: round steps covering the data.
  choose_axis_range({2, 16}, false, &lo, &hi);
  CHECK(lo <= 2);
  CHECK(hi >= 16);
  const std::vector<double> lt = major_ticks(lo, hi, false, 6);
  REQUIRE(lt.size() >= 3);
  CHECK(lt[1] - lt[0] == Approx(lt[2] - lt[1]));
  // Non-positive values are dropped from log axes instead of producing NaN coordinates.
  PlotSpec p;
  p.title = "t & <x>";
  p.log_x = p.log_y = true;
  PlotSeries s;
  s.label = "series";
  s.x = {0.1, 1, 0, 10};
  s.y = {0.5, 0.05, 1, -1};
  p.series.push_back(s);
  const std::string svg = render_svg(p);
  CHECK(svg.find("nan") == std::string::npos);
  CHECK(svg.find("t &amp; &lt;x&gt;") != std::string::npos);
  CHECK(svg.find("<polyline") != std::string::npos);
  CHECK(svg.find("series") != std::string::npos);
}

TEST_CASE("end-to-end quick report on a small scene writes consistent files") {
  // A box on a floor (~150 vertices) under a small lat-long sky with a bright sun texel.
  prt::bake::Scene scene = prt::bake::make_quad(
      glm::vec3(-2, 0, 2), glm::vec3(4, 0, 0), glm::vec3(0, 0, -4), 6, 6, glm::vec3(0.6f), "floor");
  prt::bake::append_scene(
      scene, prt::bake::make_box(glm::vec3(-0.5f, 0, -0.5f), glm::vec3(0.5f, 1, 0.5f), 2, false,
                                 glm::vec3(0.5f, 0.3f, 0.2f)));
  const auto dir = prt::test::output_path("report_e2e");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string scene_path = (dir / "scene.glb").string();
  prt::bake::write_glb(scene_path, scene);
  std::vector<float> sky(3 * 64 * 32);
  for (int r = 0; r < 32; ++r)
    for (int c = 0; c < 64; ++c)
      for (int ch = 0; ch < 3; ++ch)
        sky[3 * (r * 64 + c) + ch] = r < 16 ? 0.5f + 0.1f * static_cast<float>(ch) : 0.2f;
  for (int ch = 0; ch < 3; ++ch) sky[3 * (8 * 64 + 40) + ch] = 500.f;
  const std::string env_path = (dir / "sky.exr").string();
  write_image(env_path, 64, 32, 3, sky.data());

  ReportOptions o;
  o.scene_path = scene_path;
  o.environment_path = env_path;
  o.output_dir = (dir / "out").string();
  o.quick = true;
  o.image_width = 64, o.image_height = 36;
  o.verbose = false;
  const ReportResult r = run_report(o);
  for (const char* f :
       {"results.csv", "results.json", "pareto.svg", "error_vs_order.svg", "summary.md"})
    CHECK(std::filesystem::exists(dir / "out" / f));
  // Every setting of every axis was measured once.
  std::size_t unique = 0;
  std::vector<ReportSetting> seen;
  for (const ReportAxis& a : report_axes(true))
    for (const ReportSetting& s : a.settings) {
      bool dup = false;
      for (const ReportSetting& t : seen)
        dup |= t.order == s.order && t.samples == s.samples && t.bounces == s.bounces &&
               t.precision == s.precision;
      if (!dup) seen.push_back(s), ++unique;
    }
  REQUIRE(r.measurements.size() == unique);
  bool any_front = false;
  for (const ReportMeasurement& m : r.measurements) {
    INFO(m.axis << " order " << m.setting.order << " spp " << m.setting.samples);
    REQUIRE(m.failure.empty());
    CHECK(std::isfinite(m.relative_rms));
    CHECK(m.relative_rms < 1.0);
    CHECK(m.p99 <= m.max);
    CHECK(m.file_bytes > 0);
    CHECK(m.bake_seconds > 0);
    any_front |= m.on_pareto_front;
  }
  CHECK(any_front);
  // Physics the report must show: shadowed-only transfer (bounces 0) is worse than converged
  // interreflection (the floor and box reflect 50-60%), and order 2 is worse than order 6 with a
  // sun in the map.
  auto find = [&](int order, int samples, int bounces) {
    for (const ReportMeasurement& m : r.measurements)
      if (m.setting.order == order && m.setting.samples == samples &&
          m.setting.bounces == bounces && m.setting.precision == prt::Precision::F32)
        return m.relative_rms;
    return static_cast<double>(NAN);
  };
  const ReportSetting base = base_setting(true);
  CHECK(find(base.order, base.samples, 0) > find(base.order, base.samples, -1));
  CHECK(find(2, base.samples, -1) > find(6, base.samples, -1));
  // Projection error falls with order (the split is monotone within 1% slack for GT noise).
  REQUIRE(r.projection_error.size() == r.orders.size());
  CHECK(r.projection_error.back() < r.projection_error.front());
  // The JSON mirrors the measurements and prints the basis convention.
  std::ifstream jf(dir / "out" / "results.json");
  const nlohmann::json j = nlohmann::json::parse(jf);
  CHECK(j["results"].size() == r.measurements.size());
  CHECK(j["sh_basis"].get<std::string>().find("no Condon-Shortley") != std::string::npos);
  CHECK(j["ground_truth"]["samples_per_vertex"].get<int>() == r.ground_truth_samples);
  // CSV: a header and one row per measurement.
  std::ifstream cf(dir / "out" / "results.csv");
  int lines = 0;
  for (std::string line; std::getline(cf, line);) ++lines;
  CHECK(lines == static_cast<int>(r.measurements.size()) + 1);
  // The summary names the cheapest setting for each target and embeds both plots.
  std::ifstream mf(dir / "out" / "summary.md");
  std::stringstream md;
  md << mf.rdbuf();
  CHECK(md.str().find("| 10% |") != std::string::npos);
  CHECK(md.str().find("(pareto.png)") != std::string::npos);
  CHECK(md.str().find("(error_vs_order.png)") != std::string::npos);
}
