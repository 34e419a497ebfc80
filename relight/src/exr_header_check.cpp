// relight/src/exr_header_check.cpp — OpenEXR header plausibility check (see
// relight/exr_header_check.h).
#include "relight/exr_header_check.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

#include "message_text.h"

namespace prt::relight {
namespace {

// A name for a message: printable ASCII only, at most 40 characters, quoted.
std::string quoted(std::string_view text) {
  return detail::quoted(text, 40);
}

std::int32_t read_i32(const unsigned char* p) {
  const std::uint32_t u = std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) |
                          (std::uint32_t{p[2]} << 16) | (std::uint32_t{p[3]} << 24);
  std::int32_t v;
  std::memcpy(&v, &u, 4);
  return v;
}

std::uint32_t read_u32(const unsigned char* p) {
  return std::uint32_t{p[0]} | (std::uint32_t{p[1]} << 8) | (std::uint32_t{p[2]} << 16) |
         (std::uint32_t{p[3]} << 24);
}

// What one header says about sizes (-1: not given).
struct Part {
  long long width = -1, height = -1;            // data window
  long long tile_width = -1, tile_height = -1;  // tiles
  long long bytes_per_texel = -1;               // channels
};

class Walker {
 public:
  Walker(const unsigned char* data, std::size_t size) : data_(data), size_(size) {}

  // Reads a NUL-terminated string of at most 255 characters at pos_; "" + problem_ on failure.
  bool read_name(std::string_view* name, const char* what) {
    const std::size_t limit = std::min(size_ - pos_, std::size_t{256});
    const void* nul = std::memchr(data_ + pos_, 0, limit);
    if (nul == nullptr) {
      problem_ = limit < 256 ? "OpenEXR header is truncated"
                             : std::string("OpenEXR header has an attribute ") + what +
                                   " longer than 255 bytes";
      return false;
    }
    const std::size_t length = static_cast<const unsigned char*>(nul) - (data_ + pos_);
    *name = std::string_view(reinterpret_cast<const char*>(data_ + pos_), length);
    pos_ += length + 1;
    return true;
  }

  // Walks one header; false with problem_ set when it is implausible.
  bool header(Part* part) {
    for (;;) {
      std::string_view name, type;
      if (!read_name(&name, "name")) return false;
      if (name.empty()) return true;  // end of this header
      if (!read_name(&type, "type")) return false;
      if (size_ - pos_ < 4) {
        problem_ = "OpenEXR header is truncated";
        return false;
      }
      const std::int32_t length = read_i32(data_ + pos_);
      pos_ += 4;
      const std::size_t left = size_ - pos_;
      if (length < 0 || static_cast<std::uint64_t>(length) > left) {
        problem_ = "OpenEXR header attribute " + quoted(name) + " claims " +
                   std::to_string(length) + " bytes, the file has " + std::to_string(left) +
                   " left";
        return false;
      }
      const unsigned char* value = data_ + pos_;
      const std::size_t n = static_cast<std::size_t>(length);
      if (!attribute(name, type, value, n, part)) return false;
      pos_ += n;
    }
  }

  bool attribute(std::string_view name, std::string_view type, const unsigned char* value,
                 std::size_t n, Part* part) {
    if (name == "dataWindow" && type == "box2i" && n == 16) {
      part->width = static_cast<long long>(read_i32(value + 8)) - read_i32(value) + 1;
      part->height = static_cast<long long>(read_i32(value + 12)) - read_i32(value + 4) + 1;
    } else if (name == "tiles" && type == "tiledesc" && n >= 8) {
      part->tile_width = read_u32(value);
      part->tile_height = read_u32(value + 4);
    } else if (name == "channels" && type == "chlist") {
      // name\0, int32 pixel type (0 uint, 1 half, 2 float), uchar pLinear, 3 reserved,
      // int32 xSampling, int32 ySampling; a NUL ends the list.
      long long bytes = 0;
      std::size_t at = 0;
      while (at < n && value[at] != 0) {
        const void* nul = std::memchr(value + at, 0, n - at);
        if (nul == nullptr) break;  // malformed: OpenEXR refuses it
        at = static_cast<std::size_t>(static_cast<const unsigned char*>(nul) - value) + 1;
        if (n - at < 16) break;
        bytes += read_i32(value + at) == 1 ? 2 : 4;
        at += 16;
      }
      part->bytes_per_texel = bytes;
    } else if (name == "chunkCount" && type == "int" && n == 4) {
      const std::int32_t chunks = read_i32(value);
      if (chunks < 0 || static_cast<std::uint64_t>(chunks) * 8 > size_) {
        problem_ = "OpenEXR header claims " + std::to_string(chunks) +
                   " chunks, more than the file can hold";
        return false;
      }
    } else if (type == "preview") {
      const std::uint64_t pixels =
          n >= 8 ? std::uint64_t{read_u32(value)} * read_u32(value + 4) : 0;
      if (n < 8 || pixels > (n - 8) / 4) {
        problem_ = "OpenEXR preview image " + quoted(name) + " is larger than its attribute";
        return false;
      }
    } else if (type == "stringvector") {
      std::size_t at = 0;
      while (at < n) {
        if (n - at < 4) break;
        const std::int32_t length = read_i32(value + at);
        at += 4;
        if (length < 0 || static_cast<std::size_t>(length) > n - at) {
          problem_ = "OpenEXR string vector " + quoted(name) + " holds a string of " +
                     std::to_string(length) + " bytes, larger than the attribute";
          return false;
        }
        at += static_cast<std::size_t>(length);
      }
    }
    return true;
  }

  std::size_t pos_ = 8;
  std::string problem_;

 private:
  const unsigned char* data_;
  std::size_t size_;
};

std::string size_problem(const Part& part, std::size_t max_texels) {
  const std::string size = std::to_string(part.width) + "x" + std::to_string(part.height);
  if (part.width > 0 && part.height > 0) {
    if (part.width > kMaxExrSide || part.height > kMaxExrSide)
      return "OpenEXR data window " + size + " has a side over " + std::to_string(kMaxExrSide);
    const long long texels = part.width * part.height;
    if (static_cast<unsigned long long>(texels) > max_texels)
      return size + " is too large (more than " + std::to_string(max_texels) + " texels)";
    if (part.bytes_per_texel > kMaxExrBytesPerTexel ||
        (part.bytes_per_texel > 0 &&
         static_cast<unsigned long long>(texels * part.bytes_per_texel) >
             16ull * static_cast<unsigned long long>(max_texels)))
      return "OpenEXR image " + size + " has too many channels (" +
             std::to_string(part.bytes_per_texel) + " bytes per texel)";
  }
  if (part.tile_width >= 0) {
    if (part.tile_width > kMaxExrSide || part.tile_height > kMaxExrSide)
      return "OpenEXR tiles " + std::to_string(part.tile_width) + "x" +
             std::to_string(part.tile_height) + " have a side over " + std::to_string(kMaxExrSide);
    const long long bytes =
        part.tile_width * part.tile_height * std::max(part.bytes_per_texel, 4ll);
    if (static_cast<unsigned long long>(bytes) > 16ull * max_texels)
      return "OpenEXR tiles " + std::to_string(part.tile_width) + "x" +
             std::to_string(part.tile_height) + " are too large";
  }
  return "";
}

}  // namespace

bool has_exr_magic(const unsigned char* data, std::size_t size) noexcept {
  return size >= 4 && data[0] == 0x76 && data[1] == 0x2f && data[2] == 0x31 && data[3] == 0x01;
}

std::string exr_header_problem(const unsigned char* data, std::size_t size,
                               std::size_t max_texels) {
  if (!has_exr_magic(data, size) || size < 8) return "";
  const bool multi_part = (data[5] & 0x10) != 0;  // version bit 12
  Walker walker(data, size);
  for (;;) {
    if (multi_part) {
      if (walker.pos_ >= size) return "OpenEXR header is truncated";
      if (data[walker.pos_] == 0) return "";  // an empty header ends the list
    }
    Part part;
    if (!walker.header(&part)) return walker.problem_;
    const std::string problem = size_problem(part, max_texels);
    if (!problem.empty()) return problem;
    if (!multi_part) return "";
  }
}

}  // namespace prt::relight
