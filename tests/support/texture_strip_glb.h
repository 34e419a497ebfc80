// tests/support/texture_strip_glb.h — small GLB files whose one material reads parameter textures,
// written by hand (JSON chunk only, buffer and images as data URIs; independent of prt's writer):
// a flat strip of 2 rows × 4 columns of vertices in z = 0 (vertex v = 4·row + i at (i/3, row, 0),
// NORMAL +Z, TANGENT +X with w = +1, so the bitangent is +Y) whose TEXCOORD_0 (and TEXCOORD_1, the
// same, on request) is u = (i + ½)/4, v = 3/8: vertex v reads texel column v mod 4, row 1, of a
// 4 × 4 texture. Every texture k uses image k and one NEAREST sampler.
#pragma once

#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/base64.h"
#include "support/png_writer.h"

namespace prt::test {

// A 4 × 4 PNG of `channels` channels whose column i holds columns[i] (channels bytes) in every row.
inline std::vector<unsigned char> column_png(
    int channels, const std::vector<std::vector<unsigned char>>& columns) {
  std::vector<unsigned char> texels;
  for (int row = 0; row < 4; ++row)
    for (int i = 0; i < 4; ++i) {
      if (columns.at(std::size_t(i)).size() != std::size_t(channels))
        throw std::invalid_argument("column_png: wrong channel count");
      texels.insert(texels.end(), columns[std::size_t(i)].begin(), columns[std::size_t(i)].end());
    }
  return encode_png(4, 4, channels, texels);
}

// The glTF document of the strip with `material` (named by its "name") and the PNG images.
inline nlohmann::json texture_strip_gltf(const nlohmann::json& material,
                                         const std::vector<std::vector<unsigned char>>& pngs,
                                         bool texcoord1 = false) {
  using nlohmann::json;
  std::vector<float> positions, normals, tangents, uv;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 4; ++i) {
      positions.insert(positions.end(), {float(i) / 3.f, float(row), 0.f});
      normals.insert(normals.end(), {0.f, 0.f, 1.f});
      tangents.insert(tangents.end(), {1.f, 0.f, 0.f, 1.f});
      uv.insert(uv.end(), {(float(i) + 0.5f) / 4.f, 0.375f});
    }
  std::vector<uint16_t> indices;
  for (uint16_t i = 0; i < 3; ++i) {
    const uint16_t a = i, b = uint16_t(i + 1), c = uint16_t(i + 5), d = uint16_t(i + 4);
    indices.insert(indices.end(), {a, b, c, a, c, d});
  }
  std::vector<unsigned char> bin;
  json views = json::array(), accessors = json::array(), attributes;
  const auto add = [&](const void* data, std::size_t bytes, int component, const char* type,
                       std::size_t count) {
    while (bin.size() % 4) bin.push_back(0);
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    const auto* p = static_cast<const unsigned char*>(data);
    bin.insert(bin.end(), p, p + bytes);
    accessors.push_back({{"bufferView", views.size() - 1},
                         {"componentType", component},
                         {"count", count},
                         {"type", type}});
    return accessors.size() - 1;
  };
  attributes["POSITION"] = add(positions.data(), positions.size() * 4, 5126, "VEC3", 8);
  accessors.back()["min"] = {0, 0, 0};
  accessors.back()["max"] = {1, 1, 0};
  attributes["NORMAL"] = add(normals.data(), normals.size() * 4, 5126, "VEC3", 8);
  attributes["TANGENT"] = add(tangents.data(), tangents.size() * 4, 5126, "VEC4", 8);
  attributes["TEXCOORD_0"] = add(uv.data(), uv.size() * 4, 5126, "VEC2", 8);
  if (texcoord1) attributes["TEXCOORD_1"] = attributes["TEXCOORD_0"];
  const std::size_t index_accessor =
      add(indices.data(), indices.size() * 2, 5123, "SCALAR", indices.size());
  json images = json::array(), textures = json::array();
  for (std::size_t k = 0; k < pngs.size(); ++k) {
    images.push_back({{"uri", "data:image/png;base64," + base64(pngs[k])}});
    textures.push_back({{"source", k}, {"sampler", 0}});
  }
  json doc = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", json::array({{{"nodes", {0}}}})},
      {"nodes", json::array({{{"mesh", 0}}})},
      {"meshes", json::array({{{"name", "strip"},
                               {"primitives", json::array({{{"attributes", attributes},
                                                            {"indices", index_accessor},
                                                            {"material", 0}}})}}})},
      {"materials", json::array({material})},
      {"accessors", accessors},
      {"bufferViews", views},
      {"samplers", json::array({{{"magFilter", 9728}, {"minFilter", 9728}}})},
      {"buffers", json::array({{{"byteLength", bin.size()},
                                {"uri", "data:application/octet-stream;base64," + base64(bin)}}})}};
  if (!images.empty()) {
    doc["images"] = images;
    doc["textures"] = textures;
  }
  return doc;
}

// `text` (a glTF JSON document) as a GLB at `path` (JSON chunk only).
inline void write_glb_text(const std::string& path, std::string text) {
  while (text.size() % 4) text += ' ';
  const uint32_t header[5] = {0x46546C67u, 2u, uint32_t(12 + 8 + text.size()),
                              uint32_t(text.size()), 0x4E4F534Au};
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace prt::test
