// scene/src/gltf_textures.cpp — base-colour textures of glTF files (gltf_textures.h).
#include "gltf_textures.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "scene/scene_loader.h"
#include "texture_decoding.h"

namespace prt::scene::detail {
namespace {

// glTF sampler codes (glTF 2.0 §5.26).
constexpr int kNearest = 9728, kNearestMipmapNearest = 9984, kNearestMipmapLinear = 9986,
              kLinearMipmapNearest = 9985, kLinearMipmapLinear = 9987;
constexpr int kClampToEdge = 33071, kMirroredRepeat = 33648;

TextureWrap wrap_of(int code) {
  if (code == kClampToEdge) return TextureWrap::ClampToEdge;
  if (code == kMirroredRepeat) return TextureWrap::MirroredRepeat;
  return TextureWrap::Repeat;
}

TextureSampler sampler_of(const tinygltf::Sampler& s) {
  TextureSampler out;
  out.wrap_s = wrap_of(s.wrapS);
  out.wrap_t = wrap_of(s.wrapT);
  out.nearest_magnification = s.magFilter == kNearest;
  out.nearest_minification = s.minFilter == kNearest || s.minFilter == kNearestMipmapNearest ||
                             s.minFilter == kNearestMipmapLinear;
  out.mipmaps = s.minFilter < 0 || s.minFilter == kNearestMipmapNearest ||
                s.minFilter == kNearestMipmapLinear || s.minFilter == kLinearMipmapNearest ||
                s.minFilter == kLinearMipmapLinear;
  return out;
}

}  // namespace

bool keep_image_bytes(tinygltf::Image* image, int, std::string*, std::string*, int, int,
                      const unsigned char* bytes, int size, void*) {
  // Buffer-view images are read (bounds-checked) from their buffer when needed.
  if (image->bufferView < 0 && bytes != nullptr && size > 0) {
    image->image.assign(bytes, bytes + size);
    image->as_is = true;
  }
  return true;
}

GltfTextures::GltfTextures(const std::string& path, const tinygltf::Model& model)
    : path_(path), model_(model) {}

std::shared_ptr<const TextureImage> GltfTextures::image(int index) {
  if (const auto it = images_.find(index); it != images_.end()) return it->second;
  std::shared_ptr<const TextureImage>& slot = images_[index];
  const tinygltf::Image& image = model_.images[static_cast<std::size_t>(index)];
  const std::string label =
      "image " + std::to_string(index) + (image.name.empty() ? "" : " '" + image.name + "'");
  try {
    if (image.bufferView >= 0) {
      const std::size_t view_index = static_cast<std::size_t>(image.bufferView);
      if (view_index >= model_.bufferViews.size())
        throw std::runtime_error(label + ": its buffer view does not exist");
      const tinygltf::BufferView& view = model_.bufferViews[view_index];
      if (view.buffer < 0 || view.buffer >= static_cast<int>(model_.buffers.size()))
        throw std::runtime_error(label + ": its buffer does not exist");
      const std::vector<unsigned char>& data =
          model_.buffers[static_cast<std::size_t>(view.buffer)].data;
      if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
        throw std::runtime_error(label + ": its buffer view lies outside its buffer");
      slot = load_texture_bytes(data.data() + view.byteOffset, view.byteLength, label);
    } else if (image.uri.rfind("data:", 0) == 0) {
      slot = load_texture_bytes(image.image.data(), image.image.size(), label + " (data URI)");
    } else {
      const std::string file =
          (std::filesystem::path(path_).parent_path() / decode_uri(image.uri)).string();
      std::error_code ec;
      if (!image.image.empty())
        slot = load_texture_bytes(image.image.data(), image.image.size(), file);
      else if (std::filesystem::is_regular_file(file, ec))
        slot = load_texture_file(file);
      else
        missing_.insert(file);
    }
  } catch (const std::runtime_error& e) {
    problems_.insert(e.what());
  }
  return slot;
}

std::optional<BaseColorTexture> GltfTextures::base_color(int material) {
  if (material < 0 || material >= static_cast<int>(model_.materials.size())) return std::nullopt;
  const tinygltf::PbrMetallicRoughness& pbr =
      model_.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness;
  const tinygltf::TextureInfo& info = pbr.baseColorTexture;
  if (info.index < 0) return std::nullopt;
  if (info.index >= static_cast<int>(model_.textures.size())) {
    problems_.insert("texture " + std::to_string(info.index) + " does not exist");
    return std::nullopt;
  }
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(info.index)];
  if (texture.source < 0 || texture.source >= static_cast<int>(model_.images.size())) {
    problems_.insert("texture " + std::to_string(info.index) + " has no image");
    return std::nullopt;
  }
  BaseColorTexture out;
  out.image = image(texture.source);
  if (!out.image) return std::nullopt;
  if (texture.sampler >= 0 && texture.sampler < static_cast<int>(model_.samplers.size()))
    out.sampler = sampler_of(model_.samplers[static_cast<std::size_t>(texture.sampler)]);
  const std::vector<double>& f = pbr.baseColorFactor;
  if (f.size() >= 3) out.factor = glm::vec3(glm::dvec3(f[0], f[1], f[2]));
  out.texcoord = info.texCoord;
  return out;
}

void GltfTextures::report() const {
  if (!missing_.empty()) {
    std::string list;
    for (const std::string& uri : missing_) list += (list.empty() ? "" : ", ") + uri;
    std::fprintf(stderr,
                 "%s: warning: %zu base-colour texture file(s) missing: %s; their materials use "
                 "baseColorFactor instead\n",
                 path_.c_str(), missing_.size(), list.c_str());
  }
  for (const std::string& problem : problems_)
    std::fprintf(stderr, "%s: warning: base-colour texture not used: %s\n", path_.c_str(),
                 problem.c_str());
}

}  // namespace prt::scene::detail

namespace prt::scene {

std::string decode_uri(const std::string& uri) {
  std::string out;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

}  // namespace prt::scene
