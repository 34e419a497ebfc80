// scene/src/gltf_textures.h (private) — the base-colour textures of a glTF file: the material's
// pbrMetallicRoughness.baseColorTexture (index, texCoord), its texture's sampler (wrapS, wrapT,
// magFilter, minFilter) and source image, decoded (texture_decoding.h) once per image.
//
// Images may be files beside the .gltf (percent-encoded URIs), data: URIs, or buffer views (GLB).
// tinygltf keeps no bytes of the images it reads with a custom loader, so keep_image_bytes (the
// loader callback) stores the bytes of URI images in Image::image; buffer-view images are read
// from their buffer here, bounds-checked.
//
// An image that cannot be used (missing file, not PNG/JPEG, corrupt, too large) is not an error:
// real assets are often shipped without their textures. Its materials fall back to their
// baseColorFactor, and report() prints one warning line per problem, naming the image.
// The metallicRoughnessTexture (linear data, not sRGB: G = roughness, B = metalness) and the
// textures of KHR_materials_specular (specularTexture: linear, A; specularColorTexture: sRGB
// colour) and KHR_materials_anisotropy (anisotropyTexture: linear RGB) are read the same way
// (parameter()); their problems come back to the caller, which records them on the primitive.
#pragma once

#include <tiny_gltf.h>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "scene/texture.h"
#include "texture_decoding.h"

namespace prt::scene::detail {

// tinygltf's image callback: keeps the encoded bytes of URI images (Image::image, as_is), decodes
// nothing.
bool keep_image_bytes(tinygltf::Image* image, int image_index, std::string* error,
                      std::string* warning, int width, int height, const unsigned char* bytes,
                      int size, void* user_data);

class GltfTextures {
 public:
  GltfTextures(const std::string& path, const tinygltf::Model& model);

  // The base-colour texture of material `material` (factor included), or nullopt when it has
  // none or its image cannot be used.
  std::optional<BaseColorTexture> base_color(int material);

  // A material parameter texture: image (linear), sampler and texCoord set.
  struct ParameterTexture {
    std::shared_ptr<const TextureImage> image;
    TextureSampler sampler;
    int texcoord = 0;
  };

  // The metallicRoughnessTexture of material `material`: nullopt when it has none, or when it
  // cannot be used, then with *problem set to one line naming the image file (or index).
  std::optional<ParameterTexture> metallic_roughness(int material, std::string* problem);

  // A texture a material refers to (glTF textureInfo: index, texCoord; index < 0: none).
  struct TextureRef {
    int index = -1;
    int texcoord = 0;
  };
  // The texture `ref` names, decoded as `content`: nullopt when ref.index < 0, or when it cannot
  // be used, then with *problem set as for metallic_roughness().
  std::optional<ParameterTexture> parameter(const TextureRef& ref, TextureContent content,
                                            std::string* problem);

  // One warning line on stderr per image that could not be used (missing files in one line).
  void report() const;

 private:
  struct CachedImage {
    std::shared_ptr<const TextureImage> image;  // null: unusable
    std::string missing_file, problem;          // why, when unusable
  };
  // Image `index` decoded as `content`, once.
  const CachedImage& image(int index, TextureContent content);
  // The texture `index` refers to, checked; null with *problem set when it is unusable.
  const tinygltf::Texture* texture(int index, std::string* problem) const;

  const std::string& path_;
  const tinygltf::Model& model_;
  std::map<std::pair<int, TextureContent>, CachedImage> images_;
  std::set<std::string> missing_, problems_;  // sorted: the report is deterministic
};

}  // namespace prt::scene::detail
