// relight/src/radiance_hdr.cpp — Radiance RGBE decoding from memory (see relight/radiance_hdr.h).
#include "relight/radiance_hdr.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "message_text.h"

namespace prt::relight {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& problem) {
  throw std::runtime_error(name + ": " + problem);
}

// A piece of header text for an error message: printable ASCII only, at most 40 characters.
std::string quoted(std::string_view text) {
  return detail::quoted(text, 40);
}

std::string size_text(std::uint64_t width, std::uint64_t height) {
  return std::to_string(width) + "x" + std::to_string(height);
}

// The line starting at *pos, without its "\n" or "\r\n"; false if no '\n' ends it.
bool next_line(std::string_view data, std::size_t* pos, std::string_view* line) {
  const std::size_t end = data.find('\n', *pos);
  if (end == std::string_view::npos) return false;
  *line = data.substr(*pos, end - *pos);
  if (!line->empty() && line->back() == '\r') line->remove_suffix(1);
  *pos = end + 1;
  return true;
}

bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

std::string_view trim_right(std::string_view text) {
  while (!text.empty() && is_blank(text.back())) text.remove_suffix(1);
  return text;
}

// One half of a resolution line, e.g. "-Y 512".
struct Axis {
  bool increasing = false;  // '+'
  char letter = 0;          // 'X' or 'Y'
  std::uint32_t size = 0;
};

// Parses "<+|-><X|Y> <1 to 9 digits>" at *at (blanks before it skipped); false on anything else.
bool parse_axis(std::string_view line, std::size_t* at, Axis* axis) {
  std::size_t i = *at;
  while (i < line.size() && is_blank(line[i])) ++i;
  if (i + 2 > line.size()) return false;
  const char sign = line[i], letter = line[i + 1];
  if ((sign != '+' && sign != '-') || (letter != 'X' && letter != 'Y')) return false;
  i += 2;
  if (i >= line.size() || !is_blank(line[i])) return false;
  while (i < line.size() && is_blank(line[i])) ++i;
  std::uint32_t value = 0;
  int digits = 0;
  for (; i < line.size() && line[i] >= '0' && line[i] <= '9'; ++i) {
    if (++digits > 9) return false;
    value = value * 10 + static_cast<std::uint32_t>(line[i] - '0');
  }
  if (digits == 0) return false;
  axis->increasing = sign == '+';
  axis->letter = letter;
  axis->size = value;
  *at = i;
  return true;
}

// The fewest bytes any valid encoding of a scanline of `length` pixels can take: flat data with
// old-style repeats (one pixel, then r repeat records covering up to 256^r − 1 more pixels), or
// new-style RLE (4 header bytes, then 4 planes of 2-byte runs of at most 127).
std::uint64_t min_scanline_bytes(std::uint32_t length) {
  std::uint64_t records = 0, reach = 0;
  while (reach < length - 1u) {
    ++records;
    reach = reach * 256 + 255;
  }
  const std::uint64_t old_style = 4 + 4 * records;
  if (length < 8 || length > 0x7fff) return old_style;
  const std::uint64_t new_style = 4 + 4 * 2 * ((std::uint64_t{length} + 126) / 127);
  return std::min(old_style, new_style);
}

// 2^(e − 136) for e = 1..255 (exact in float: 2^-135 is a denormal), 0 for e = 0.
const std::array<float, 256>& exponent_scales() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> t{};
    for (int e = 1; e < 256; ++e) t[static_cast<std::size_t>(e)] = std::ldexp(1.0f, e - 136);
    return t;
  }();
  return table;
}

}  // namespace

bool has_radiance_magic(const unsigned char* data, std::size_t size) noexcept {
  return size >= 2 && data[0] == '#' && data[1] == '?';
}

namespace {

// The header after the "#?" line, up to the blank line that ends it: it must declare
// FORMAT=32-bit_rle_rgbe. Returns the position after it.
std::size_t read_header(std::string_view text, const std::string& name) {
  std::size_t pos = 0;
  std::string_view line;
  if (!next_line(text, &pos, &line)) fail(name, "truncated header (the first line never ends)");
  bool format_seen = false;
  for (;;) {
    if (!next_line(text, &pos, &line)) fail(name, "truncated header (no blank line ends it)");
    if (line.empty()) break;
    constexpr std::string_view kFormat = "FORMAT=";
    if (line.substr(0, kFormat.size()) != kFormat) continue;  // comments, EXPOSURE=, ...
    const std::string_view value = trim_right(line.substr(kFormat.size()));
    if (value == "32-bit_rle_rgbe") {
      format_seen = true;
    } else if (value == "32-bit_rle_xyze") {
      fail(name, "XYZE pixels (FORMAT=32-bit_rle_xyze) are not supported; convert the map to RGBE");
    } else {
      fail(name, "unsupported pixel format " + quoted(value) + " (expected 32-bit_rle_rgbe)");
    }
  }
  if (!format_seen) fail(name, "the header has no FORMAT=32-bit_rle_rgbe line");
  return pos;
}

// The resolution line: scanlines run along `minor`, one after another along `major`.
struct Resolution {
  Axis major, minor;
  std::uint32_t width = 0, height = 0;
};

// Reads the resolution line at *pos (advancing it) and checks the size against max_texels and
// against the bytes left.
Resolution read_resolution(std::string_view text, std::size_t* pos, const std::string& name,
                           std::size_t max_texels) {
  const std::size_t size = text.size();
  std::string_view line;
  if (!next_line(text, pos, &line)) fail(name, "truncated: no resolution line after the header");
  Resolution r;
  Axis &major = r.major, &minor = r.minor;
  std::size_t at = 0;
  if (!parse_axis(line, &at, &major) || !parse_axis(line, &at, &minor) ||
      !trim_right(line.substr(at)).empty() || major.letter == minor.letter)
    fail(name, "bad resolution line " + quoted(line) + " (expected e.g. \"-Y 512 +X 1024\")");
  const std::uint32_t width = r.width = major.letter == 'X' ? major.size : minor.size;
  const std::uint32_t height = r.height = major.letter == 'Y' ? major.size : minor.size;
  if (width == 0 || height == 0)
    fail(name, "the image has zero size (" + size_text(width, height) + ")");
  const std::uint64_t texels = std::uint64_t{width} * height;
  if (texels > max_texels)
    fail(name, size_text(width, height) + " is too large (more than " + std::to_string(max_texels) +
                   " texels)");
  const std::uint32_t scanlines = major.size, length = minor.size;
  const std::uint64_t needed = std::uint64_t{scanlines} * min_scanline_bytes(length);
  if (size - *pos < needed)
    fail(name, "truncated: " + size_text(width, height) + " pixels need at least " +
                   std::to_string(needed) + " bytes, the file has " + std::to_string(size - *pos) +
                   " after the header");
  return r;
}

// Pixel i of scanline s goes to pixels[(first_row + s·row_per_scanline)·w·3 +
// (first_col + s·col_per_scanline)·3 + i·step] (upright: row 0 at the top).
struct ScanlinePlacement {
  std::ptrdiff_t step = 0;
  std::ptrdiff_t first_row = 0, first_col = 0, row_per_scanline = 0, col_per_scanline = 0;
};

ScanlinePlacement scanline_placement(const Resolution& r) {
  const std::ptrdiff_t w = r.width, h = r.height;
  ScanlinePlacement pl;
  if (r.major.letter == 'Y') {  // scanlines are rows: "-Y" from the top, "+Y" from the bottom
    pl.step = r.minor.increasing ? 3 : -3;
    pl.first_row = r.major.increasing ? h - 1 : 0;
    pl.row_per_scanline = r.major.increasing ? -1 : 1;
    pl.first_col = r.minor.increasing ? 0 : w - 1;
  } else {  // scanlines are columns: "+X" from the left, "-X" from the right
    pl.step = r.minor.increasing ? -3 * w : 3 * w;
    pl.first_col = r.major.increasing ? 0 : w - 1;
    pl.col_per_scanline = r.major.increasing ? 1 : -1;
    pl.first_row = r.minor.increasing ? h - 1 : 0;
  }
  return pl;
}

// Throws "NAME: scanline S of N: problem".
struct ScanlineError {
  const std::string& name;
  std::uint32_t s, scanlines;
  [[noreturn]] void operator()(const std::string& problem) const {
    fail(name,
         "scanline " + std::to_string(s + 1) + " of " + std::to_string(scanlines) + ": " + problem);
  }
};

// A new-style RLE scanline at p (its 4-byte header checked and skipped) into the R, G, B, E
// planes; returns the position after it.
const unsigned char* decode_rle_scanline(const unsigned char* p, const unsigned char* end,
                                         std::uint32_t length, unsigned char* planes,
                                         const ScanlineError& bad) {
  const std::uint32_t encoded = (std::uint32_t{p[2]} << 8) | p[3];
  if (encoded != length)
    bad("RLE length " + std::to_string(encoded) + " differs from the scanline length " +
        std::to_string(length));
  p += 4;
  for (std::size_t c = 0; c < 4; ++c) {
    unsigned char* plane = &planes[c * length];
    std::uint32_t filled = 0;
    while (filled < length) {
      if (p == end) bad("the data ends inside the scanline");
      const std::uint32_t code = *p++;
      if (code > 128) {
        const std::uint32_t run = code - 128;
        if (run > length - filled)
          bad("an RLE run of " + std::to_string(run) + " overflows the scanline");
        if (p == end) bad("the data ends inside the scanline");
        std::memset(plane + filled, *p++, run);
        filled += run;
      } else {
        if (code == 0) bad("a zero-length RLE literal");
        if (code > length - filled)
          bad("an RLE literal of " + std::to_string(code) + " overflows the scanline");
        if (static_cast<std::uint64_t>(end - p) < code) bad("the data ends inside the scanline");
        std::memcpy(plane + filled, p, code);
        p += code;
        filled += code;
      }
    }
  }
  return p;
}

// A scanline of flat pixels, with old-style repeat records (1, 1, 1, n), into the R, G, B, E
// planes; returns the position after it.
const unsigned char* decode_flat_scanline(const unsigned char* p, const unsigned char* end,
                                          std::uint32_t length, unsigned char* planes,
                                          const ScanlineError& bad) {
  std::uint32_t filled = 0;
  int shift = 0;
  while (filled < length) {
    if (end - p < 4) bad("the data ends inside the scanline");
    if (p[0] == 1 && p[1] == 1 && p[2] == 1) {
      if (filled == 0) bad("an old-style RLE repeat with no pixel before it");
      const std::uint64_t count = std::uint64_t{p[3]} << shift;  // shift <= 32
      if (count > length - filled)
        bad("an old-style RLE repeat of " + std::to_string(count) +
            " pixels overflows the scanline");
      for (std::size_t c = 0; c < 4; ++c) {
        unsigned char* plane = &planes[c * length];
        std::memset(plane + filled, plane[filled - 1], static_cast<std::size_t>(count));
      }
      filled += static_cast<std::uint32_t>(count);
      shift = std::min(shift + 8, 32);
    } else {
      for (std::size_t c = 0; c < 4; ++c) planes[c * length + filled] = p[c];
      ++filled;
      shift = 0;
    }
    p += 4;
  }
  return p;
}

// Scanline s's R, G, B, E planes → float pixels of the image, m · 2^(e − 136).
void store_scanline(const unsigned char* planes, std::uint32_t length, std::uint32_t s,
                    const ScanlinePlacement& pl, FloatImage& image) {
  const std::array<float, 256>& scale = exponent_scales();
  const std::ptrdiff_t w = image.width;
  const std::ptrdiff_t row = pl.first_row + pl.row_per_scanline * static_cast<std::ptrdiff_t>(s);
  const std::ptrdiff_t col = pl.first_col + pl.col_per_scanline * static_cast<std::ptrdiff_t>(s);
  float* const pixels = image.pixels.data();
  std::ptrdiff_t index = (row * w + col) * 3;
  const unsigned char* r = planes;
  const unsigned char* g = r + length;
  const unsigned char* b = g + length;
  const unsigned char* e = b + length;
  for (std::uint32_t i = 0; i < length; ++i, index += pl.step) {
    float* out = pixels + index;
    const float f = scale[e[i]];
    out[0] = static_cast<float>(r[i]) * f;
    out[1] = static_cast<float>(g[i]) * f;
    out[2] = static_cast<float>(b[i]) * f;
  }
}

}  // namespace

FloatImage decode_radiance_hdr(const unsigned char* data, std::size_t size, const std::string& name,
                               std::size_t max_texels) {
  if (!has_radiance_magic(data, size))
    fail(name, "not a Radiance RGBE file (it does not start with \"#?\")");
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  std::size_t pos = read_header(text, name);
  const Resolution res = read_resolution(text, &pos, name, max_texels);

  FloatImage image;
  image.width = static_cast<int>(res.width);
  image.height = static_cast<int>(res.height);
  image.channels = 3;
  image.pixels.resize(static_cast<std::size_t>(std::uint64_t{res.width} * res.height) * 3);

  const ScanlinePlacement placement = scanline_placement(res);
  const std::uint32_t scanlines = res.major.size, length = res.minor.size;
  std::vector<unsigned char> planes(std::size_t{4} * length);  // R, G, B, E planes of a scanline
  const unsigned char* p = data + pos;
  const unsigned char* const end = data + size;
  for (std::uint32_t s = 0; s < scanlines; ++s) {
    const ScanlineError bad{name, s, scanlines};
    const bool new_rle = length >= 8 && length <= 0x7fff && end - p >= 4 && p[0] == 2 &&
                         p[1] == 2 && (p[2] & 0x80) == 0;
    p = new_rle ? decode_rle_scanline(p, end, length, planes.data(), bad)
                : decode_flat_scanline(p, end, length, planes.data(), bad);
    store_scanline(planes.data(), length, s, placement, image);
  }
  return image;
}

}  // namespace prt::relight
