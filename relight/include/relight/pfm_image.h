// relight/pfm_image.h — decoding Portable Float Map images (.pfm) from memory.
//
// The file: "PF" (3 channels, RGB) or "Pf" (1 channel, grey), whitespace, the width, whitespace,
// the height, whitespace, the scale, exactly one whitespace byte (usually "\n"), then
// width × height × channels 32-bit IEEE floats, rows from the BOTTOM of the image to the top, each
// row left to right. The scale's sign gives the byte order: negative = little-endian, positive =
// big-endian. Its magnitude multiplies every sample, as OpenImageIO does (so a file with scale
// −1 or 1 — nearly all of them — is returned as stored, bit for bit); a zero or non-finite scale
// is refused (zero carries no byte order). "#" comments up to the end of a line are allowed
// between the header fields, as in the other Netpbm formats. Width and height are decimal, 1 to 9
// digits; the scale is a decimal floating-point number. NaN, infinite and negative samples are
// returned as stored (the environment code decides what to do with them). Bytes after the pixels
// are ignored.
//
// Errors throw std::runtime_error with one line "NAME: problem": bad magic, a malformed header,
// a zero size, more than `max_texels` texels (refused before allocating), fewer pixel bytes than
// the header announces (checked before allocating, so memory is only allocated for pixels the
// data holds).
#pragma once

#include <cstddef>
#include <string>

#include "relight/float_image.h"

namespace prt::relight {

// True if the bytes start with "PF" or "Pf" followed by whitespace.
bool has_pfm_magic(const unsigned char* data, std::size_t size) noexcept;

// Decodes a PFM file held in memory: 3 channels for "PF", 1 for "Pf", row 0 at the top. `name`
// (usually the path) starts every error message.
FloatImage decode_pfm(const unsigned char* data, std::size_t size, const std::string& name,
                      std::size_t max_texels = kMaxImageTexels);

}  // namespace prt::relight
