// relight/src/pfm_image.cpp — Portable Float Map decoding from memory (see relight/pfm_image.h).
#include "relight/pfm_image.h"

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <string_view>
#include <system_error>

#include "message_text.h"

namespace prt::relight {
namespace {

[[noreturn]] void fail(const std::string& name, const std::string& problem) {
  throw std::runtime_error(name + ": " + problem);
}

bool is_space(unsigned char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\r' || c == '\v' || c == '\f';
}

// Reads header tokens: whitespace and "#" comments (to the end of the line) are skipped.
class HeaderReader {
 public:
  HeaderReader(const unsigned char* data, std::size_t size, std::size_t pos)
      : data_(data), size_(size), pos_(pos) {}

  // The next whitespace-delimited token ("" at the end of the data).
  std::string_view token() {
    for (;;) {
      while (pos_ < size_ && is_space(data_[pos_])) ++pos_;
      if (pos_ < size_ && data_[pos_] == '#') {
        while (pos_ < size_ && data_[pos_] != '\n') ++pos_;
        continue;
      }
      break;
    }
    const std::size_t begin = pos_;
    while (pos_ < size_ && !is_space(data_[pos_]) && data_[pos_] != '#') ++pos_;
    return {reinterpret_cast<const char*>(data_) + begin, pos_ - begin};
  }

  std::size_t position() const { return pos_; }

 private:
  const unsigned char* data_;
  std::size_t size_;
  std::size_t pos_;
};

// A header token for an error message: printable ASCII only, at most 20 characters.
std::string quoted(std::string_view text) {
  return detail::quoted(text, 20);
}

// 1 to 9 decimal digits, nothing else.
bool parse_dimension(std::string_view text, std::uint32_t* value) {
  if (text.empty() || text.size() > 9) return false;
  std::uint32_t v = 0;
  for (char c : text) {
    if (c < '0' || c > '9') return false;
    v = v * 10 + static_cast<std::uint32_t>(c - '0');
  }
  *value = v;
  return true;
}

bool host_is_little_endian() {
  const std::uint32_t one = 1;
  unsigned char first;
  std::memcpy(&first, &one, 1);
  return first == 1;
}

}  // namespace

bool has_pfm_magic(const unsigned char* data, std::size_t size) noexcept {
  return size >= 3 && data[0] == 'P' && (data[1] == 'F' || data[1] == 'f') && is_space(data[2]);
}

FloatImage decode_pfm(const unsigned char* data, std::size_t size, const std::string& name,
                      std::size_t max_texels) {
  if (!has_pfm_magic(data, size))
    fail(name, "not a PFM file (it does not start with \"PF\" or \"Pf\")");
  const int channels = data[1] == 'F' ? 3 : 1;
  HeaderReader header(data, size, 2);
  const std::string_view width_text = header.token();
  const std::string_view height_text = header.token();
  std::uint32_t width = 0, height = 0;
  if (!parse_dimension(width_text, &width) || !parse_dimension(height_text, &height))
    fail(name, "bad PFM size " + quoted(width_text) + " " + quoted(height_text) +
                   " (expected two whole numbers)");
  if (width == 0 || height == 0)
    fail(name,
         "the image has zero size (" + std::to_string(width) + "x" + std::to_string(height) + ")");
  const std::uint64_t texels = std::uint64_t{width} * height;
  if (texels > max_texels)
    fail(name, std::to_string(width) + "x" + std::to_string(height) + " is too large (more than " +
                   std::to_string(max_texels) + " texels)");
  const std::string_view scale_text = header.token();
  float scale = 0.0f;
  const char* scale_begin = scale_text.data();
  const char* scale_end = scale_begin + scale_text.size();
  if (scale_begin != scale_end && *scale_begin == '+') ++scale_begin;  // from_chars takes no '+'
  const std::from_chars_result parsed =
      std::from_chars(scale_begin, scale_end, scale, std::chars_format::general);
  if (scale_begin == scale_end || parsed.ec != std::errc() || parsed.ptr != scale_end)
    fail(name, "bad PFM scale " + quoted(scale_text) + " (expected a number, e.g. -1.0)");
  if (!std::isfinite(scale) || scale == 0.0f)
    fail(name,
         "the PFM scale must be a non-zero finite number (its sign gives the byte order), not " +
             quoted(scale_text));
  // Exactly one whitespace byte separates the scale from the pixels.
  std::size_t pos = header.position();
  if (pos >= size || !is_space(data[pos]))
    fail(name, "truncated: no whitespace after the PFM scale");
  ++pos;
  const std::uint64_t samples = texels * static_cast<std::uint64_t>(channels);
  const std::uint64_t needed = samples * 4;
  if (size - pos < needed)
    fail(name, "truncated: " + std::to_string(width) + "x" + std::to_string(height) + " needs " +
                   std::to_string(needed) + " bytes of pixels, the file has " +
                   std::to_string(size - pos));

  FloatImage image;
  image.width = static_cast<int>(width);
  image.height = static_cast<int>(height);
  image.channels = channels;
  image.pixels.resize(static_cast<std::size_t>(samples));
  const bool swap = (scale > 0.0f) == host_is_little_endian();  // file order differs from ours
  const float magnitude = std::fabs(scale);
  const std::size_t row_samples = std::size_t{width} * static_cast<std::size_t>(channels);
  for (std::uint32_t file_row = 0; file_row < height; ++file_row) {
    const unsigned char* in = data + pos + std::size_t{file_row} * row_samples * 4;
    float* out = image.pixels.data() + std::size_t{height - 1 - file_row} * row_samples;
    if (!swap) {
      std::memcpy(out, in, row_samples * 4);
    } else {
      for (std::size_t i = 0; i < row_samples; ++i) {
        const unsigned char bytes[4] = {in[4 * i + 3], in[4 * i + 2], in[4 * i + 1], in[4 * i]};
        std::memcpy(out + i, bytes, 4);
      }
    }
    if (magnitude != 1.0f)
      for (std::size_t i = 0; i < row_samples; ++i) out[i] *= magnitude;
  }
  return image;
}

}  // namespace prt::relight
