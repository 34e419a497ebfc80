// tests/support/metal_rough_glb.h — a GLB written through tinygltf (independently of prt's
// writer) whose material has a metallicRoughnessTexture: a flat strip of 2 × 8 vertices in z = 0
// (x = i/7, y = 0 or 1, normal +Z) whose TEXCOORD_0 is u = (i + ½)/8, v = ½, so vertices
// i = 0..3 read the texture's left half and i = 4..7 its right half. The texture is 4 × 2 RGB,
// linear data (glTF: G = roughness, B = metalness), sampled NEAREST; material "patchy" has
// baseColorFactor 0.5 grey, roughnessFactor and metallicFactor 1.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "support/png_writer.h"

namespace prt::test {

// How the texture's image is given.
enum class MetalRoughImage { kInBuffer, kUri };

// Writes the GLB at `path`. The left texels hold (0, left_g, left_b), the right ones
// (0, right_g, right_b). kInBuffer stores the PNG in the GLB's buffer (or `image_bytes` when
// not empty, e.g. garbage); kUri names `uri` beside the GLB (the caller writes, or does not
// write, that file).
inline void write_metal_rough_glb(const std::string& path, int left_g, int left_b, int right_g,
                                  int right_b, MetalRoughImage where = MetalRoughImage::kInBuffer,
                                  const std::string& uri = "",
                                  std::vector<unsigned char> image_bytes = {}) {
  std::vector<float> positions, normals, uv;
  for (int row = 0; row < 2; ++row)
    for (int i = 0; i < 8; ++i) {
      positions.insert(positions.end(), {float(i) / 7.f, float(row), 0.f});
      normals.insert(normals.end(), {0.f, 0.f, 1.f});
      uv.insert(uv.end(), {(float(i) + 0.5f) / 8.f, 0.5f});
    }
  std::vector<uint16_t> indices;
  for (uint16_t i = 0; i < 7; ++i) {
    const uint16_t a = i, b = uint16_t(i + 1), c = uint16_t(i + 9), d = uint16_t(i + 8);
    indices.insert(indices.end(), {a, b, c, a, c, d});
  }
  if (image_bytes.empty()) {
    std::vector<unsigned char> texels;
    for (int row = 0; row < 2; ++row)
      for (int i = 0; i < 4; ++i) {
        const bool right = i >= 2;
        texels.insert(texels.end(), {0, static_cast<unsigned char>(right ? right_g : left_g),
                                     static_cast<unsigned char>(right ? right_b : left_b)});
      }
    image_bytes = encode_png(4, 2, 3, texels);
  }

  tinygltf::Model model;
  tinygltf::Buffer buffer;
  const auto add_view = [&](const void* data, std::size_t bytes, int target) {
    while (buffer.data.size() % 4 != 0) buffer.data.push_back(0);
    tinygltf::BufferView view;
    view.buffer = 0;
    view.byteOffset = buffer.data.size();
    view.byteLength = bytes;
    view.target = target;
    const auto* p = static_cast<const unsigned char*>(data);
    buffer.data.insert(buffer.data.end(), p, p + bytes);
    model.bufferViews.push_back(view);
    return int(model.bufferViews.size() - 1);
  };
  const auto add_accessor = [&](int view, int component, std::size_t count, int type) {
    tinygltf::Accessor a;
    a.bufferView = view;
    a.componentType = component;
    a.count = count;
    a.type = type;
    model.accessors.push_back(a);
    return int(model.accessors.size() - 1);
  };
  const int pos = add_accessor(add_view(positions.data(), positions.size() * 4, 34962),
                               TINYGLTF_COMPONENT_TYPE_FLOAT, 16, TINYGLTF_TYPE_VEC3);
  model.accessors[std::size_t(pos)].minValues = {0, 0, 0};
  model.accessors[std::size_t(pos)].maxValues = {1, 1, 0};
  const int nrm = add_accessor(add_view(normals.data(), normals.size() * 4, 34962),
                               TINYGLTF_COMPONENT_TYPE_FLOAT, 16, TINYGLTF_TYPE_VEC3);
  const int tex = add_accessor(add_view(uv.data(), uv.size() * 4, 34962),
                               TINYGLTF_COMPONENT_TYPE_FLOAT, 16, TINYGLTF_TYPE_VEC2);
  const int idx =
      add_accessor(add_view(indices.data(), indices.size() * 2, 34963),
                   TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT, indices.size(), TINYGLTF_TYPE_SCALAR);
  tinygltf::Image image;
  if (where == MetalRoughImage::kInBuffer) {
    image.bufferView = add_view(image_bytes.data(), image_bytes.size(), 0);
    image.mimeType = "image/png";
  } else {
    image.uri = uri;
  }
  model.images.push_back(image);
  tinygltf::Sampler sampler;
  sampler.magFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  sampler.minFilter = TINYGLTF_TEXTURE_FILTER_NEAREST;
  model.samplers.push_back(sampler);
  tinygltf::Texture texture;
  texture.source = 0;
  texture.sampler = 0;
  model.textures.push_back(texture);
  tinygltf::Material material;
  material.name = "patchy";
  material.pbrMetallicRoughness.baseColorFactor = {0.5, 0.5, 0.5, 1.0};
  material.pbrMetallicRoughness.metallicFactor = 1.0;
  material.pbrMetallicRoughness.roughnessFactor = 1.0;
  material.pbrMetallicRoughness.metallicRoughnessTexture.index = 0;
  model.materials.push_back(material);
  tinygltf::Primitive primitive;
  primitive.attributes = {{"POSITION", pos}, {"NORMAL", nrm}, {"TEXCOORD_0", tex}};
  primitive.indices = idx;
  primitive.material = 0;
  primitive.mode = TINYGLTF_MODE_TRIANGLES;
  tinygltf::Mesh mesh;
  mesh.name = "strip";
  mesh.primitives.push_back(primitive);
  model.meshes.push_back(mesh);
  tinygltf::Node node;
  node.mesh = 0;
  model.nodes.push_back(node);
  tinygltf::Scene scene;
  scene.nodes = {0};
  model.scenes.push_back(scene);
  model.defaultScene = 0;
  model.buffers.push_back(buffer);
  model.asset.version = "2.0";
  tinygltf::TinyGLTF writer;
  writer.SetImageWriter(
      [](const std::string*, const std::string*, const tinygltf::Image*, bool, std::string*,
         void*) { return false; },  // keep the URI as given, write no image
      nullptr);
  if (!writer.WriteGltfSceneToFile(&model, path, /*embedImages=*/false, /*embedBuffers=*/true,
                                   /*prettyPrint=*/false, /*writeBinary=*/true))
    throw std::runtime_error("cannot write " + path);
}

}  // namespace prt::test
