// `prt report --sun-study`: the files it writes and what they hold, and its refusals (one line,
// non-zero exit, nothing written).
#include <string>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

namespace {

using namespace prt::test::cli;

// The rel_rms of `material`'s sphere row at `order` in sun_errors.csv (-1 when absent).
double sphere_rms(const std::string& csv, const std::string& material, int order) {
  std::istringstream in(csv);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind(material + ",", 0) != 0) continue;
    const std::size_t at = line.find(",sphere," + std::to_string(order) + ",");
    if (at == std::string::npos) continue;
    const std::string rest = line.substr(at + 8 + std::to_string(order).size() + 1);
    return std::stod(rest.substr(0, rest.find(',')));
  }
  return -1;
}

}  // namespace

TEST_CASE("prt report --sun-study --quick writes the study and its error falls with order",
          "[cli][sun_study]") {
  const fs::path dir = scratch("sun_study_quick") / "out";
  const RunResult r = run(prt_cli() + " report --sun-study -o " + dir.string() +
                          " --quick --quiet --roughness 0.4");
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* name : {"summary.md", "sun_errors.csv", "sun_memory.csv",
                           "sun_error_vs_order.svg", "sun_normal_incidence.svg"})
    CHECK(fs::exists(dir / name));
  const std::string csv = slurp(dir / "sun_errors.csv");
  // Every material of the study, only the α asked for.
  for (const char* m : {"lambert,", "ggx_a0.4,", "glossy_red,", "brushed_steel,", "rough_gold,"})
    CHECK(csv.find(std::string("\n") + m) != std::string::npos);
  CHECK(csv.find("ggx_a0.05,") == std::string::npos);
  // A rough lobe: the error at order 12 is well under that at order 2 (measured 5% against 52%).
  const double e2 = sphere_rms(csv, "ggx_a0.4", 2), e12 = sphere_rms(csv, "ggx_a0.4", 12);
  REQUIRE(e2 > 0);
  REQUIRE(e12 > 0);
  CHECK(e12 < 0.25 * e2);
  // 50k vertices: order 10 at f16 is the largest within 1 GiB (10⁴·2·5e4 B = 0.93 GiB).
  const std::string summary = slurp(dir / "summary.md");
  CHECK(summary.find("| 1 GiB/object f16 | 10 |") != std::string::npos);
  CHECK(summary.find("| 24 GiB f16 | 22 |") != std::string::npos);
  CHECK(slurp(dir / "sun_memory.csv").find("\n8,16384,8192,") != std::string::npos);
}

TEST_CASE("prt report --sun-study refuses bad input in one line and writes nothing",
          "[cli][sun_study]") {
  const fs::path base = scratch("sun_study_bad");
  const fs::path dir = base / "out";
  const std::string head = prt_cli() + " report -o " + dir.string() + " ";
  struct Case {
    std::string arguments, mention;
  } cases[] = {
      {"--sun-study --roughness 0.1,glossy", "glossy"},
      {"--sun-study --roughness 0.1,", "--roughness"},
      {"--sun-study --roughness 2", "--roughness"},
      {"--sun-study --sky -1", "--sky"},
      {"--sun-study --vertices 0", "--vertices"},
      {"--sun-study --stability", "--stability"},
      {"--sun-study scene.glb", "SCENE"},
      {"--sun-study --seed 3", "--seed"},
      {"--roughness 0.1 --stability", "--roughness needs --sun-study"},
  };
  for (const Case& c : cases) {
    INFO(c.arguments);
    const RunResult r = run(head + c.arguments);
    require_one_line_error(r, c.mention);
    CHECK(files_in(base).empty());
  }
}
