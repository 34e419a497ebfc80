// scene/src/texture_decoding.h (private) — texture images decoded through the OpenImageIO plugin
// (scene/image_codec.h) into linear TextureImages (scene/texture.h), for the glTF and OBJ readers.
//
// Colour is read as stored (alpha unassociated, then dropped) and linearised as sRGB. Images of
// more than kMaxTextureTexels texels are refused. Errors throw std::runtime_error "NAME: problem".
#pragma once

#include <cstddef>
#include <memory>
#include <string>

#include "scene/texture.h"

namespace prt::scene::detail {

// "png" or "jpeg" when the bytes start with that format's signature, else "".
std::string image_format_of(const unsigned char* bytes, std::size_t size);

// What a texture image holds: sRGB-encoded colour, linear data (RGB), or linear data in alpha
// (TextureImage::from_image_alpha: grey = A).
enum class TextureContent { kSrgbColour, kLinear, kAlpha };

// A texture from an image file (format from the signature, else from the extension); its samples
// are sRGB-encoded unless srgb_encoded is false.
std::shared_ptr<const TextureImage> load_texture_file(const std::string& path,
                                                      bool srgb_encoded = true);

// A texture from PNG or JPEG bytes; `name` names it in messages.
std::shared_ptr<const TextureImage> load_texture_bytes(const unsigned char* bytes, std::size_t size,
                                                       const std::string& name,
                                                       bool srgb_encoded = true);

// The same, for any TextureContent.
std::shared_ptr<const TextureImage> load_texture_file(const std::string& path,
                                                      TextureContent content);
std::shared_ptr<const TextureImage> load_texture_bytes(const unsigned char* bytes, std::size_t size,
                                                       const std::string& name,
                                                       TextureContent content);

}  // namespace prt::scene::detail
