// relight/src/image_codec.h (private) — image formats other than Radiance and PFM, through the
// OpenImageIO plugin (image_codec_abi.h), opened on first use.
//
// The plugin is looked for, in order, at $PRT_IMAGE_PLUGIN, beside the installed program
// (<prefix>/lib/prt/libprt_image_oiio.so for <prefix>/bin/prt), and where the build tree made it.
// When none loads, reads and writes fail with "PATH: OpenImageIO support is not available (…)".
#pragma once

#include <cstddef>
#include <string>

#include "image_codec_abi.h"
#include "prt/status.h"
#include "relight/float_image.h"

namespace prt::relight::detail {

// Reads `path` with OpenImageIO's reader for `format` ("" = probe every reader). Throws
// std::runtime_error "PATH: problem" (one line).
FloatImage codec_read(const std::string& path, const std::string& format, std::size_t max_texels);

// Writes pixels to `file` with the writer that `path`'s extension selects; errors name `path`.
prt::Status codec_write(const std::string& path, const std::string& file, int width, int height,
                        int channels, PrtImagePixelType file_type, PrtImagePixelType buffer_type,
                        bool name_y, const void* pixels);

}  // namespace prt::relight::detail
