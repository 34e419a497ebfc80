// relight/src/image_io.cpp — environment-map reading (own Radiance and PFM decoders, the
// OpenImageIO plugin for the rest) and atomic image writing through that plugin.
#include "relight/image_io.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "prt/core/atomic_file.h"
#include "relight/exr_header_check.h"
#include "relight/pfm_image.h"
#include "relight/radiance_hdr.h"

#include "message_text.h"
#include "scene/image_codec.h"

namespace prt::relight {
namespace {

using detail::one_line;
using scene::ImageSampleType;

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw std::runtime_error(path + ": " + one_line(problem));
}

std::string lower_extension(const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

// Float RGB from an image with any channel count (3 channels: the pixels are moved).
sh::EnvMap to_rgb(FloatImage&& image, sh::EnvLayout layout) {
  sh::EnvMap env;
  env.layout = layout;
  env.width = image.width;
  env.height = image.height;
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  const int channels = image.channels;
  if (channels == 3) {
    env.rgb = std::move(image.pixels);
    return env;
  }
  env.rgb.resize(texels * 3);
  for (std::size_t i = 0; i < texels; ++i) {
    const float* in = &image.pixels[i * channels];
    float* out = &env.rgb[i * 3];
    if (channels >= 3) {
      out[0] = in[0];
      out[1] = in[1];
      out[2] = in[2];
    } else {
      out[0] = out[1] = out[2] = in[0];
    }
  }
  return env;
}

enum class Decoder { Radiance, Pfm, OpenImageIO };

// See "Which decoder reads a file" in image_io.h.
Decoder choose_decoder(const std::string& path, const unsigned char* head, std::size_t size) {
  if (has_radiance_magic(head, size)) return Decoder::Radiance;
  if (has_pfm_magic(head, size)) return Decoder::Pfm;
  const std::string extension = lower_extension(path);
  if (extension == ".hdr" || extension == ".rgbe") return Decoder::Radiance;
  if (extension == ".pfm") return Decoder::Pfm;
  return Decoder::OpenImageIO;
}

// Up to `limit` bytes from the start of the file (all of it for limit = SIZE_MAX).
std::vector<unsigned char> read_file_bytes(const std::string& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::vector<unsigned char> bytes;
  if (limit == SIZE_MAX) {
    in.seekg(0, std::ios::end);
    const std::streamoff size = in.tellg();
    in.seekg(0, std::ios::beg);
    if (size < 0 || !in) fail(path, "cannot read: cannot tell the file's size");
    bytes.resize(static_cast<std::size_t>(size));
  } else {
    bytes.resize(limit);
  }
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (in.bad() || (limit == SIZE_MAX && in.gcount() != static_cast<std::streamsize>(bytes.size())))
    fail(path, "cannot read the file");
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// OpenImageIO (through its plugin, scene/image_codec.h), with the reader of the extension's format
// only when OpenImageIO knows the extension (no probing of every plugin), else with its usual
// search. OpenEXR files (by magic) are checked by exr_header_problem before OpenEXR sees them.
// (OpenEXR then reads the file itself: OpenImageIO 2.4's IOMemReader does not bounds-check
// negative offsets, which a hostile line-offset table produces — fuzz_env_map_exr found that, so
// the pixels are not decoded from the checked bytes.)
FloatImage read_with_openimageio(const std::string& path, const std::vector<unsigned char>& head,
                                 std::size_t max_texels) {
  std::string format = lower_extension(path);
  if (!format.empty()) format.erase(0, 1);  // ".exr" -> "exr"
  if (has_exr_magic(head.data(), head.size())) {
    format = "openexr";
    const std::vector<unsigned char> bytes = read_file_bytes(path, SIZE_MAX);
    const std::string problem = exr_header_problem(bytes.data(), bytes.size(), max_texels);
    if (!problem.empty()) fail(path, problem);
  }
  return scene::decode_image_file(path, format, max_texels);
}

// Writes pixels of `buffer_type`, stored as `file_type`, to PATH atomically
// (prt/core/atomic_file.h).
void write_atomically(const std::string& path, int width, int height, int channels,
                      ImageSampleType file_type, ImageSampleType buffer_type, bool name_y,
                      const void* pixels) {
  const prt::Status written = prt::replace_file_atomically(path, [&](const std::string& temporary) {
    return scene::encode_image_file(path, temporary, width, height, channels, file_type,
                                    buffer_type, name_y, pixels);
  });
  if (!written.ok()) throw std::runtime_error(written.message());
}

}  // namespace

FloatImage read_image(const std::string& path, std::size_t max_texels) {
  std::error_code error;
  if (!std::filesystem::exists(path, error)) fail(path, "no such file");
  if (std::filesystem::is_directory(path, error)) fail(path, "is a directory, not an image");
  const std::vector<unsigned char> head = read_file_bytes(path, 4);
  switch (choose_decoder(path, head.data(), head.size())) {
    case Decoder::Radiance: {
      const std::vector<unsigned char> bytes = read_file_bytes(path, SIZE_MAX);
      return decode_radiance_hdr(bytes.data(), bytes.size(), path, max_texels);
    }
    case Decoder::Pfm: {
      const std::vector<unsigned char> bytes = read_file_bytes(path, SIZE_MAX);
      return decode_pfm(bytes.data(), bytes.size(), path, max_texels);
    }
    case Decoder::OpenImageIO:
      break;
  }
  return read_with_openimageio(path, head, max_texels);
}

sh::EnvMap to_environment(FloatImage image, const std::string& path,
                          std::optional<sh::EnvLayout> layout, std::string* chosen_note) {
  sh::EnvLayout chosen;
  if (layout) {
    chosen = *layout;
    std::string why;
    if (!sh::validate_layout(chosen, image.width, image.height, &why))
      fail(path, std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " does not fit the " + sh::layout_name(chosen) + " layout: " + why);
    if (chosen_note) *chosen_note = std::string("layout ") + sh::layout_name(chosen);
  } else {
    bool ok = false;
    chosen = sh::guess_layout(image.width, image.height, &ok);
    if (!ok)
      fail(path,
           "cannot tell the layout from the size " + std::to_string(image.width) + "x" +
               std::to_string(image.height) +
               " (expected 2:1 lat-long, 1:1 angular, 3:4 cross or 1:6 faces); pass a layout");
    if (chosen_note) {
      static const char* const kRatios[] = {"2:1", "1:1", "3:4", "1:6"};
      *chosen_note = std::string("layout ") + sh::layout_name(chosen) +
                     " (auto: " + std::to_string(image.width) + "x" + std::to_string(image.height) +
                     " is " + kRatios[static_cast<int>(chosen)] + ")";
    }
  }
  return to_rgb(std::move(image), chosen);
}

sh::EnvMap read_environment(const std::string& path, std::optional<sh::EnvLayout> layout,
                            std::string* chosen_note) {
  const bool is_pattern = path.find("%s") != std::string::npos;
  if (is_pattern && (!layout || *layout == sh::EnvLayout::Faces)) {
    if (chosen_note) *chosen_note = "layout faces (six files from the pattern)";
    return read_environment_faces_pattern(path);
  }
  return to_environment(read_image(path), path, layout, chosen_note);
}

sh::EnvMap read_environment_faces(const std::vector<std::string>& six_paths) {
  if (six_paths.size() != 6)
    throw std::runtime_error("faces: expected 6 files (+X, -X, +Y, -Y, +Z, -Z), got " +
                             std::to_string(six_paths.size()));
  sh::EnvMap env;
  env.layout = sh::EnvLayout::Faces;
  for (std::size_t face = 0; face < 6; ++face) {
    const std::string& path = six_paths[face];
    FloatImage image = read_image(path);
    if (image.width != image.height)
      fail(path, "a cube face must be square, not " + std::to_string(image.width) + "x" +
                     std::to_string(image.height));
    if (face == 0) {
      env.width = image.width;
      env.height = 6 * image.width;
      env.rgb.reserve(static_cast<std::size_t>(env.width) * env.height * 3);
    } else if (image.width != env.width) {
      fail(path, "face size " + std::to_string(image.width) + " differs from the first face's " +
                     std::to_string(env.width));
    }
    const sh::EnvMap face_map = to_rgb(std::move(image), sh::EnvLayout::Faces);
    env.rgb.insert(env.rgb.end(), face_map.rgb.begin(), face_map.rgb.end());
  }
  return env;
}

sh::EnvMap read_environment_faces_pattern(const std::string& pattern) {
  const std::size_t at = pattern.find("%s");
  if (at == std::string::npos) fail(pattern, "a faces pattern needs %s (replaced by px, nx, ...)");
  std::vector<std::string> paths;
  for (const char* suffix : kFaceSuffixes)
    paths.push_back(pattern.substr(0, at) + suffix + pattern.substr(at + 2));
  return read_environment_faces(paths);
}

void write_image(const std::string& path, int width, int height, int channels, const float* pixels,
                 const ImageWriteOptions& options) {
  if (width <= 0 || height <= 0) fail(path, "cannot write an empty image");
  if (channels < 1 || channels > 4)
    fail(path, "cannot write " + std::to_string(channels) + " channels (1 to 4 supported)");
  const std::string extension = lower_extension(path);
  const std::size_t texels = static_cast<std::size_t>(width) * height;
  if (extension == ".png") {
    std::vector<unsigned char> bytes(texels * channels);
    for (std::size_t i = 0; i < bytes.size(); ++i) {
      const float v = pixels[i];
      const float clamped = std::isnan(v) ? 0.0f : std::clamp(v, 0.0f, 1.0f);
      bytes[i] = static_cast<unsigned char>(std::lround(clamped * 255.0f));
    }
    write_atomically(path, width, height, channels, ImageSampleType::UInt8, ImageSampleType::UInt8,
                     false, bytes.data());
  } else if (extension == ".hdr") {
    std::vector<float> rgb(texels * 3);
    for (std::size_t i = 0; i < texels; ++i)
      for (int c = 0; c < 3; ++c) rgb[i * 3 + c] = pixels[i * channels + (channels >= 3 ? c : 0)];
    write_atomically(path, width, height, 3, ImageSampleType::Float, ImageSampleType::Float, false,
                     rgb.data());
  } else if (extension == ".exr") {
    const ImageSampleType stored =
        options.exr_half ? ImageSampleType::Half : ImageSampleType::Float;
    if (options.exr_half) {
      constexpr float kHalfMax = 65504.0f;
      std::vector<float> clamped(pixels, pixels + texels * channels);
      for (float& v : clamped)
        if (!std::isnan(v)) v = std::clamp(v, -kHalfMax, kHalfMax);
      write_atomically(path, width, height, channels, stored, ImageSampleType::Float, true,
                       clamped.data());
    } else {
      write_atomically(path, width, height, channels, stored, ImageSampleType::Float, true, pixels);
    }
  } else {
    fail(path, "unsupported output extension '" + extension + "' (use .exr, .hdr or .png)");
  }
}

void write_png_rgba8(const std::string& path, int width, int height, const unsigned char* rgba) {
  if (width <= 0 || height <= 0) fail(path, "cannot write an empty image");
  if (lower_extension(path) != ".png") fail(path, "write_png_rgba8 writes .png files only");
  write_atomically(path, width, height, 4, ImageSampleType::UInt8, ImageSampleType::UInt8, false,
                   rgba);
}

}  // namespace prt::relight
