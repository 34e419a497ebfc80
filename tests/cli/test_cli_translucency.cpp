// `prt report --translucency`: the files it writes and what they hold on the lone sphere of
// `prt make-scene --scene translucent-sphere`, and its refusals (one line, exit 2, nothing
// written).
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

namespace {

using namespace prt::test::cli;

// relative_rms of the row (part "all") for `lighting` and `approximation` (-1 when absent).
double error_of(const std::string& csv, const std::string& lighting,
                const std::string& approximation) {
  std::istringstream in(csv);
  const std::string key = ",all," + lighting + "," + approximation + ",";
  for (std::string line; std::getline(in, line);) {
    const std::size_t at = line.find(key);
    if (at == std::string::npos) continue;
    const std::string rest = line.substr(at + key.size());
    return std::stod(rest.substr(rest.find(',') + 1));
  }
  return -1;
}

}  // namespace

TEST_CASE("prt report --translucency --quick on the lone sphere", "[cli][translucency]") {
  const fs::path base = scratch("translucency_quick");
  const fs::path sphere = base / "sphere.glb", dir = base / "out";
  REQUIRE(
      run(prt_cli() + " make-scene --scene translucent-sphere -o " + sphere.string()).exit_code ==
      0);
  const RunResult r = run(prt_cli() + " report --translucency " + sphere.string() + " " +
                          prt::test::project_data("sky.hdr").string() + " -o " + dir.string() +
                          " --quick --quiet --mm-per-unit 1 --subsurface skin1");
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  for (const char* name :
       {"translucency_errors.csv", "translucency_timing.csv", "translucency.json",
        "translucency_errors.svg", "translucency_timing.svg", "translucency_summary.md",
        "sphere.dipole.prt", "sphere.lambert-rtotal.prt", "sphere.normal-blur.prt",
        "sphere.mesh-diffusion.prt", "sphere.depth-map.prt"})
    CHECK(fs::exists(dir / name));
  const std::string csv = slurp(dir / "translucency_errors.csv");
  for (const char* light : {"back", "front"}) {
    INFO(light);
    const double lambert = error_of(csv, light, "lambert-rtotal");
    const double diffusion = error_of(csv, light, "mesh-diffusion");
    REQUIRE(lambert > 0);
    REQUIRE(diffusion > 0);
    // Mesh-space diffusion sums the same straight-line kernel the dipole does (a Gaussian fit of
    // it): it must come closer than a BRDF with the same total reflectance.
    CHECK(diffusion < lambert);
    CHECK(diffusion < 0.1);
  }
  // the hierarchical bake against its O(n²) reference at every size the sweep ran it
  const std::string timing = slurp(dir / "translucency_timing.csv");
  CHECK(timing.find("\n482,") != std::string::npos);
}

TEST_CASE("prt report --translucency refuses bad input in one line and writes nothing",
          "[cli][translucency]") {
  const fs::path base = scratch("translucency_bad");
  const fs::path sphere = base / "sphere.glb", dir = base / "out";
  REQUIRE(
      run(prt_cli() + " make-scene --scene translucent-sphere -o " + sphere.string()).exit_code ==
      0);
  const std::string sky = prt::test::project_data("sky.hdr").string();
  const std::string head =
      prt_cli() + " report -o " + dir.string() + " " + sphere.string() + " " + sky + " ";
  const std::pair<const char*, const char*> cases[] = {
      {"--translucency --subsurface jade", "jade"},
      {"--subsurface marble", "--subsurface needs --translucency"},
      {"--translucency --mm-per-unit=-1", "--mm-per-unit"},
      {"--translucency --mm-per-unit 1,1", "--mm-per-unit"},
      {"--translucency --glossy", "--glossy"}};
  for (const auto& [tail, mention] : cases) {
    const RunResult r = run(head + tail);
    CHECK(r.exit_code == 2);
    require_one_line_error(r, mention);
    CHECK_FALSE(fs::exists(dir));
  }
}
