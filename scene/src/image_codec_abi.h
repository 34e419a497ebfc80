// scene/src/image_codec_abi.h (private) — the C interface between prt and its OpenImageIO
// plugin (scene/plugin/openimageio_codec.cpp, built as the module libprt_image_oiio.so).
//
// prt decodes Radiance RGBE and PFM itself; every other image format goes through OpenImageIO,
// which loads about 250 shared libraries (OpenCV, FFmpeg, OpenVDB, ...) and costs a second and
// 130 MB at start-up. Keeping it in a plugin that image_codec.cpp opens on first use means that
// `prt info`, `prt bake` of an untextured scene and `prt env` on an .hdr file never pay for it.
// It sits in scene/ because the scene loader decodes textures with it (relight/ uses it too). The
// interface is plain C so that the plugin and the program need not share a C++ ABI beyond this
// header.
//
// Error texts are written NUL-terminated into the caller's buffer (truncated to its size).
#pragma once

#include <stddef.h>

extern "C" {

#define PRT_IMAGE_CODEC_ABI 2

// Pixel types of a write: the type stored in the file and the type of the caller's buffer.
enum PrtImagePixelType { PRT_PIXEL_UINT8 = 0, PRT_PIXEL_HALF = 1, PRT_PIXEL_FLOAT = 2 };

// Flags of a read.
enum PrtImageReadFlags {
  PRT_READ_UNASSOCIATED_ALPHA = 1,  // colour as stored, not multiplied by alpha (PNG, TIFF, ...)
};

// Status of a call.
enum PrtImageCodecStatus {
  PRT_CODEC_OK = 0,
  PRT_CODEC_FAILED = 1,     // the error text is the whole problem
  PRT_CODEC_NO_WRITER = 2,  // write: OpenImageIO has no writer for the name's extension
};

typedef struct PrtImageCodec {
  int abi;  // PRT_IMAGE_CODEC_ABI
  // Reads `path` as float pixels with the reader of `format` (an OpenImageIO format name, e.g.
  // "openexr"), or by probing every reader when `format` is empty. The plugin checks the size
  // (at most max_texels texels, depth 1, at most 4·max_texels samples), then asks `allocate` for
  // width·height·channels floats and decodes into them. `flags`: PrtImageReadFlags.
  int (*read)(const char* path, const char* format, unsigned long long max_texels, int flags,
              float* (*allocate)(void* context, int width, int height, int channels), void* context,
              char* error, size_t error_size);
  // Writes width × height × channels pixels of `buffer_type` from `pixels` to `file`, with the
  // writer that `name_for_format`'s extension selects, stored as `file_type`. A one-channel image
  // names its channel "Y" when name_y is non-zero.
  int (*write)(const char* name_for_format, const char* file, int width, int height, int channels,
               int file_type, int buffer_type, int name_y, const void* pixels, char* error,
               size_t error_size);
  // Reads an image held in memory (`size` bytes) with the reader of `format` (required: "png",
  // "jpeg", ...), with the checks and the allocation of `read`.
  int (*read_memory)(const void* bytes, size_t size, const char* format,
                     unsigned long long max_texels, int flags,
                     float* (*allocate)(void* context, int width, int height, int channels),
                     void* context, char* error, size_t error_size);
} PrtImageCodec;

// The plugin's one exported symbol.
typedef const PrtImageCodec* (*PrtImageCodecEntry)(void);
#define PRT_IMAGE_CODEC_ENTRY "prt_image_codec_v1"

}  // extern "C"
