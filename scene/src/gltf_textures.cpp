// scene/src/gltf_textures.cpp — base-colour and metallic-roughness textures of glTF files
// (gltf_textures.h).
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

const GltfTextures::CachedImage& GltfTextures::image(int index, TextureContent content) {
  if (const auto it = images_.find({index, content}); it != images_.end()) return it->second;
  CachedImage& slot = images_[{index, content}];
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
      slot.image =
          load_texture_bytes(data.data() + view.byteOffset, view.byteLength, label, content);
    } else if (image.uri.rfind("data:", 0) == 0) {
      slot.image = load_texture_bytes(image.image.data(), image.image.size(), label + " (data URI)",
                                      content);
    } else {
      const std::string file =
          (std::filesystem::path(path_).parent_path() / decode_uri(image.uri)).string();
      std::error_code ec;
      if (!image.image.empty())
        slot.image = load_texture_bytes(image.image.data(), image.image.size(), file, content);
      else if (std::filesystem::is_regular_file(file, ec))
        slot.image = load_texture_file(file, content);
      else
        slot.missing_file = file;
    }
  } catch (const std::runtime_error& e) {
    slot.problem = e.what();
  }
  return slot;
}

const tinygltf::Texture* GltfTextures::texture(int index, std::string* problem) const {
  if (index >= static_cast<int>(model_.textures.size())) {
    *problem = "texture " + std::to_string(index) + " does not exist";
    return nullptr;
  }
  const tinygltf::Texture& texture = model_.textures[static_cast<std::size_t>(index)];
  if (texture.source < 0 || texture.source >= static_cast<int>(model_.images.size())) {
    *problem = "texture " + std::to_string(index) + " has no image";
    return nullptr;
  }
  return &texture;
}

std::optional<BaseColorTexture> GltfTextures::base_color(int material) {
  if (material < 0 || material >= static_cast<int>(model_.materials.size())) return std::nullopt;
  const tinygltf::PbrMetallicRoughness& pbr =
      model_.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness;
  const tinygltf::TextureInfo& info = pbr.baseColorTexture;
  if (info.index < 0) return std::nullopt;
  std::string problem;
  const tinygltf::Texture* texture = this->texture(info.index, &problem);
  if (!texture) {
    problems_.insert(problem);
    return std::nullopt;
  }
  const CachedImage& cached = image(texture->source, TextureContent::kSrgbColour);
  if (!cached.image) {
    if (!cached.missing_file.empty()) missing_.insert(cached.missing_file);
    if (!cached.problem.empty()) problems_.insert(cached.problem);
    return std::nullopt;
  }
  BaseColorTexture out;
  out.image = cached.image;
  if (texture->sampler >= 0 && texture->sampler < static_cast<int>(model_.samplers.size()))
    out.sampler = sampler_of(model_.samplers[static_cast<std::size_t>(texture->sampler)]);
  const std::vector<double>& f = pbr.baseColorFactor;
  if (f.size() >= 3) out.factor = glm::vec3(glm::dvec3(f[0], f[1], f[2]));
  out.texcoord = info.texCoord;
  return out;
}

std::optional<GltfTextures::ParameterTexture> GltfTextures::metallic_roughness(
    int material, std::string* problem) {
  problem->clear();
  if (material < 0 || material >= static_cast<int>(model_.materials.size())) return std::nullopt;
  const tinygltf::TextureInfo& info = model_.materials[static_cast<std::size_t>(material)]
                                          .pbrMetallicRoughness.metallicRoughnessTexture;
  return parameter(TextureRef{info.index, info.texCoord}, TextureContent::kLinear, problem);
}

std::optional<GltfTextures::ParameterTexture> GltfTextures::parameter(const TextureRef& ref,
                                                                      TextureContent content,
                                                                      std::string* problem) {
  problem->clear();
  if (ref.index < 0) return std::nullopt;
  const tinygltf::Texture* texture = this->texture(ref.index, problem);
  if (!texture) return std::nullopt;
  const CachedImage& cached = image(texture->source, content);
  if (!cached.image) {
    *problem =
        cached.missing_file.empty() ? cached.problem : cached.missing_file + ": no such file";
    return std::nullopt;
  }
  ParameterTexture out;
  out.image = cached.image;
  if (texture->sampler >= 0 && texture->sampler < static_cast<int>(model_.samplers.size()))
    out.sampler = sampler_of(model_.samplers[static_cast<std::size_t>(texture->sampler)]);
  out.texcoord = ref.texcoord;
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
