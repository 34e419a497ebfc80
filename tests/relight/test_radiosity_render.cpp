// Drawing a radiosity solution (relight/radiosity_render.h) from a scene and per-vertex
// radiance: its automatic exposure (the one rule), the files it writes and the outputs it
// refuses.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "relight/auto_exposure.h"
#include "relight/radiosity_render.h"
#include "scene/procedural_mesh.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using prt::relight::RadiosityRenderRequest;

TEST_CASE("radiosity images take the one exposure rule: choose_auto_exposure, a quarter stop",
          "[relight][radiosity-render]") {
  // The exposure prt relight picks for the same vertex radiance (relight/auto_exposure.h), so
  // a solution and the relight of its responses agree; before, the radiosity image had its own
  // rule (log-average of the pixels to 0.18, not rounded).
  const fs::path dir = prt::test::output_path("radiosity_render_exposure");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const prt::scene::Scene quad =
      prt::scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 4, 4, glm::vec3(0.5f));
  std::vector<float> radiance(3 * quad.vertex_count());
  for (std::size_t i = 0; i < radiance.size(); ++i) radiance[i] = 0.013f + 0.37f * float(i % 5);
  RadiosityRenderRequest r;
  r.scene_path = (dir / "quad.obj").string();
  r.output_path = (dir / "quad.png").string();
  r.render.width = 16;
  r.render.height = 12;
  r.render.samples_per_axis = 1;
  r.camera = "0,0,3,0,0,0,0,1,0,60";
  const prt::relight::RadiosityRenderSummary s = prt::relight::render_radiosity(
      r, quad, radiance, prt::relight::radiosity_camera(r, quad).camera);
  CHECK(s.exposure_auto);
  CHECK(s.exposure_ev == prt::relight::choose_auto_exposure(radiance));
  CHECK(std::fmod(double(s.exposure_ev) * 4.0, 1.0) == 0.0);  // a multiple of 1/4 EV, exactly
  r.exposure_ev = 0.3f;                                       // a given one is kept as it is
  const prt::relight::RadiosityRenderSummary given = prt::relight::render_radiosity(
      r, quad, radiance, prt::relight::radiosity_camera(r, quad).camera);
  CHECK_FALSE(given.exposure_auto);
  CHECK(given.exposure_ev == 0.3f);
}

TEST_CASE("a radiosity solution is drawn from its vertex radiance: CSV, image, vertex colours",
          "[relight][radiosity-render]") {
  const fs::path dir = prt::test::output_path("radiosity_render");
  fs::remove_all(dir);
  fs::create_directories(dir);
  const prt::scene::Scene quad =
      prt::scene::make_quad({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}, 2, 2, glm::vec3(0.5f));
  std::vector<float> radiance(3 * quad.vertex_count());
  for (std::size_t i = 0; i < radiance.size(); ++i) radiance[i] = 0.25f + 0.125f * float(i % 7);
  RadiosityRenderRequest r;
  r.scene_path = (dir / "quad.obj").string();
  r.output_path = (dir / "quad.exr").string();
  r.vertex_colors_path = (dir / "quad.glb").string();
  r.csv_path = (dir / "quad.csv").string();
  r.render.width = 32;
  r.render.height = 24;
  r.render.samples_per_axis = 1;
  r.camera = "0,0,3,0,0,0,0,1,0,60";
  prt::relight::check_radiosity_outputs(r);
  const prt::relight::RadiosityRenderSummary s = prt::relight::render_radiosity(
      r, quad, radiance, prt::relight::radiosity_camera(r, quad).camera);
  CHECK(s.files_written ==
        std::vector<std::string>{r.output_path, r.vertex_colors_path, r.csv_path});
  for (const std::string& file : s.files_written) CHECK(fs::file_size(file) > 0);
  // The CSV holds the given radiance, vertex by vertex (%.9g: floats round-trip exactly).
  std::ifstream csv(r.csv_path);
  std::string line;
  std::getline(csv, line);
  CHECK(line == "index,x,y,z,r,g,b");
  std::size_t v = 0;
  for (; std::getline(csv, line); ++v) {
    std::istringstream row(line);
    std::string cell;
    for (int column = 0; std::getline(row, cell, ','); ++column)
      if (column >= 4) CHECK(std::stof(cell) == radiance[3 * v + std::size_t(column - 4)]);
  }
  CHECK(v == quad.vertex_count());
  // Radiance for other vertices is refused before anything is drawn.
  CHECK_THROWS(prt::relight::render_radiosity(r, quad, std::vector<float>(3),
                                              prt::relight::radiosity_camera(r, quad).camera));
}

TEST_CASE("radiosity outputs: image, GLB and CSV refused by type, directory and the scene",
          "[relight][radiosity-render]") {
  RadiosityRenderRequest r;
  r.scene_path = prt::test::output_path("radiosity_render_scene.obj").string();
  std::ofstream(r.scene_path) << "v 0 0 0\n";
  r.output_path = "out.jpg";
  CHECK_THROWS_WITH(prt::relight::check_radiosity_outputs(r),
                    "out.jpg: unsupported output type '.jpg'");
  r.output_path = "out.PNG";
  prt::relight::check_radiosity_outputs(r);  // the case of the extension does not matter
  r.vertex_colors_path = "colours.gltf";
  CHECK_THROWS_WITH(prt::relight::check_radiosity_outputs(r),
                    "colours.gltf: unsupported output type '.gltf'");
  r.vertex_colors_path.clear();
  r.csv_path = "no_such_directory/out.csv";
  CHECK_THROWS_WITH(prt::relight::check_radiosity_outputs(r),
                    "no_such_directory/out.csv: directory no_such_directory does not exist");
  r.csv_path = r.scene_path;
  CHECK_THROWS_WITH(prt::relight::check_radiosity_outputs(r),
                    r.scene_path + ": an output may not overwrite the input scene");
}
