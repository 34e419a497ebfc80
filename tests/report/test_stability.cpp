// tests/report/test_stability.cpp — the stability cases of `prt report --stability` as tests
// (report/stability_cases.h; quick sizes). Each case computes its own analytic or
// independent reference and pass criterion (stated in the case and in docs/STABILITY.md); the
// tests require the case to pass and re-check the figures that matter, so a regression shows
// which number moved.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "report/stability_cases.h"
#include "report/stability_report.h"
#include "support/test_data.h"

using namespace prt::report::stability;

namespace {

const CaseOptions kQuick{true};

void require_passed(const CaseResult& r) {
  std::string figures;
  for (const auto& [k, v] : r.numbers) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    figures += "\n  " + k + " = " + buf;
  }
  INFO(r.group << "/" << r.name << ": " << r.detail << figures);
  REQUIRE(r.passed);
}

}  // namespace

TEST_CASE("SH evaluation is accurate to l = 200 at and near both poles", "[stability]") {
  const CaseResult r = check_sh_evaluation_at_poles(kQuick);
  require_passed(r);
  // Double: the library's own documented accuracy at l = 200 is 1e-10 (sh/basis.h).
  CHECK(r.number("double_max_band_error") <= 1e-10);
  // Float holds a relative 1e-3 at least to l = 30 (float's 24-bit mantissa).
  CHECK(r.number("float_usable_up_to_l") >= 30);
  // Known limitation (sh/basis.h): float overflows its intermediates near l ≈ 186 at the poles.
  CHECK(r.number("float_first_nonfinite_l") > 150);
}

TEST_CASE("SH rotation stays orthogonal to l = 30 and finite to l = 60", "[stability]") {
  const CaseResult r = check_rotation_orthogonality(kQuick);
  require_passed(r);
  CHECK(r.number("error_l30") <= 1e-10);
  CHECK(std::isfinite(r.number("error_l60")));
}

TEST_CASE("A sun 1e5 and 1e6 times the sky: finite, auto window removes negative irradiance",
          "[stability]") {
  for (double ratio : {1e5, 1e6}) {
    const CaseResult r = check_bright_sun(kQuick, ratio);
    require_passed(r);
    // Unwindowed order 9 must ring into negative radiance for such a sun (otherwise the case
    // does not test what it claims).
    CHECK(r.number("order9_none_negative_radiance_fraction") > 0.0);
    CHECK(r.number("order9_auto_min_irradiance_over_max") >= -1e-3);
  }
}

TEST_CASE("An all-black map gives exactly zero lighting for every window", "[stability]") {
  require_passed(check_black_map(kQuick));
}

TEST_CASE("A single bright texel projects to ω·L·Y(texel direction)", "[stability]") {
  const CaseResult r = check_single_bright_texel(kQuick);
  require_passed(r);
  CHECK(r.number("relative_coefficient_error") <= 1e-12);
}

TEST_CASE("NaN, Inf and negative texels are skipped and counted", "[stability]") {
  const CaseResult r = check_nan_inf_pixels(kQuick);
  require_passed(r);
  CHECK(r.number("nan_texels") == 5);
  CHECK(r.number("inf_texels") == 4);
  CHECK(r.number("negative_texels") == 3);
}

TEST_CASE("1×1, 2×1 and 2048×1024 maps project correctly", "[stability]") {
  require_passed(check_map_size(kQuick, 1, 1));
  require_passed(check_map_size(kQuick, 2, 1));
  const CaseResult big = check_map_size(kQuick, 2048, 1024);
  require_passed(big);
  // 1024 rows: the row-centre sampling of 1 + 0.5·cos θ differs from the exact row integral by
  // O((π/H)²/24) ≈ 4e-7 relative.
  CHECK(big.number("max_coefficient_error") <= 2e-6);
}

TEST_CASE("Spherical-cavity furnace at albedo 0.9, 0.99, 0.999 matches ρf/(1−ρ(1−f))",
          "[stability]") {
  for (double albedo : {0.9, 0.99, 0.999}) {
    const CaseResult r = check_cavity_furnace(kQuick, albedo);
    require_passed(r);
    CHECK(std::fabs(r.number("mean_relative_error")) <= 0.02);
  }
}

TEST_CASE("The interreflection solver stops in bounded time and converges when allowed",
          "[stability]") {
  const CaseResult r = check_solver_bounded(kQuick);
  require_passed(r);
  CHECK(r.number("symmetric_mean_error") <= 1e-6);
  // Regression (bake/src/interreflection_solver.cpp): BiCGSTAB used to return an iterate with
  // residual ~2e4 on the non-normal ring; it now keeps its best iterate.
  CHECK(r.number("nonnormal_2000_residual") <= r.number("warmup_residual"));
}

TEST_CASE("Albedo >= 1 (and NaN, negative) is refused", "[stability]") {
  require_passed(check_albedo_refused(kQuick));
}

TEST_CASE("Degenerate, duplicated, non-manifold and flipped geometry bakes without NaN",
          "[stability]") {
  const CaseResult r = check_degenerate_geometry(kQuick);
  require_passed(r);
  CHECK(r.number("skipped_degenerate_triangles") == 3);
}

TEST_CASE("Scenes at 1e-3 and 1e4 scale bake the same transfer, a plane has AO 1", "[stability]") {
  for (float scale : {1e-3f, 1e4f}) {
    const CaseResult r = check_scene_scale(kQuick, scale);
    require_passed(r);
    CHECK(r.number("plane_min_ao") == 1.0);
  }
}

TEST_CASE("A vertex inside a closed box has zero transfer", "[stability]") {
  const CaseResult r = check_vertex_inside_box(kQuick);
  require_passed(r);
  CHECK(r.number("max_abs_transfer") == 0.0);
}

TEST_CASE("Float16 storage of very bright transfer is refused, never stored as Inf",
          "[stability]") {
  require_passed(check_half_overflow(kQuick));
}

TEST_CASE("run_case turns exceptions and non-finite figures into failures", "[stability]") {
  const CaseResult thrown = run_case("g", "n", "c", [](CaseResult& r) {
    r.passed = true;
    throw std::runtime_error("x.prt: broken");
  });
  CHECK_FALSE(thrown.passed);
  CHECK(thrown.detail.find("x.prt: broken") != std::string::npos);
  const CaseResult nan = run_case("g", "n", "c", [](CaseResult& r) {
    r.passed = true;
    r.add("value", std::nan(""));
  });
  CHECK_FALSE(nan.passed);
}

TEST_CASE("run_stability_report writes stability.md and stability.json", "[stability]") {
  const std::filesystem::path dir = prt::test::output_path("stability_quick");
  std::filesystem::remove_all(dir);
  const int failed = prt::report::run_stability_report(dir.string(), true);
  CHECK(failed == 0);
  std::ifstream in(dir / "stability.json");
  REQUIRE(in);
  const nlohmann::json j = nlohmann::json::parse(in);
  REQUIRE(j["cases"].size() == 20);
  int passed = 0;
  for (const auto& c : j["cases"]) {
    passed += c["passed"].get<bool>() ? 1 : 0;
    for (const auto& [k, v] : c["numbers"].items()) {
      INFO(c["name"].get<std::string>() << ": " << k);
      CHECK(v.is_number());  // non-finite figures would be written as null
    }
  }
  CHECK(passed == 20 - failed);
  CHECK(j["sh_basis"].get<std::string>().find("no Condon-Shortley") != std::string::npos);
  std::ifstream md(dir / "stability.md");
  const std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  CHECK(text.find("cases passed") != std::string::npos);
}
