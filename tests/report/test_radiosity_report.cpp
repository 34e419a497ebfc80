// `prt report --radiosity` as a library call (report/radiosity_report.h): the sweep's rows, its
// files, and an error measure that tells a good solution from a poor one.
#include <filesystem>
#include <fstream>
#include <string>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "report/radiosity_report.h"
#include "scene/glb_writer.h"
#include "scene/material_assignment.h"
#include "scene/procedural_mesh.h"
#include "support/test_data.h"

namespace {

namespace rad = prt::radiosity;

// A floor, a wall and a lamp facing down (an open scene), written as GLB with the lamp's
// material named "lamp" so --emission can name it.
std::string write_open_scene(const std::filesystem::path& dir) {
  prt::scene::Scene s;
  auto add = [&s](const prt::scene::Scene& part, const std::string& material) {
    const uint32_t v0 = static_cast<uint32_t>(s.positions.size());
    const uint32_t t0 = static_cast<uint32_t>(s.triangles.size());
    s.positions.insert(s.positions.end(), part.positions.begin(), part.positions.end());
    s.normals.insert(s.normals.end(), part.normals.begin(), part.normals.end());
    s.albedo.insert(s.albedo.end(), part.albedo.begin(), part.albedo.end());
    for (const glm::uvec3& t : part.triangles) s.triangles.push_back(t + glm::uvec3(v0));
    for (prt::scene::ScenePrimitive p : part.primitives) {
      p.first_vertex += v0, p.first_triangle += t0, p.material = material;
      s.primitives.push_back(p);
    }
  };
  add(prt::scene::make_quad({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, 1, 1, glm::vec3(0.7f), "floor"),
      "floor");
  add(prt::scene::make_quad({0, 0, 0}, {0, 1, 0}, {0, 0, 1}, 1, 1, glm::vec3(0.6f), "wall"),
      "wall");
  add(prt::scene::make_quad({0.3f, 0.8f, 0.3f}, {0.4f, 0, 0}, {0, 0, 0.4f}, 1, 1, glm::vec3(0.5f),
                            "lamp"),
      "lamp");
  const std::string path = (dir / "open.glb").string();
  prt::scene::write_glb(path, s, nullptr);
  return path;
}

}  // namespace

// Two patch counts × analytic and rays (16 rays per patch: deliberately noisy) × Gauss–Seidel and
// progressive. The noisy rays must measure worse than analytic (at 16 rays a receiving patch's
// direct light has about 25% noise, analytic is within 1.5% here: see test_emitter_ground_truth),
// the matrix rows have a re-solve and progressive none, and the files hold every row.
TEST_CASE("radiosity report: rows, files, and a measure that separates methods",
          "[radiosity_report]") {
  const std::filesystem::path dir = prt::test::output_path("radiosity_report");
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  prt::report::RadiosityReportOptions o;
  o.scene_path = write_open_scene(dir);
  o.output_dir = (dir / "out").string();
  o.emission = {prt::scene::parse_material_colour("--emission", "lamp=10")};
  o.max_edges = {0.25, 0.125};
  o.methods = {rad::FormFactorMethod::Analytic, rad::FormFactorMethod::Rays};
  o.solvers = {rad::SolverKind::GaussSeidel, rad::SolverKind::Progressive};
  o.rays_per_patch = 16;
  o.ground_truth_patches = 64;
  o.ground_truth_samples = 2048;
  o.surface_samples = 1024;
  const prt::report::RadiosityReportResult r = prt::report::run_radiosity_report(o);
  REQUIRE(r.rows.size() == 8);
  REQUIRE(r.ground_truth.size() == 2);
  CHECK(r.ground_truth[0].patches < r.ground_truth[1].patches);
  CHECK(r.ground_truth[1].evaluated == 64);
  double analytic = 0, rays = 0;
  for (const auto& w : r.rows) {
    CHECK(w.converged);
    CHECK(std::isfinite(w.relative_rms));
    CHECK(w.relative_rms_corrected <= w.relative_rms);
    CHECK((w.solver == rad::SolverKind::Progressive) == (w.resolve_seconds < 0));
    if (w.max_edge == 0.125 && w.solver == rad::SolverKind::GaussSeidel)
      (w.method == rad::FormFactorMethod::Analytic ? analytic : rays) = w.relative_rms;
  }
  CHECK(analytic < 0.03);
  CHECK(rays > 2 * analytic);
  int front = 0;
  for (const auto& w : r.rows) front += w.on_pareto_front;
  CHECK(front >= 1);
  // Surfaces: floor, wall and lamp; the lamp's patch average is its emission plus what it reflects.
  REQUIRE(r.surfaces.size() == 3);
  for (const auto& s : r.surfaces)
    if (s.primitive.find("lamp") != std::string::npos) CHECK(s.truth.x >= 10.0);
  for (const std::string& name : prt::report::radiosity_report_file_names())
    if (name.find(".png") == std::string::npos) CHECK(std::filesystem::exists(dir / "out" / name));
  std::ifstream in(dir / "out" / "radiosity_results.json");
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["rows"].size() == 8);
}
