// `prt relight --material` with glossy files: a material's BRDF replaced at shading time equals
// a bake with that material wherever the bake's transport does not depend on the materials
// (shadowed transfer), a rougher lobe lowers the highlight, and bad overrides are refused in
// one line before anything is written. Textured roughness (glTF metallicRoughnessTexture) and
// textured anisotropy (KHR_materials_anisotropy's anisotropyTexture: strength per-vertex
// materials, direction per-vertex tangents) reach the glossy file.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"
#include "prt/formats/glossy_transfer_file.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "support/metal_rough_glb.h"
#include "support/texture_strip_glb.h"

using namespace prt::test::cli;

namespace {

// Two unit spheres, materials "left" and "right", 3 units apart, and a dark sky with a small
// bright sun toward +X+Y.
struct Files {
  fs::path scene, env;
};

Files make_two_spheres(const fs::path& dir) {
  Files f{dir / "spheres.glb", dir / "sun.exr"};
  prt::scene::Scene scene =
      prt::scene::make_uv_sphere({-1.5f, 0, 0}, 1.f, 24, 48, false, glm::vec3(0.5f), "left");
  prt::scene::append_scene(scene, prt::scene::make_uv_sphere({1.5f, 0, 0}, 1.f, 24, 48, false,
                                                             glm::vec3(0.5f), "right"));
  prt::scene::write_glb(f.scene.string(), scene);
  const int w = 64, h = 32;
  std::vector<float> pixels(3 * w * h, 0.05f);
  for (int r = 9; r < 12; ++r)
    for (int c = 7; c < 10; ++c)
      for (int k = 0; k < 3; ++k) pixels[3 * (r * w + c) + k] = 400.f;
  prt::relight::write_image(f.env.string(), w, h, 3, pixels.data());
  return f;
}

const std::string kWard = "ward:rho_d=0.1,rho_s=0.6,alpha=0.12";
const std::string kGgx = "ggx:roughness=0.45,f0=0.9/0.6/0.3,kd=0.05";

// Bakes `f` with glossy shadowed transfer at order 6 with the given --material options.
fs::path bake(const Files& f, const fs::path& out, const std::string& materials) {
  const RunResult r = run(prt_cli() + " bake " + f.scene.string() + " --glossy -o " + out.string() +
                          " --order 6 --samples 64 --quiet " + materials);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  return out;
}

// Relights to an image and a CSV toward the eye (0, 1, 6); returns the CSV's r,g,b per vertex.
std::vector<double> relight_csv(const Files& f, const fs::path& prtg, const fs::path& dir,
                                const std::string& name, const std::string& extra) {
  const fs::path csv = dir / (name + ".csv");
  const RunResult r = run(prt_cli() + " relight " + f.scene.string() + " " + prtg.string() + " " +
                          f.env.string() + " -o " + (dir / (name + ".png")).string() +
                          " --size 64x48 --spp 1 --quiet --camera 0,1,6,0,0,0,0,1,0,50 "
                          "--eye 0,1,6 --csv " +
                          csv.string() + " " + extra);
  INFO(r.err);
  REQUIRE(r.exit_code == 0);
  std::istringstream in(slurp(csv));
  std::string line;
  std::getline(in, line);  // header
  std::vector<double> rgb;
  while (std::getline(in, line)) {
    std::vector<double> fields;
    std::istringstream cells(line);
    std::string cell;
    while (std::getline(cells, cell, ',')) fields.push_back(std::stod(cell));
    REQUIRE(fields.size() == 7);
    rgb.insert(rgb.end(), fields.begin() + 4, fields.end());
  }
  return rgb;
}

double max_abs(const std::vector<double>& v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::fabs(x));
  return m;
}

// Largest luminance of the vertices [first, first + count).
double peak_luminance(const std::vector<double>& rgb, std::size_t first, std::size_t count) {
  double peak = 0;
  for (std::size_t v = first; v < first + count; ++v)
    peak = std::max(peak, 0.2126 * rgb[3 * v] + 0.7152 * rgb[3 * v + 1] + 0.0722 * rgb[3 * v + 2]);
  return peak;
}

constexpr std::size_t kSphereVertices = 2 + 23 * 48;

}  // namespace

TEST_CASE("cli: glossy relight --material equals a bake with that material (shadowed transfer)",
          "[cli][materials]") {
  const fs::path dir = scratch("glossy_override");
  const Files f = make_two_spheres(dir);
  // File A: both spheres Ward. File B: the right sphere GGX. Shadowed transfer (visibility
  // times SH, rotated into the vertex frame) does not depend on any material, and both bakes
  // use the same seed, so the matrices agree and the right sphere's own BRDF is all that
  // differs: relighting A with right=GGX must give B's values. Allowed difference: 1e-5 of the
  // peak (the two runs do the same float arithmetic; the margin only covers rounding of the CSV,
  // 9 significant digits) — against a difference of tens of percent without the override.
  const fs::path a = bake(f, dir / "a.prtg", "--material '*=" + kWard + "'");
  const fs::path b =
      bake(f, dir / "b.prtg", "--material '*=" + kWard + "' --material 'right=" + kGgx + "'");
  const std::vector<double> from_b = relight_csv(f, b, dir, "b", "");
  const std::vector<double> plain_a = relight_csv(f, a, dir, "a", "");
  const std::vector<double> a_as_b =
      relight_csv(f, a, dir, "ab", "--material 'right=" + kGgx + "'");
  REQUIRE(from_b.size() == 3 * 2 * kSphereVertices);
  REQUIRE(a_as_b.size() == from_b.size());
  const double peak = max_abs(from_b);
  REQUIRE(peak > 0);
  double worst = 0, worst_left = 0, without = 0;
  for (std::size_t i = 0; i < from_b.size(); ++i) {
    worst = std::max(worst, std::fabs(a_as_b[i] - from_b[i]));
    if (i < 3 * kSphereVertices)
      worst_left = std::max(worst_left, std::fabs(a_as_b[i] - plain_a[i]));
    without = std::max(without, std::fabs(plain_a[i] - from_b[i]));
  }
  INFO("peak " << peak << ", |override - bake| " << worst << ", without override " << without);
  CHECK(worst <= 1e-5 * peak);
  CHECK(without > 0.1 * peak);  // the override changed what it had to change
  CHECK(worst_left == 0.0);     // and nothing on the sphere it does not name
}

TEST_CASE("cli: glossy relight --material: a rougher lobe lowers the highlight peak",
          "[cli][materials]") {
  const fs::path dir = scratch("glossy_override_rough");
  const Files f = make_two_spheres(dir);
  const fs::path a = bake(f, dir / "a.prtg", "--material '*=" + kWard + "'");
  // The same F0 and Lambert layer, GGX α = r² from 0.09 to 0.49: the lobe's peak value
  // D(0) = 1/(π α²) drops ~30-fold, the SH order 6 blurs the sharp one, but the highlight's
  // peak radiance must still fall clearly (by more than a third) while the reflected energy
  // spreads (the mean over the sphere stays within a factor 2). Both under the same lighting:
  // the same fixed window, the Laplacian λ = 0.182 that --window auto chose from this map's
  // irradiance before it chose on the vertices (now it picks one per material's shading).
  const auto smooth = relight_csv(
      f, a, dir, "s",
      "--window laplacian --window-strength 0.182 --material '*=ggx:roughness=0.3,f0=0.9,kd=0.05'");
  const auto rough = relight_csv(
      f, a, dir, "r",
      "--window laplacian --window-strength 0.182 --material '*=ggx:roughness=0.7,f0=0.9,kd=0.05'");
  const double peak_smooth = peak_luminance(smooth, 0, kSphereVertices);
  const double peak_rough = peak_luminance(rough, 0, kSphereVertices);
  double sum_smooth = 0, sum_rough = 0;
  for (std::size_t i = 0; i < 3 * kSphereVertices; ++i)
    sum_smooth += smooth[i], sum_rough += rough[i];
  INFO("peak smooth " << peak_smooth << ", rough " << peak_rough << "; sums " << sum_smooth << ", "
                      << sum_rough);
  CHECK(peak_rough < 0.67 * peak_smooth);
  CHECK(sum_rough > 0.5 * sum_smooth);
  CHECK(sum_rough < 2.0 * sum_smooth);
}

TEST_CASE("cli: glossy relight --material: bad overrides are one-line errors, nothing written",
          "[cli][materials]") {
  const fs::path dir = scratch("glossy_override_bad");
  const Files f = make_two_spheres(dir);
  const fs::path a = bake(f, dir / "a.prtg", "--material '*=" + kWard + "'");
  const fs::path diffuse = dir / "d.prt";
  REQUIRE(run(prt_cli() + " bake " + f.scene.string() + " -o " + diffuse.string() +
              " --order 3 --samples 16 --quiet")
              .exit_code == 0);
  const std::vector<std::string> before = files_in(dir);
  const std::string out = (dir / "x.png").string(), csv = (dir / "x.csv").string();
  const auto relight = [&](const fs::path& file, const std::string& value) {
    return run(prt_cli() + " relight " + f.scene.string() + " " + file.string() + " " +
               f.env.string() + " -o " + out + " --size 32x24 --spp 1 --eye 0,1,6 --csv " + csv +
               " --material '" + value + "'");
  };
  for (const std::string value :
       {"left=ggx:roughness=0", "left=ggx:alpha=nan", "left=blinn-phong:ks=0.3,s=-2",
        "left=velvet:alpha=0.2", "left=ggx:roughness=0.3,shine=2"}) {
    const RunResult r = relight(a, value);
    INFO(value << ": " << r.err);
    require_one_line_error(r, "--material " + value + ": ");
    CHECK(r.exit_code == 2);
  }
  const RunResult unknown = relight(a, "chrome=ggx:alpha=0.1");
  require_one_line_error(unknown, "no material or primitive named 'chrome'");
  CHECK(unknown.err.find("'left', 'right'") != std::string::npos);
  // A diffuse file's BRDF is baked into its coefficients: refused by name.
  const RunResult on_diffuse =
      run(prt_cli() + " relight " + f.scene.string() + " " + diffuse.string() + " " +
          f.env.string() + " -o " + out + " --material 'left=ggx:alpha=0.1'");
  require_one_line_error(on_diffuse, "--material applies to glossy files");
  CHECK(files_in(dir) == before);
}

TEST_CASE(
    "cli: textured roughness reaches the glossy file, and a missing texture stops the glossy "
    "bake only",
    "[cli][materials]") {
  const fs::path dir = scratch("glossy_mr_texture");
  // Left half of the strip: roughness 64/255, dielectric; right half: roughness 200/255, metal.
  const fs::path good = dir / "good.glb", missing = dir / "missing.glb";
  prt::test::write_metal_rough_glb(good.string(), 64, 0, 200, 255);
  prt::test::write_metal_rough_glb(missing.string(), 64, 0, 200, 255,
                                   prt::test::MetalRoughImage::kUri, "absent_mr.png");
  const fs::path out = dir / "good.prtg";
  const RunResult baked = run(prt_cli() + " bake " + good.string() + " --glossy -o " +
                              out.string() + " --order 3 --samples 16 --quiet");
  INFO(baked.err);
  REQUIRE(baked.exit_code == 0);
  const prt::Result<prt::GlossyTransferData> data = prt::read_glossy_transfer_file(out.string());
  REQUIRE(data.ok());
  REQUIRE(data->materials.size() == 2);
  for (std::size_t v = 0; v < 16; ++v) {
    const prt::brdf::Material& m = data->materials[data->material_of_vertex[v]];
    const double r = v % 8 >= 4 ? 200 / 255.0 : 64 / 255.0;
    INFO("vertex " << v << ": " << prt::brdf::describe(m));
    CHECK(m.alpha_x == Approx(r * r).epsilon(1e-6));  // texels are stored as float
  }

  const std::vector<std::string> before = files_in(dir);
  const RunResult refused = run(prt_cli() + " bake " + missing.string() + " --glossy -o " +
                                (dir / "missing.prtg").string() + " --order 3 --samples 16");
  require_one_line_error(refused, "metallicRoughnessTexture");
  CHECK(refused.err.find((dir / "absent_mr.png").string() + ": no such file") != std::string::npos);
  CHECK(files_in(dir) == before);
  // The diffuse bake does not use the BRDF; prt info names the unusable texture.
  const RunResult diffuse = run(prt_cli() + " bake " + missing.string() + " -o " +
                                (dir / "missing.prt").string() + " --samples 16 --quiet");
  INFO(diffuse.err);
  CHECK(diffuse.exit_code == 0);
  const RunResult info = run(prt_cli() + " info " + missing.string());
  CHECK(info.exit_code == 0);
  CHECK(info.out.find("not used: material 'patchy': metallicRoughnessTexture") !=
        std::string::npos);
}

TEST_CASE(
    "cli: a textured anisotropy direction reaches the glossy file's tangents, its strength the "
    "materials, and a bad specularTexture index stops the glossy bake in one line naming the file",
    "[cli][materials]") {
  const fs::path dir = scratch("glossy_aniso_texture");
  nlohmann::json m = {{"name", "brushed"},
                      {"pbrMetallicRoughness",
                       {{"baseColorFactor", {0.9, 0.9, 0.9, 1.0}},
                        {"metallicFactor", 1.0},
                        {"roughnessFactor", 0.4}}}};
  const double strength = 0.8, rotation = 0.5;
  m["extensions"]["KHR_materials_anisotropy"] = {{"anisotropyStrength", strength},
                                                 {"anisotropyRotation", rotation},
                                                 {"anisotropyTexture", {{"index", 0}}}};
  // Columns: direction (x, y) = 2·(R, G)/255 − 1, strength factor × B/255 (linear texels).
  const std::vector<std::vector<unsigned char>> texels = {
      {255, 128, 255}, {128, 255, 128}, {0, 0, 64}, {200, 40, 0}};
  const fs::path good = dir / "brushed.glb", bad = dir / "bad_index.glb";
  prt::test::write_glb_text(
      good.string(), prt::test::texture_strip_gltf(m, {prt::test::column_png(3, texels)}).dump());
  const fs::path out = dir / "brushed.prtg";
  const RunResult baked = run(prt_cli() + " bake " + good.string() + " --glossy -o " +
                              out.string() + " --order 3 --samples 16 --quiet");
  INFO(baked.err);
  REQUIRE(baked.exit_code == 0);
  const prt::Result<prt::GlossyTransferData> data = prt::read_glossy_transfer_file(out.string());
  REQUIRE(data.ok());
  REQUIRE(data->tangents.size() == 4 * 8);
  CHECK(data->materials.size() == 4);
  const double c = std::cos(rotation), s = std::sin(rotation);
  for (std::size_t v = 0; v < 8; ++v) {
    const std::vector<unsigned char>& t = texels[v % 4];
    const double x = 2.0 * t[0] / 255.0 - 1.0, y = 2.0 * t[1] / 255.0 - 1.0;
    const double len = std::hypot(x, y);
    INFO("vertex " << v);
    // The file's TANGENT is +X, the bitangent +Y: the stored tangent is the rotated direction.
    CHECK(data->tangents[4 * v] == Approx((c * x - s * y) / len).margin(1e-6));
    CHECK(data->tangents[4 * v + 1] == Approx((s * x + c * y) / len).margin(1e-6));
    CHECK(data->tangents[4 * v + 2] == Approx(0.0).margin(1e-6));
    const double sv = strength * t[2] / 255.0;
    const prt::brdf::Material& mat = data->materials[data->material_of_vertex[v]];
    CHECK(mat.alpha_x == Approx(0.16 + 0.84 * sv * sv).epsilon(1e-6));
    CHECK(mat.alpha_y == Approx(0.16).epsilon(1e-6));
  }

  m["extensions"]["KHR_materials_specular"] = {{"specularTexture", {{"index", 7}}}};
  prt::test::write_glb_text(
      bad.string(), prt::test::texture_strip_gltf(m, {prt::test::column_png(3, texels)}).dump());
  const std::vector<std::string> before = files_in(dir);
  const RunResult refused = run(prt_cli() + " bake " + bad.string() + " --glossy -o " +
                                (dir / "bad.prtg").string() + " --order 3 --samples 16");
  require_one_line_error(refused, bad.string() +
                                      ": material 'brushed': specularTexture texture 7 "
                                      "does not exist");
  CHECK(files_in(dir) == before);
}

// The white-furnace check (prt/brdf/energy_check.h): a --material that reflects more light than
// arrives is a command-line error (exit 2), one from a scene file an input error (exit 1); both
// name the material and the angle, and nothing is written.
TEST_CASE("cli: materials that create energy are refused before the bake", "[cli][materials]") {
  const fs::path dir = scratch("glossy_energy");
  const Files f = make_two_spheres(dir);
  const std::vector<std::string> before = files_in(dir);
  const std::string out = (dir / "x.prtg").string();
  const RunResult r = run(prt_cli() + " bake " + f.scene.string() + " --glossy --bounces 3 -o " +
                          out + " --material '*=ggx:roughness=0.9,kd=0.95,f0=0.95'");
  INFO(r.err);
  require_one_line_error(r, "material '*' ggx(alpha 0.81x0.81, F0 0.95, diffuse 0.95) reflects ");
  CHECK(r.err.find("x the light arriving at ") != std::string::npos);
  CHECK(r.err.find("°: directional albedo must not exceed 1") != std::string::npos);
  CHECK(r.exit_code == 2);
  // The additive glTF layering with a white base exceeds 1; the spec's mix is accepted.
  const RunResult additive = run(prt_cli() + " bake " + f.scene.string() + " --glossy -o " + out +
                                 " --material 'left=gltf-additive:base=1,roughness=0.5'");
  require_one_line_error(additive, "material 'left' ggx(");
  CHECK(additive.exit_code == 2);
  CHECK(files_in(dir) == before);

  const fs::path obj = dir / "shiny.obj", mtl = dir / "shiny.mtl";
  {
    std::ofstream m(mtl);
    m << "newmtl shiny\nKd 0.5 0.5 0.5\nKs 0.5 0.5 0.5\nNs 10\nillum 2\n";
    std::ofstream o(obj);
    o << "mtllib shiny.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nusemtl shiny\nf 1//1 2//1 3//1\n";
  }
  const std::vector<std::string> with_obj = files_in(dir);
  const RunResult from_file =
      run(prt_cli() + " bake " + obj.string() + " --glossy -o " + out + " --samples 16");
  INFO(from_file.err);
  require_one_line_error(from_file, obj.string() + ": material 'shiny' blinn-phong(");
  CHECK(from_file.err.find("directional albedo must not exceed 1") != std::string::npos);
  CHECK(from_file.exit_code == 1);
  CHECK(files_in(dir) == with_obj);
}

// "converged" in a glossy file's metadata is true only when the last bounce changed the transfer
// by at most the tolerance: a single bounce of an interreflecting pair of spheres is not.
TEST_CASE("cli: a glossy file says converged only when the bounces reached the tolerance",
          "[cli][materials]") {
  const fs::path dir = scratch("glossy_converged");
  const Files f = make_two_spheres(dir);
  const auto converged = [&](const std::string& bounces, const std::string& name) {
    const fs::path out = dir / name;
    const RunResult b = run(prt_cli() + " bake " + f.scene.string() + " --glossy -o " +
                            out.string() + " --order 3 --samples 32 --quiet --bounces " + bounces +
                            " --material 'left=gltf:base=0.8,roughness=0.4'");
    INFO(b.err);
    REQUIRE(b.exit_code == 0);
    const RunResult info = run(prt_cli() + " info " + out.string() + " --json");
    REQUIRE(info.exit_code == 0);
    const std::size_t at = info.out.find("\"converged\"");
    REQUIRE(at != std::string::npos);
    return info.out.substr(at, 20).find("true") != std::string::npos;
  };
  CHECK_FALSE(converged("1", "one.prtg"));
  CHECK(converged("-1", "solved.prtg"));
}
