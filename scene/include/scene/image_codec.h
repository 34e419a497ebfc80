// scene/image_codec.h — decoding and encoding images through the OpenImageIO plugin, opened on
// first use (the plugin's C interface is scene/src/image_codec_abi.h).
//
// OpenImageIO loads about 250 shared libraries and costs a second at start-up, so it lives in a
// module that is opened only when an image is read or written: by the scene loader for texture
// images (scene/texture.h) and by relight/image_io.h for environment maps and rendered images.
// Commands that touch no such image (prt info, prt bake of an untextured scene, prt env on a
// Radiance file) never load it.
//
// The plugin is looked for, in order, at $PRT_IMAGE_PLUGIN, beside the installed program
// (<prefix>/lib/prt/libprt_image_oiio.so for <prefix>/bin/prt), and where the build tree made it.
// When none loads, reads and writes fail with "NAME: OpenImageIO support is not available (…)".
//
// Pixels are returned as stored (no colour-space conversion), as float: 8-bit and 16-bit
// integer samples are scaled to [0, 1].
#pragma once

#include <cstddef>
#include <string>

#include "prt/core/status.h"
#include "scene/float_image.h"

namespace prt::scene {

// How colour and alpha come back: by default as OpenImageIO gives them (colour associated with,
// i.e. multiplied by, alpha); with unassociated_alpha as the file stores them (textures).
struct ImageReadOptions {
  bool unassociated_alpha = false;
};

// Reads `path` with OpenImageIO's reader for `format` (an OpenImageIO format name such as
// "openexr" or "png"; "" = probe every reader). Throws std::runtime_error "PATH: problem" (one
// line), also for more than max_texels texels.
FloatImage decode_image_file(const std::string& path, const std::string& format,
                             std::size_t max_texels, const ImageReadOptions& options = {});

// Reads an image held in memory with the reader of `format` (required, e.g. "png", "jpeg").
// Errors are thrown as std::runtime_error "NAME: problem".
FloatImage decode_image_memory(const void* bytes, std::size_t size, const std::string& format,
                               const std::string& name, std::size_t max_texels,
                               const ImageReadOptions& options = {});

// Sample types of an encode: the type stored in the file and the type of the caller's buffer.
enum class ImageSampleType { UInt8, Half, Float };

// Writes pixels to `file` with the writer that `path`'s extension selects; errors name `path`
// (`file` may be a temporary that is renamed onto `path` afterwards). A one-channel image names
// its channel "Y" when name_y is set.
prt::Status encode_image_file(const std::string& path, const std::string& file, int width,
                              int height, int channels, ImageSampleType file_type,
                              ImageSampleType buffer_type, bool name_y, const void* pixels);

}  // namespace prt::scene
