// relight/radiance_hdr.h — decoding Radiance RGBE images (.hdr, .pic) from memory.
//
// The file: a header of text lines, a blank line, a resolution line, then the pixels.
//   Header   The first line starts with "#?" (the program type after it, e.g. "#?RADIANCE" or
//            "#?RGBE", is not checked). A line "FORMAT=32-bit_rle_rgbe" is required.
//            "FORMAT=32-bit_rle_xyze" (CIE XYZ pixels) is refused with a message saying so: no
//            map in use is stored that way and converting needs the file's primaries. Every
//            other line (comments, EXPOSURE=, GAMMA=, PRIMARIES=, SOFTWARE=, ...) is ignored.
//            In particular EXPOSURE is NOT divided out: the pixels are returned as stored, as
//            OpenImageIO, stb_image and the renderers that wrote the maps in use do (the shared
//            maps all say EXPOSURE=1 or nothing). Lines may end in "\r\n".
//   Size     "-Y H +X W" is the standard orientation: H scanlines from the top, each W pixels
//            from left to right. All eight Radiance orientations are supported and returned
//            upright (row 0 at the top, +X to the right): "+Y H +X W" stores the bottom row first,
//            "-X" runs right to left, and "+X W -Y H" etc. store columns as scanlines (the image
//            is then W wide and H high all the same). Numbers are decimal, 1 to 9 digits.
//   Pixels   Each scanline is decoded on its own, in one of three encodings:
//            - new-style RLE (scanline length 8..32767): the bytes 2, 2, len >> 8, len & 255,
//              then the R, G, B and E planes in turn, each as runs (a byte 128 + n, n = 1..127,
//              then the value repeated n times) and literals (a byte n = 1..128, then n values);
//            - flat: 4 bytes R, G, B, E per pixel;
//            - old-style RLE, within flat data: a pixel (1, 1, 1, n) repeats the previous pixel
//              n << s times, s starting at 0 and growing by 8 for each consecutive such pixel.
// Conversion: mantissa m, exponent e → m · 2^(e − 136), and e = 0 → 0 (OpenImageIO's rgbe.cpp
// and Bruce Walter's rgbe.c, not Radiance's (m + ½) · 2^(e − 136)). Every value is exact in float,
// so the result is bit-identical to OpenImageIO's for the standard orientation.
//
// Strictness: anything malformed throws std::runtime_error with one line "NAME: problem" —
// bad magic, a missing FORMAT, a bad resolution line, a zero size, an RLE length that differs
// from the scanline's, a zero-length literal, a run or repeat past the end of the scanline, a
// repeat with no previous pixel in its scanline, data ending early. Images over `max_texels`
// texels are refused before anything is allocated, and so is a file too short to hold even the
// most compact encoding of its announced size, so memory is only allocated for pixels the data
// can fill. Bytes after the last scanline are ignored.
// References: [19] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <string>

#include "relight/float_image.h"

namespace prt::relight {

// True if the bytes start with the Radiance magic "#?".
bool has_radiance_magic(const unsigned char* data, std::size_t size) noexcept;

// Decodes a Radiance RGBE file held in memory into a 3-channel FloatImage. `name` (usually the
// path) starts every error message.
FloatImage decode_radiance_hdr(const unsigned char* data, std::size_t size, const std::string& name,
                               std::size_t max_texels = kMaxImageTexels);

}  // namespace prt::relight
