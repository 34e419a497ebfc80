// scene/src/texture_decoding.cpp — texture images through the OpenImageIO plugin
// (texture_decoding.h).
#include "texture_decoding.h"

#include <cstring>
#include <fstream>
#include <stdexcept>

#include "scene/image_codec.h"

namespace prt::scene::detail {
namespace {

ImageReadOptions texture_read_options() {
  ImageReadOptions options;
  options.unassociated_alpha = true;  // colour as painted, whatever the alpha
  return options;
}

}  // namespace

std::string image_format_of(const unsigned char* bytes, std::size_t size) {
  static const unsigned char kPng[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  if (size >= 8 && std::memcmp(bytes, kPng, 8) == 0) return "png";
  if (size >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff) return "jpeg";
  return "";
}

namespace {

std::shared_ptr<const TextureImage> texture_of(const FloatImage& image, const std::string& name,
                                               TextureContent content) {
  if (content == TextureContent::kAlpha)
    return std::make_shared<const TextureImage>(TextureImage::from_image_alpha(image, name));
  return std::make_shared<const TextureImage>(
      TextureImage::from_image(image, name, content == TextureContent::kSrgbColour));
}

}  // namespace

std::shared_ptr<const TextureImage> load_texture_file(const std::string& path, bool srgb_encoded) {
  return load_texture_file(path,
                           srgb_encoded ? TextureContent::kSrgbColour : TextureContent::kLinear);
}

std::shared_ptr<const TextureImage> load_texture_bytes(const unsigned char* bytes, std::size_t size,
                                                       const std::string& name, bool srgb_encoded) {
  return load_texture_bytes(bytes, size, name,
                            srgb_encoded ? TextureContent::kSrgbColour : TextureContent::kLinear);
}

std::shared_ptr<const TextureImage> load_texture_file(const std::string& path,
                                                      TextureContent content) {
  unsigned char head[8] = {};
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": no such file or not readable");
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const std::string format = image_format_of(head, static_cast<std::size_t>(in.gcount()));
  const FloatImage image =
      decode_image_file(path, format, kMaxTextureTexels, texture_read_options());
  return texture_of(image, path, content);
}

std::shared_ptr<const TextureImage> load_texture_bytes(const unsigned char* bytes, std::size_t size,
                                                       const std::string& name,
                                                       TextureContent content) {
  const std::string format = image_format_of(bytes, size);
  if (format.empty()) throw std::runtime_error(name + ": not a PNG or JPEG image");
  const FloatImage image =
      decode_image_memory(bytes, size, format, name, kMaxTextureTexels, texture_read_options());
  return texture_of(image, name, content);
}

}  // namespace prt::scene::detail
