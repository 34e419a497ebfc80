// relight/image_io.h — reading environment maps and writing images.
//
// Environment maps are read as linear float RGB (sh::EnvMap: row 0 at the top, layouts and the
// glTF frame as in sh/env_map.h). Radiance RGBE (.hdr, .pic) and PFM are decoded by the
// project's own decoders (relight/radiance_hdr.h, relight/pfm_image.h); everything else (.exr,
// .png, ...) by OpenImageIO. Alpha and extra channels are dropped, one- and two-channel images
// are treated as grey (channel 0 replicated). No colour-space conversion is applied: HDR formats
// hold linear radiance. NaN, infinite and negative texels are passed through as stored
// (relight/environment_input.h applies the commands' policy to them, sh/env_check.h).
//
// Which decoder reads a file: the magic "#?" → Radiance; "PF"/"Pf" + whitespace → PFM; otherwise
// the extension .hdr/.rgbe → Radiance and .pfm → PFM (which then refuse the file's magic), and
// anything else → OpenImageIO's reader for the extension's format only (a bad .exr fails in the
// OpenEXR plugin instead of being offered to every plugin in turn). ".pic" without "#?" goes to
// OpenImageIO (Softimage PIC shares the extension). A file whose extension OpenImageIO does not
// know is offered to all its plugins, as before. OpenEXR files (magic 76 2f 31 01) have their
// headers checked by relight/exr_header_check.h first (OpenEXR would otherwise allocate whatever
// a hostile header claims).
//
// Size: images of more than `max_texels` texels (default kMaxImageTexels = 2^28, e.g. 16384 ×
// 16384) are refused before their pixels are allocated; so are volume images (depth > 1) and
// images with more samples than 4 channels' worth (texels × channels > 4 × max_texels).
//
// Errors are thrown as std::runtime_error with a one-line message "PATH: problem".
// Writes are atomic: the image goes to PATH.tmp-<pid> and is renamed onto PATH; on error the
// temporary is removed and nothing partial is left behind.
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "relight/float_image.h"
#include "sh/env_map.h"

namespace prt::relight {

// Reads an environment map. With no layout, the layout is guessed from the aspect ratio
// (sh::guess_layout) and *chosen_note (if given) says which was taken and why, e.g.
// "layout angular (auto: 1000x1000 is 1:1)". With layout Faces and a path containing "%s",
// the six faces are read with read_environment_faces_pattern. Throws for a missing or unreadable
// file, a zero-size image, or an aspect ratio that fits no layout / not the requested one.
sh::EnvMap read_environment(const std::string& path, std::optional<sh::EnvLayout> layout,
                            std::string* chosen_note = nullptr);

// Reads six square faces of equal size, in the order +X, −X, +Y, −Y, +Z, −Z, each as seen from
// the centre of the cube (see sh/env_map.h, layout Faces), into one Faces map.
sh::EnvMap read_environment_faces(const std::vector<std::string>& six_paths);

// The same with a path pattern whose "%s" is replaced by px, nx, py, ny, pz, nz.
sh::EnvMap read_environment_faces_pattern(const std::string& pattern);

// The six face names substituted for "%s": px, nx, py, ny, pz, nz.
inline constexpr std::array<const char*, 6> kFaceSuffixes = {"px", "nx", "py", "ny", "pz", "nz"};

// Reads any image as float pixels (channels as stored; relight/float_image.h). Throws like
// read_environment, and for more than `max_texels` texels.
FloatImage read_image(const std::string& path, std::size_t max_texels = kMaxImageTexels);

// The layout step of read_environment on an already decoded image: checks the requested layout
// or guesses it from the aspect ratio (see read_environment; errors name `path`), then converts
// to RGB (the pixels are moved, not copied, when the image has 3 channels).
sh::EnvMap to_environment(FloatImage image, const std::string& path,
                          std::optional<sh::EnvLayout> layout, std::string* chosen_note = nullptr);

struct ImageWriteOptions {
  // EXR only: store 16-bit half floats instead of 32-bit floats. Values beyond the half range
  // (65504) are clamped to it rather than turned into infinities (a bright sun can exceed it).
  bool exr_half = false;
};

// Writes width × height × channels floats (row 0 at the top) by the path's extension:
//   .exr  float or half (options), channels as given (1 = Y, 3 = RGB, 4 = RGBA);
//   .hdr  RGBE (Radiance); 1 channel is replicated to RGB, a 4th channel is dropped;
//   .png  8 bits per channel: the caller passes display-encoded values in [0, 1] (tone mapping
//         lives elsewhere); they are clamped and rounded to 0..255 (NaN → 0).
// Atomic (temporary + rename). Throws std::runtime_error "PATH: problem" on failure.
void write_image(const std::string& path, int width, int height, int channels, const float* pixels,
                 const ImageWriteOptions& options = {});

// Writes an already 8-bit RGBA image as PNG, atomically.
void write_png_rgba8(const std::string& path, int width, int height, const unsigned char* rgba);

}  // namespace prt::relight
