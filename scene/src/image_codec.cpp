// scene/src/image_codec.cpp — opening the OpenImageIO plugin and calling it (scene/image_codec.h).
#include "scene/image_codec.h"

#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <stdexcept>
#include <vector>

#include "image_codec_abi.h"
#include "scene_file_errors.h"

namespace prt::scene {
namespace {

constexpr const char* kPluginName = "libprt_image_oiio.so";

std::vector<std::string> plugin_candidates() {
  std::vector<std::string> paths;
  if (const char* env = std::getenv("PRT_IMAGE_PLUGIN"); env != nullptr && env[0] != '\0')
    paths.emplace_back(env);
  std::error_code error;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", error);
  if (!error) paths.push_back((exe.parent_path().parent_path() / "lib/prt" / kPluginName).string());
#ifdef PRT_IMAGE_PLUGIN_BUILD_PATH
  paths.emplace_back(PRT_IMAGE_PLUGIN_BUILD_PATH);
#endif
  return paths;
}

struct LoadedCodec {
  const PrtImageCodec* codec = nullptr;
  std::string problem;  // why it did not load
};

const LoadedCodec& loaded_codec() {
  static LoadedCodec loaded;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const std::string& path : plugin_candidates()) {
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (handle == nullptr) {
        tried += (tried.empty() ? "" : "; ") + detail::condense(dlerror());
        continue;
      }
      auto entry = reinterpret_cast<PrtImageCodecEntry>(dlsym(handle, PRT_IMAGE_CODEC_ENTRY));
      const PrtImageCodec* codec = entry != nullptr ? entry() : nullptr;
      if (codec != nullptr && codec->abi == PRT_IMAGE_CODEC_ABI) {
        loaded.codec = codec;
        return;
      }
      tried += (tried.empty() ? "" : "; ") + path + ": not a prt image plugin of this version";
    }
    loaded.problem = "OpenImageIO support is not available (" + tried +
                     "; set PRT_IMAGE_PLUGIN to the path of " + kPluginName + ")";
  });
  return loaded;
}

float* allocate_pixels(void* context, int width, int height, int channels) {
  auto* image = static_cast<FloatImage*>(context);
  image->width = width;
  image->height = height;
  image->channels = channels;
  image->pixels.resize(static_cast<std::size_t>(width) * static_cast<std::size_t>(height) *
                       static_cast<std::size_t>(channels));
  return image->pixels.data();
}

int read_flags(const ImageReadOptions& options) {
  return options.unassociated_alpha ? PRT_READ_UNASSOCIATED_ALPHA : 0;
}

int pixel_type(ImageSampleType type) {
  switch (type) {
    case ImageSampleType::UInt8:
      return PRT_PIXEL_UINT8;
    case ImageSampleType::Half:
      return PRT_PIXEL_HALF;
    default:
      return PRT_PIXEL_FLOAT;
  }
}

}  // namespace

FloatImage decode_image_file(const std::string& path, const std::string& format,
                             std::size_t max_texels, const ImageReadOptions& options) {
  const LoadedCodec& loaded = loaded_codec();
  if (loaded.codec == nullptr) throw std::runtime_error(path + ": " + loaded.problem);
  FloatImage image;
  char error[1024] = "";
  if (loaded.codec->read(path.c_str(), format.c_str(), max_texels, read_flags(options),
                         &allocate_pixels, &image, error, sizeof error) != PRT_CODEC_OK)
    throw std::runtime_error(path + ": " + detail::condense(error));
  return image;
}

FloatImage decode_image_memory(const void* bytes, std::size_t size, const std::string& format,
                               const std::string& name, std::size_t max_texels,
                               const ImageReadOptions& options) {
  const LoadedCodec& loaded = loaded_codec();
  if (loaded.codec == nullptr) throw std::runtime_error(name + ": " + loaded.problem);
  FloatImage image;
  char error[1024] = "";
  if (loaded.codec->read_memory(bytes, size, format.c_str(), max_texels, read_flags(options),
                                &allocate_pixels, &image, error, sizeof error) != PRT_CODEC_OK)
    throw std::runtime_error(name + ": " + detail::condense(error));
  return image;
}

prt::Status encode_image_file(const std::string& path, const std::string& file, int width,
                              int height, int channels, ImageSampleType file_type,
                              ImageSampleType buffer_type, bool name_y, const void* pixels) {
  const LoadedCodec& loaded = loaded_codec();
  if (loaded.codec == nullptr) return prt::Status::Error(path + ": " + loaded.problem);
  char error[1024] = "";
  const int status = loaded.codec->write(path.c_str(), file.c_str(), width, height, channels,
                                         pixel_type(file_type), pixel_type(buffer_type),
                                         name_y ? 1 : 0, pixels, error, sizeof error);
  if (status == PRT_CODEC_NO_WRITER)
    return prt::Status::Error(
        path + ": " +
        detail::condense(std::string("no image writer for this extension (") + error + ")"));
  if (status != PRT_CODEC_OK)
    return prt::Status::Error(path + ": " +
                              detail::condense(std::string("cannot write: ") + error));
  return prt::Status::Ok();
}

}  // namespace prt::scene
