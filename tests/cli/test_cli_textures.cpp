// tests/cli/test_cli_textures.cpp — textured scenes through the `prt` executable: a glTF with a
// PNG base-colour texture bakes with the albedo kept apart, `prt relight` paints the texture per
// pixel (read back from the EXR it writes), the CSV says what it holds, and a missing texture is
// one warning line naming the file, not a failure.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "relight/image_io.h"
#include "support/png_writer.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Run {
  int exit_code = 0;
  std::string out, err;
};

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// Runs `command` in the shell; stdout and stderr captured in files named by process id.
Run run(const std::string& command) {
  static int counter = 0;
  const fs::path dir = prt::test::output_path("cli_textures");
  fs::create_directories(dir);
  const std::string stem = "run" + std::to_string(::getpid()) + "_" + std::to_string(counter++);
  const fs::path out = dir / (stem + ".out"), err = dir / (stem + ".err");
  const int status = std::system((command + " >" + out.string() + " 2>" + err.string()).c_str());
  Run r;
  r.exit_code = status == -1 ? -1 : WEXITSTATUS(status);
  r.out = slurp(out);
  r.err = slurp(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

double linear_of_byte(int byte) {  // IEC 61966-2-1
  const double c = byte / 255.0;
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

// A one-cell quad y = 0, x and z in [0, 1], facing +Y, texture coordinates (x, z), with a
// material whose baseColorTexture is image `uri`; written as DIR/quad.gltf + quad.bin.
fs::path write_textured_quad(const fs::path& dir, const std::string& uri) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 1, 0, 1, 0, 0, 1};
  const float normals[] = {0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0};
  const float uv[] = {0, 0, 1, 0, 1, 1, 0, 1};
  const uint32_t indices[] = {0, 2, 1, 0, 3, 2};  // counter-clockwise seen from +Y
  std::vector<unsigned char> bin;
  const auto append = [&](const void* p, std::size_t n) {
    const auto* b = static_cast<const unsigned char*>(p);
    bin.insert(bin.end(), b, b + n);
  };
  append(positions, sizeof positions);
  append(normals, sizeof normals);
  append(uv, sizeof uv);
  append(indices, sizeof indices);
  std::ofstream(dir / "quad.bin", std::ios::binary)
      .write(reinterpret_cast<const char*>(bin.data()), static_cast<std::streamsize>(bin.size()));
  const json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TEXCOORD_0", 2}}},
            {"indices", 3},
            {"material", 0}}}}}}},
      {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", uri}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", bin.size()}}}},
      {"bufferViews",
       {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 48}, {"byteLength", 48}},
        {{"buffer", 0}, {"byteOffset", 96}, {"byteLength", 32}},
        {{"buffer", 0}, {"byteOffset", 128}, {"byteLength", 24}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"count", 4},
         {"type", "VEC3"},
         {"min", {0, 0, 0}},
         {"max", {1, 0, 1}}},
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5125}, {"count", 6}, {"type", "SCALAR"}}}}};
  std::ofstream(dir / "quad.gltf") << doc.dump(1);
  return dir / "quad.gltf";
}

}  // namespace

TEST_CASE(
    "cli: a textured glTF bakes with the albedo apart and relights with the texture per pixel") {
  const fs::path dir = prt::test::output_path("cli_textures") / "halves";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // 16 × 16 texels: the left half (u < ½) one colour, the right half another.
  const int left[3] = {200, 60, 40}, right[3] = {40, 90, 200};
  std::vector<unsigned char> texels;
  for (int j = 0; j < 16; ++j)
    for (int i = 0; i < 16; ++i)
      for (int c = 0; c < 3; ++c)
        texels.push_back(static_cast<unsigned char>(i < 8 ? left[c] : right[c]));
  prt::test::write_png((dir / "halves.png").string(), 16, 16, 3, texels);
  const fs::path scene = write_textured_quad(dir, "halves.png");
  // A white sky of radiance 1: an open surface's exit radiance is its albedo.
  std::vector<float> sky(3 * 64 * 32, 1.f);
  prt::relight::write_image((dir / "white.hdr").string(), 64, 32, 3, sky.data());

  const std::string prt = PRT_CLI_PATH;
  const fs::path file = dir / "quad.prt";
  const Run baked = run(prt + " bake " + scene.string() + " -o " + file.string() +
                        " --transfer shadowed --order 3 --samples 16 --quiet");
  INFO(baked.err);
  REQUIRE(baked.exit_code == 0);
  const Run info = run(prt + " info " + file.string() + " --json");
  REQUIRE(info.exit_code == 0);
  CHECK(json::parse(info.out)["albedo_folded"] == false);

  // Looking straight down from (½, 1.5, ½) with +X to the right: the image's left half shows
  // x < ½ (u < ½). Pixel columns 16 and 48 of 64 look at x ≈ 0.24 and 0.76.
  const fs::path exr = dir / "quad.exr", csv = dir / "quad.csv";
  const Run relit = run(prt + " relight " + scene.string() + " " + file.string() + " " +
                        (dir / "white.hdr").string() + " -o " + exr.string() + " --csv " +
                        csv.string() + " --size 64x64 --camera 0.5,1.5,0.5,0.5,0,0.5,0,0,-1,40");
  INFO(relit.err);
  REQUIRE(relit.exit_code == 0);
  // The CSV holds the exit radiance at the vertices and, the albedo being apart, the light
  // before it: about 1 under this sky (the map's projection is exact only up to quadrature; the
  // vertices' sampled transfer differs in the 4th decimal). A pixel shows the light interpolated
  // between the vertices times the texture: pixel / texture lies between the vertices' extremes.
  std::istringstream table(slurp(csv));
  std::string header, row;
  std::getline(table, header);
  CHECK(header == "index,x,y,z,r,g,b,r_per_albedo,g_per_albedo,b_per_albedo");
  double lowest[3] = {2, 2, 2}, highest[3] = {0, 0, 0};
  int vertices = 0;
  while (std::getline(table, row)) {
    std::vector<double> fields;
    std::istringstream cells(row);
    for (std::string cell; std::getline(cells, cell, ',');) fields.push_back(std::stod(cell));
    REQUIRE(fields.size() == 10);
    for (std::size_t c = 0; c < 3; ++c) {
      CHECK(fields[7 + c] == Approx(1.0).margin(2e-3));
      lowest[c] = std::min(lowest[c], fields[7 + c]);
      highest[c] = std::max(highest[c], fields[7 + c]);
    }
    ++vertices;
  }
  REQUIRE(vertices == 4);
  const prt::relight::FloatImage image = prt::relight::read_image(exr.string());
  REQUIRE(image.width == 64);
  for (const auto& [col, bytes] : {std::pair{16, left}, std::pair{48, right}})
    for (int r : {20, 32, 44})
      for (int c = 0; c < 3; ++c) {
        const std::size_t at = static_cast<std::size_t>((r * 64 + col) * image.channels + c);
        const double light = image.pixels[at] / linear_of_byte(bytes[c]);
        INFO("pixel " << col << "," << r << " channel " << c << ": light " << light);
        CHECK(light >= lowest[c] - 1e-6);
        CHECK(light <= highest[c] + 1e-6);
      }
}

TEST_CASE("cli: a missing texture is one warning line naming the file, and the bake goes on") {
  const fs::path dir = prt::test::output_path("cli_textures") / "missing";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path scene = write_textured_quad(dir, "no_such_texture.png");
  const fs::path file = dir / "quad.prt";
  const Run baked = run(std::string(PRT_CLI_PATH) + " bake " + scene.string() + " -o " +
                        file.string() + " --order 2 --samples 16 --quiet");
  INFO(baked.err);
  CHECK(baked.exit_code == 0);
  CHECK(fs::exists(file));
  // The texture warning names the file; the note that follows says the colour is the default
  // grey (the material has no baseColorFactor of its own).
  std::istringstream lines(baked.err);
  std::string line;
  int warnings = 0;
  while (std::getline(lines, line))
    if (line.find("warning") != std::string::npos) {
      ++warnings;
      CHECK(line.find((dir / "no_such_texture.png").string()) != std::string::npos);
      CHECK(line.rfind(scene.string() + ": ", 0) == 0);
    }
  CHECK(warnings == 1);
}
