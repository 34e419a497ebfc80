// `prt relight` with glossy transfer files: the camera's eye point drives the view direction
// (highlights move with the camera), the CSV needs --eye, and the turntable orbits the camera.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/glossy_transfer_baker.h"
#include "cli_test_support.h"
#include "prt/formats/glossy_transfer_file.h"
#include "relight/image_io.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"

using namespace prt::test::cli;

namespace {

struct GlossyFiles {
  fs::path scene, glossy, env;
};

// A shiny sphere (isotropic Ward, α 0.12) baked at order 6, and a dark sky with a small bright
// sun towards +X+Y: one clear highlight whose place on the sphere depends on the view.
GlossyFiles make_glossy_sphere(const fs::path& dir) {
  GlossyFiles f{dir / "sphere.glb", dir / "sphere.prtg", dir / "sun.exr"};
  prt::scene::write_glb(f.scene.string(),
                        prt::scene::make_uv_sphere({0, 0, 0}, 1.f, 32, 64, false, glm::vec3(0.5f)));
  prt::scene::Scene scene = prt::scene::load_scene(f.scene.string());
  prt::brdf::Material ward;
  ward.model = prt::brdf::MaterialModel::kWard;
  ward.diffuse = prt::brdf::grey(0.1);
  ward.specular = prt::brdf::grey(0.6);
  ward.alpha_x = ward.alpha_y = 0.12;
  for (auto& primitive : scene.primitives) primitive.brdf = ward;
  prt::bake::GlossyBakeOptions options;
  options.order = 6;
  options.samples = 64;
  const prt::bake::GlossyBakeResult baked = prt::bake::bake_glossy_transfer(scene, options);
  REQUIRE(prt::write_glossy_transfer_file(f.glossy.string(), baked.data).ok());
  const int w = 64, h = 32;
  std::vector<float> pixels(3 * w * h, 0.05f);
  for (int r = 9; r < 12; ++r)
    for (int c = 7; c < 10; ++c)
      for (int k = 0; k < 3; ++k) pixels[3 * (r * w + c) + k] = 400.f;
  prt::relight::write_image(f.env.string(), w, h, 3, pixels.data());
  return f;
}

std::string relight(const GlossyFiles& f, const fs::path& out, const std::string& extra) {
  return prt_cli() + " relight " + f.scene.string() + " " + f.glossy.string() + " " +
         f.env.string() + " -o " + out.string() + " --size 96x72 --spp 1 --quiet " + extra;
}

std::string camera(const std::string& eye) {
  return "--camera " + eye + ",0,0,0,0,1,0,40";
}

// Row and column of the brightest pixel (luminance).
std::pair<int, int> brightest(const prt::scene::FloatImage& image) {
  int best = 0;
  float value = -1.f;
  for (int i = 0; i < image.width * image.height; ++i) {
    const float* p = &image.pixels[std::size_t(3 * i)];
    const float y = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
    if (y > value) value = y, best = i;
  }
  return {best / image.width, best % image.width};
}

}  // namespace

TEST_CASE("cli: glossy relight: highlights move with the camera's eye point") {
  const fs::path dir = scratch("glossy_highlight");
  const GlossyFiles f = make_glossy_sphere(dir);
  // Two cameras on the same circle about the target, both with the sphere filling the middle of
  // the view; the sun is fixed. The highlight sits near the half-way direction between the sun and
  // the eye, so it moves across the sphere as the eye moves: the brightest pixel must move by
  // more than 5 pixels (of 96), and the same camera twice gives the same image bit for bit.
  const fs::path a = dir / "a.exr", b = dir / "b.exr", a2 = dir / "a2.exr";
  REQUIRE(run(relight(f, a, camera("0,0,4"))).exit_code == 0);
  REQUIRE(run(relight(f, b, camera("2.83,0,2.83"))).exit_code == 0);
  REQUIRE(run(relight(f, a2, camera("0,0,4"))).exit_code == 0);
  const auto ia = prt::relight::read_image(a.string()), ib = prt::relight::read_image(b.string());
  REQUIRE(ia.pixels == prt::relight::read_image(a2.string()).pixels);
  REQUIRE(ia.pixels != ib.pixels);
  const auto pa = brightest(ia), pb = brightest(ib);
  INFO("brightest pixel a: " << pa.first << "," << pa.second << "  b: " << pb.first << ","
                             << pb.second);
  CHECK(std::hypot(pa.first - pb.first, pa.second - pb.second) > 5.0);
}

TEST_CASE("cli: glossy relight: --csv and --vertex-colors need --eye and the CSV depends on it") {
  const fs::path dir = scratch("glossy_eye");
  const GlossyFiles f = make_glossy_sphere(dir);
  const std::vector<std::string> before = files_in(dir);
  for (const std::string& extra : {std::string("--csv ") + (dir / "v.csv").string(),
                                   std::string("--vertex-colors ") + (dir / "v.glb").string()}) {
    const RunResult r = run(relight(f, dir / "x.png", extra));
    require_one_line_error(r, "--eye");
    CHECK(r.err.find("sphere.prtg") != std::string::npos);
  }
  CHECK(files_in(dir) == before);  // nothing written, not even the image
  require_one_line_error(
      run(relight(f, dir / "x.png", "--eye 1,2 --csv " + (dir / "v.csv").string())), "--eye");
  // --eye without a CSV or vertex colours does nothing: refused by name, as is an orbit without
  // a turntable.
  require_one_line_error(run(relight(f, dir / "x.png", "--eye 0,0,4")), "--eye");
  require_one_line_error(run(relight(f, dir / "x.png", "--turntable-orbit camera")),
                         "--turntable-orbit");
  CHECK(files_in(dir) == before);

  const fs::path c1 = dir / "one.csv", c2 = dir / "two.csv";
  REQUIRE(run(relight(f, dir / "1.png", "--eye 0,0,4 --csv " + c1.string())).exit_code == 0);
  REQUIRE(run(relight(f, dir / "2.png", "--eye 4,0,0 --csv " + c2.string())).exit_code == 0);
  const std::string s1 = slurp(c1), s2 = slurp(c2);
  CHECK(line_count(s1) == line_count(s2));
  CHECK(s1 != s2);
}

TEST_CASE(
    "cli: glossy relight: the turntable orbits the camera and --eye is refused for other files") {
  const fs::path dir = scratch("glossy_turntable");
  const GlossyFiles f = make_glossy_sphere(dir);
  const fs::path out = dir / "t.exr";
  REQUIRE(
      run(relight(f, out, camera("0,0,4") + " --turntable 3 --turntable-orbit camera")).exit_code ==
      0);
  std::vector<std::pair<int, int>> peaks;
  for (int i = 0; i < 3; ++i) {
    const fs::path frame = dir / ("t_00" + std::to_string(i) + ".exr");
    REQUIRE(fs::exists(frame));
    peaks.push_back(brightest(prt::relight::read_image(frame.string())));
  }
  // Under fixed light the camera's orbit makes the highlight slide across the image.
  CHECK(peaks[0] != peaks[1]);
  CHECK(peaks[1] != peaks[2]);
  // A coefficient file has no view dependence: --eye is refused by name.
  const fs::path prt_file = dir / "diffuse.prt";
  REQUIRE(run(prt_cli() + " bake " + f.scene.string() + " -o " + prt_file.string() +
              " --order 3 --samples 16 --quiet")
              .exit_code == 0);
  require_one_line_error(
      run(prt_cli() + " relight " + f.scene.string() + " " + prt_file.string() + " " +
          f.env.string() + " -o " + (dir / "d.png").string() + " --eye 0,0,4"),
      "--eye");
}

TEST_CASE("cli: glossy relight: the turntable orbits the scene's centre, or --target") {
  // The default orbit centre is the centre of the scene's bounds (the sphere's centre, the
  // origin): --target 0,0,0 gives the same frames bit for bit; another target moves every frame
  // but the first (frame 0 is the camera itself). --target needs an orbiting camera.
  const fs::path dir = scratch("glossy_orbit_target");
  const GlossyFiles f = make_glossy_sphere(dir);
  const std::string table = camera("0,1,4") + " --turntable 2 --turntable-orbit camera";
  REQUIRE(run(relight(f, dir / "d.exr", table)).exit_code == 0);
  REQUIRE(run(relight(f, dir / "o.exr", table + " --target 0,0,0")).exit_code == 0);
  REQUIRE(run(relight(f, dir / "x.exr", table + " --target 1.5,0,0")).exit_code == 0);
  const auto pixels = [&](const std::string& name) {
    return prt::relight::read_image((dir / name).string()).pixels;
  };
  CHECK(pixels("d_000.exr") == pixels("o_000.exr"));
  CHECK(pixels("d_001.exr") == pixels("o_001.exr"));
  CHECK(pixels("d_000.exr") == pixels("x_000.exr"));
  CHECK(pixels("d_001.exr") != pixels("x_001.exr"));
  const std::vector<std::string> before = files_in(dir);
  require_one_line_error(run(relight(f, dir / "n.exr", camera("0,1,4") + " --target 0,0,0")),
                         "--target");
  require_one_line_error(run(relight(f, dir / "n.exr", table + " --target 0,0")), "--target");
  CHECK(files_in(dir) == before);
}
