// `prt bake --subsurface gltf`: dipole coefficients from a glTF material's KHR_materials_volume /
// KHR_materials_diffuse_transmission (cli/subsurface_gltf.h), against the same coefficients given
// on the command line, and the refusals of bad extension values (one line naming the file and
// the material, nothing written).
#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

namespace {

using namespace prt::test::cli;

// Two 8 × 8-vertex grids of side 1 facing +Z, side by side (x in [0, 1] and [1.5, 2.5]): mesh
// "skin" with material "Skin" (baseColorFactor 0.75, 0.5, 0.25 — exact in float — and
// `skin_extensions` as its "extensions" JSON), mesh "paint" with material "Paint" (0.5 grey, no
// extension). Written as JSON text beside a .bin buffer, independently of prt's writers.
fs::path write_two_grids(const fs::path& dir, const std::string& skin_extensions) {
  constexpr int n = 8;
  std::vector<float> positions, normals;
  std::vector<uint16_t> indices;
  for (int g = 0; g < 2; ++g)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        positions.insert(positions.end(), {1.5f * float(g) + float(i) / float(n - 1), float(j) / float(n - 1), 0.f});
        normals.insert(normals.end(), {0, 0, 1});
      }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const uint16_t a = uint16_t(j * n + i), b = uint16_t(a + 1), c = uint16_t(a + n + 1),
                     d = uint16_t(a + n);
      indices.insert(indices.end(), {a, b, c, a, c, d});
    }
  const std::size_t half_pos = positions.size() * 4 / 2, idx_bytes = indices.size() * 2;
  std::ofstream bin(dir / "grids.bin", std::ios::binary);
  bin.write(reinterpret_cast<const char*>(positions.data()), std::streamsize(positions.size() * 4));
  bin.write(reinterpret_cast<const char*>(normals.data()), std::streamsize(normals.size() * 4));
  bin.write(reinterpret_cast<const char*>(indices.data()), std::streamsize(idx_bytes));
  bin.close();
  const std::size_t total = positions.size() * 8 + idx_bytes;
  const auto view = [](std::size_t offset, std::size_t length) {
    return "{\"buffer\":0,\"byteOffset\":" + std::to_string(offset) +
           ",\"byteLength\":" + std::to_string(length) + "}";
  };
  const std::size_t count = n * n;
  const auto accessor = [count](int v, const char* min, const char* max) {
    return "{\"bufferView\":" + std::to_string(v) +
           ",\"componentType\":5126,\"count\":" + std::to_string(count) +
           ",\"type\":\"VEC3\",\"min\":" + min + ",\"max\":" + max + "}";
  };
  const std::string idx =
      "{\"bufferView\":4,\"componentType\":5123,\"count\":" + std::to_string(indices.size()) +
      ",\"type\":\"SCALAR\"}";
  const auto mesh = [](const char* name, int pos, int nrm, int material) {
    return std::string("{\"name\":\"") + name +
           "\",\"primitives\":[{\"attributes\":{\"POSITION\":" + std::to_string(pos) +
           ",\"NORMAL\":" + std::to_string(nrm) +
           "},\"indices\":4,\"material\":" + std::to_string(material) + "}]}";
  };
  const std::string json =
      "{\"asset\":{\"version\":\"2.0\"},\"extensionsUsed\":[\"KHR_materials_volume\","
      "\"KHR_materials_diffuse_transmission\",\"KHR_materials_ior\"],"
      "\"buffers\":[{\"uri\":\"grids.bin\",\"byteLength\":" +
      std::to_string(total) + "}],\"bufferViews\":[" + view(0, half_pos) + "," +
      view(half_pos, half_pos) + "," + view(2 * half_pos, half_pos) + "," +
      view(3 * half_pos, half_pos) + "," + view(4 * half_pos, idx_bytes) + "],\"accessors\":[" +
      accessor(0, "[0,0,0]", "[1,1,0]") + "," + accessor(1, "[1.5,0,0]", "[2.5,1,0]") + "," +
      accessor(2, "[0,0,1]", "[0,0,1]") + "," + accessor(3, "[0,0,1]", "[0,0,1]") + "," + idx +
      "],\"materials\":[" +
      "{\"name\":\"Skin\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.75,0.5,0.25,1]},"
      "\"extensions\":" +
      skin_extensions +
      "},{\"name\":\"Paint\",\"pbrMetallicRoughness\":{\"baseColorFactor\":[0.5,0.5,0.5,1]}}],"
      "\"meshes\":[" +
      mesh("skin", 0, 2, 0) + "," + mesh("paint", 1, 3, 1) +
      "],\"nodes\":[{\"mesh\":0},{\"mesh\":1}],\"scenes\":[{\"nodes\":[0,1]}],\"scene\":0}";
  // views and accessors 0, 1: the grids' positions; 2, 3: their normals; 4: the shared indices
  std::ofstream(dir / "grids.gltf") << json;
  return dir / "grids.gltf";
}

const char* kSkinExtensions =
    "{\"KHR_materials_volume\":{\"attenuationDistance\":0.5,\"attenuationColor\":[0.9,0.5,0.4],"
    "\"thicknessFactor\":0.2},\"KHR_materials_diffuse_transmission\":{"
    "\"diffuseTransmissionFactor\":0.5},\"KHR_materials_ior\":{\"ior\":1.4}}";

}  // namespace

TEST_CASE("prt bake --subsurface gltf takes the coefficients from the material's extensions",
          "[cli][translucency]") {
  const fs::path dir = scratch("subsurface_gltf");
  const fs::path scene = write_two_grids(dir, kSkinExtensions);
  // 4 mm per unit: attenuationDistance 0.5 → mean free path 2 mm; η from KHR_materials_ior.
  const std::string bake = prt_cli() + " bake " + scene.string() +
                           " --order 2 --samples 64 --threads 2 --subsurface-scale 4 ";
  const fs::path from_gltf = dir / "gltf.prt", by_hand = dir / "hand.prt", all = dir / "all.prt";
  RunResult r = run(bake + "--subsurface gltf -o " + from_gltf.string());
  INFO("stderr: " << r.err);
  REQUIRE(r.exit_code == 0);
  CHECK(r.out.find("(64 translucent)") != std::string::npos);  // Skin's grid only
  // The same coefficients on the command line, for Skin only: Paint stays opaque in both.
  r = run(bake + "--subsurface Skin=custom --subsurface-color 0.75,0.5,0.25 --mean-free-path 2 " +
          "--eta 1.4 -o " + by_hand.string());
  REQUIRE(r.exit_code == 0);
  const std::string a = slurp(from_gltf), b = slurp(by_hand);
  REQUIRE(!a.empty());
  CHECK(a == b);  // byte-identical: same coefficients, same vertices translucent
  // Both grids translucent differs: the gltf bake left Paint opaque.
  r = run(bake + "--subsurface custom --subsurface-color 0.75,0.5,0.25 --mean-free-path 2 " +
          "--eta 1.4 -o " + all.string());
  REQUIRE(r.exit_code == 0);
  CHECK(slurp(all) != a);
  // --eta overrides the file's ior; a later --subsurface MATERIAL=PRESET overrides gltf.
  r = run(bake + "--subsurface gltf --eta 1.3 -o " + (dir / "eta.prt").string());
  REQUIRE(r.exit_code == 0);
  CHECK(slurp(dir / "eta.prt") != a);
  r = run(bake + "--subsurface gltf --subsurface Skin=skin1 -o " + (dir / "o.prt").string());
  REQUIRE(r.exit_code == 0);
  r = run(bake + "--subsurface Skin=skin1 -o " + (dir / "p.prt").string());
  REQUIRE(r.exit_code == 0);
  // The files' metadata differ (the first lists the unused gltf material too); the transfer is
  // skin1's: the same size, not the gltf bake.
  const std::string o = slurp(dir / "o.prt"), p = slurp(dir / "p.prt");
  CHECK(o != a);
  CHECK(o.size() > p.size());
  CHECK(o.find("\"translucent_vertices\":64") != std::string::npos);
}

TEST_CASE("prt bake --subsurface gltf refuses bad extension values in one line",
          "[cli][translucency]") {
  const std::pair<const char*, const char*> cases[] = {
      {"{\"KHR_materials_volume\":{\"attenuationDistance\":-1}}", "attenuationDistance -1"},
      {"{\"KHR_materials_volume\":{\"attenuationDistance\":\"far\"}}", "attenuationDistance nan"},
      {"{\"KHR_materials_diffuse_transmission\":{\"diffuseTransmissionFactor\":1}}",
       "no KHR_materials_volume attenuationDistance"},
      {"{\"KHR_materials_volume\":{\"attenuationDistance\":1},\"KHR_materials_ior\":{\"ior\":0.5}}",
       "ior 0.5"},
      {"{}", "no material has KHR_materials_volume"}};
  int k = 0;
  for (const auto& [extensions, mention] : cases) {
    INFO(extensions);
    const fs::path dir = scratch("subsurface_gltf_bad" + std::to_string(k++));
    const fs::path scene = write_two_grids(dir, extensions);
    const fs::path out = dir / "out.prt";
    const RunResult r = run(prt_cli() + " bake " + scene.string() +
                            " --order 2 --samples 16 --subsurface gltf -o " + out.string());
    require_one_line_error(r, mention);
    CHECK(r.err.find(scene.string()) != std::string::npos);
    if (std::string(mention).rfind("no material", 0) != 0)
      CHECK(r.err.find("material 'Skin'") != std::string::npos);
    CHECK(!fs::exists(out));
  }
}
