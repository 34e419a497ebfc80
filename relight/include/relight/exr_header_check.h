// relight/exr_header_check.h — a plausibility check of OpenEXR headers, run on the file's bytes
// before OpenImageIO/OpenEXR open them.
//
// Why: OpenEXR 3.1 allocates whatever a header claims before it finds out that the file cannot
// hold it — a string attribute "of 2 GB" in a 100-byte file, line buffers for a data window
// 7 million pixels wide, a preview image of 4 billion pixels. This walks the header(s) without
// allocating and refuses such files first, with a one-line problem. It only refuses files that
// are broken (an attribute larger than the rest of the file, a malformed attribute) or that the
// caller refuses anyway (more than `max_texels` texels, or more samples than 4 float channels'
// worth — texels × bytes per texel over 16 × max_texels — as relight::read_image does), plus
// documented caps that no environment map comes near:
//   - data window and tile sides at most kMaxExrSide (65536): every layout within the texel cap
//     needs at most 40132 (faces, 6688 × 40128), and OpenEXR sizes line buffers and per-line
//     tables by the width and the height;
//   - at most kMaxExrBytesPerTexel (256, e.g. 64 float channels) bytes per texel over all
//     channels, and tiles of at most 16 × max_texels bytes.
// Anything it does not understand (another magic, unknown attribute types, out-of-range enums)
// is left to OpenEXR.
//
// Format walked (openexr.com, "OpenEXR File Layout"): magic 76 2f 31 01, a 4-byte version field
// (bit 12 = multi-part: headers follow one another and an empty header ends the list), then per
// header attributes "name\0type\0" + int32 size (little-endian) + size bytes of value, ended by
// an empty name. Values inspected: dataWindow (box2i), tiles (tiledesc), channels (chlist),
// chunkCount (int), preview (preview), and the lengths inside stringvector.
#pragma once

#include <cstddef>
#include <string>

namespace prt::relight {

inline constexpr long long kMaxExrSide = 65536;
inline constexpr long long kMaxExrBytesPerTexel = 256;

// True if the bytes start with the OpenEXR magic number 76 2f 31 01.
bool has_exr_magic(const unsigned char* data, std::size_t size) noexcept;

// "" if nothing implausible was found, else the problem (one line, without the file name).
std::string exr_header_problem(const unsigned char* data, std::size_t size, std::size_t max_texels);

}  // namespace prt::relight
