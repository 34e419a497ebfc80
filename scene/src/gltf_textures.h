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
#pragma once

#include <tiny_gltf.h>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "scene/texture.h"

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

  // One warning line on stderr per image that could not be used (missing files in one line).
  void report() const;

 private:
  std::shared_ptr<const TextureImage> image(int index);

  const std::string& path_;
  const tinygltf::Model& model_;
  std::map<int, std::shared_ptr<const TextureImage>> images_;  // null: unusable
  std::set<std::string> missing_, problems_;  // sorted: the report is deterministic
};

}  // namespace prt::scene::detail
