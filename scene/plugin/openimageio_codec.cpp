// scene/plugin/openimageio_codec.cpp — the OpenImageIO plugin: image reading (from a file or from
// memory) and writing behind the C interface of scene/src/image_codec_abi.h. Built as the module
// libprt_image_oiio.so and opened by scene/src/image_codec.cpp on first use.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <memory>
#include <string>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "../src/image_codec_abi.h"

namespace {

int report(const std::string& text, char* error, size_t error_size, int status) {
  if (error != nullptr && error_size > 0) {
    const size_t n = std::min(text.size(), error_size - 1);
    std::memcpy(error, text.data(), n);
    error[n] = '\0';
  }
  return status;
}

std::string size_text(long long width, long long height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

OIIO::TypeDesc type_of(int pixel_type) {
  switch (pixel_type) {
    case PRT_PIXEL_UINT8:
      return OIIO::TypeDesc::UINT8;
    case PRT_PIXEL_HALF:
      return OIIO::TypeDesc::HALF;
    default:
      return OIIO::TypeDesc::FLOAT;
  }
}

// Checks the opened image's size, allocates through the caller and decodes all channels as float.
int decode_opened(OIIO::ImageInput& in, unsigned long long max_texels,
                  float* (*allocate)(void*, int, int, int), void* context, char* error,
                  size_t error_size) {
  auto fail = [&](const std::string& problem) {
    return report(problem, error, error_size, PRT_CODEC_FAILED);
  };
  const OIIO::ImageSpec& spec = in.spec();
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    return fail("the image has zero size (" + size_text(spec.width, spec.height) + ")");
  if (spec.depth > 1)
    return fail("volume images are not supported (depth " + std::to_string(spec.depth) + ")");
  const std::uint64_t texels = static_cast<std::uint64_t>(spec.width) * spec.height;
  if (texels > max_texels)
    return fail(size_text(spec.width, spec.height) + " is too large (more than " +
                std::to_string(max_texels) + " texels)");
  if (texels * static_cast<std::uint64_t>(spec.nchannels) > 4 * std::uint64_t{max_texels})
    return fail(size_text(spec.width, spec.height) + " with " + std::to_string(spec.nchannels) +
                " channels is too large");
  float* pixels = allocate(context, spec.width, spec.height, spec.nchannels);
  if (pixels == nullptr) return fail("cannot allocate the pixels");
  if (!in.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels))
    return fail("cannot read the pixels: " + in.geterror());
  in.close();
  return PRT_CODEC_OK;
}

// The reader's configuration for `flags` (PrtImageReadFlags).
OIIO::ImageSpec read_config(int flags) {
  OIIO::ImageSpec config;
  if ((flags & PRT_READ_UNASSOCIATED_ALPHA) != 0) config.attribute("oiio:UnassociatedAlpha", 1);
  return config;
}

int read_image(const char* path, const char* format, unsigned long long max_texels, int flags,
               float* (*allocate)(void*, int, int, int), void* context, char* error,
               size_t error_size) {
  auto fail = [&](const std::string& problem) {
    return report(problem, error, error_size, PRT_CODEC_FAILED);
  };
  const OIIO::ImageSpec config = read_config(flags);
  std::unique_ptr<OIIO::ImageInput> in;
  if (format != nullptr && format[0] != '\0') in = OIIO::ImageInput::create(format);
  if (in) {
    OIIO::ImageSpec opened;
    if (!in->open(path, opened, config)) {
      std::string why = in->geterror();
      if (why.empty()) why = OIIO::geterror();
      return fail("cannot read the image: " + why);
    }
  } else {
    (void)OIIO::geterror();  // drop "no format for this extension"
    in = OIIO::ImageInput::open(path, &config);
    if (!in) return fail("cannot read the image: " + OIIO::geterror());
  }
  return decode_opened(*in, max_texels, allocate, context, error, error_size);
}

int read_memory(const void* bytes, size_t size, const char* format, unsigned long long max_texels,
                int flags, float* (*allocate)(void*, int, int, int), void* context, char* error,
                size_t error_size) {
  auto fail = [&](const std::string& problem) {
    return report(problem, error, error_size, PRT_CODEC_FAILED);
  };
  if (format == nullptr || format[0] == '\0') return fail("no image format given");
  OIIO::Filesystem::IOMemReader proxy(bytes, size);
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::create(format);
  if (!in) return fail("no " + std::string(format) + " reader: " + OIIO::geterror());
  if (!in->supports("ioproxy") || !in->set_ioproxy(&proxy))
    return fail("the " + std::string(format) + " reader cannot read from memory");
  OIIO::ImageSpec opened;
  if (!in->open(std::string("memory.") + format, opened, read_config(flags))) {
    std::string why = in->geterror();
    if (why.empty()) why = OIIO::geterror();
    return fail("cannot read the image: " + why);
  }
  return decode_opened(*in, max_texels, allocate, context, error, error_size);
}

int write_image(const char* name_for_format, const char* file, int width, int height, int channels,
                int file_type, int buffer_type, int name_y, const void* pixels, char* error,
                size_t error_size) {
  // The writer is chosen from the final name; the file written may be a temporary.
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(name_for_format);
  if (!out) return report(OIIO::geterror(), error, error_size, PRT_CODEC_NO_WRITER);
  OIIO::ImageSpec spec(width, height, channels, type_of(file_type));
  if (channels == 1 && name_y != 0) spec.channelnames = {"Y"};
  // No time stamp: the same pixels give the same file (OpenEXR's writer adds the current
  // DateTime unless one is given; an empty one is left out).
  spec.attribute("DateTime", "");
  if (!out->open(file, spec)) return report(out->geterror(), error, error_size, PRT_CODEC_FAILED);
  if (!out->write_image(type_of(buffer_type), pixels)) {
    const std::string why = out->geterror();
    out->close();
    return report(why, error, error_size, PRT_CODEC_FAILED);
  }
  if (!out->close()) return report(out->geterror(), error, error_size, PRT_CODEC_FAILED);
  return PRT_CODEC_OK;
}

const PrtImageCodec kCodec = {PRT_IMAGE_CODEC_ABI, &read_image, &write_image, &read_memory};

}  // namespace

extern "C" __attribute__((visibility("default"))) const PrtImageCodec* prt_image_codec_v1(void) {
  return &kCodec;
}
