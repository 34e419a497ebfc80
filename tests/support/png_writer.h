// tests/support/png_writer.h — a minimal PNG encoder for tests, written from the PNG
// specification (ISO/IEC 15948) and RFC 1950/1951 independently of the code under test: 8-bit
// grey (1 channel), RGB (3) or RGBA (4), no interlace, filter 0 on every row, and the zlib stream
// made of "stored" (uncompressed) deflate blocks. Textures written with it test the decoding
// path (OpenImageIO through the plugin) against values the test chose.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

namespace prt::test {

namespace png_detail {

inline uint32_t crc32(const unsigned char* data, std::size_t size, uint32_t crc = 0) {
  crc = ~crc;
  for (std::size_t i = 0; i < size; ++i) {
    crc ^= data[i];
    for (int k = 0; k < 8; ++k) crc = (crc >> 1) ^ (0xedb88320u & (0u - (crc & 1u)));
  }
  return ~crc;
}

inline void put32(std::vector<unsigned char>& out, uint32_t x) {
  for (int shift = 24; shift >= 0; shift -= 8)
    out.push_back(static_cast<unsigned char>(x >> shift));
}

inline void chunk(std::vector<unsigned char>& out, const char type[4],
                  const std::vector<unsigned char>& data) {
  put32(out, static_cast<uint32_t>(data.size()));
  std::vector<unsigned char> body(type, type + 4);
  body.insert(body.end(), data.begin(), data.end());
  out.insert(out.end(), body.begin(), body.end());
  put32(out, crc32(body.data(), body.size()));
}

}  // namespace png_detail

// The bytes of a PNG holding `samples` (width·height·channels bytes, row 0 at the top).
inline std::vector<unsigned char> encode_png(int width, int height, int channels,
                                             const std::vector<unsigned char>& samples) {
  using namespace png_detail;
  const unsigned char color_type = channels == 1 ? 0 : channels == 3 ? 2 : 6;
  std::vector<unsigned char> raw;  // filter byte 0, then the row
  const std::size_t row_bytes =
      static_cast<std::size_t>(width) * static_cast<std::size_t>(channels);
  for (int y = 0; y < height; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), samples.begin() + static_cast<std::ptrdiff_t>(y * row_bytes),
               samples.begin() + static_cast<std::ptrdiff_t>((y + 1) * row_bytes));
  }
  std::vector<unsigned char> z = {0x78, 0x01};  // deflate, 32K window, no dictionary
  for (std::size_t at = 0; at < raw.size() || at == 0; at += 65535) {
    const std::size_t n = std::min<std::size_t>(65535, raw.size() - at);
    z.push_back(at + n >= raw.size() ? 1 : 0);  // BFINAL, BTYPE = 00 (stored)
    z.push_back(static_cast<unsigned char>(n & 0xff));
    z.push_back(static_cast<unsigned char>(n >> 8));
    z.push_back(static_cast<unsigned char>(~n & 0xff));
    z.push_back(static_cast<unsigned char>((~n >> 8) & 0xff));
    z.insert(z.end(), raw.begin() + static_cast<std::ptrdiff_t>(at),
             raw.begin() + static_cast<std::ptrdiff_t>(at + n));
    if (raw.empty()) break;
  }
  uint32_t a = 1, b = 0;  // Adler-32 of the uncompressed data
  for (unsigned char c : raw) a = (a + c) % 65521, b = (b + a) % 65521;
  put32(z, (b << 16) | a);

  std::vector<unsigned char> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  std::vector<unsigned char> header;
  put32(header, static_cast<uint32_t>(width));
  put32(header, static_cast<uint32_t>(height));
  header.insert(header.end(), {8, color_type, 0, 0, 0});
  chunk(png, "IHDR", header);
  chunk(png, "IDAT", z);
  chunk(png, "IEND", {});
  return png;
}

inline void write_png(const std::string& path, int width, int height, int channels,
                      const std::vector<unsigned char>& samples) {
  const std::vector<unsigned char> png = encode_png(width, height, channels, samples);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
}

}  // namespace prt::test
