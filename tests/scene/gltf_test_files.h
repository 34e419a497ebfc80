// Hand-written glTF test files (independent of prt's writer): base64 data URIs and writing a
// JSON document as .gltf or .glb into the test output folder.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/test_data.h"

namespace gltf_test {

inline std::string base64(const std::vector<unsigned char>& bytes) {
  static const char* table = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const uint32_t n = (uint32_t(bytes[i]) << 16) |
                       (i + 1 < bytes.size() ? uint32_t(bytes[i + 1]) << 8 : 0) |
                       (i + 2 < bytes.size() ? uint32_t(bytes[i + 2]) : 0);
    out += table[(n >> 18) & 63];
    out += table[(n >> 12) & 63];
    out += i + 1 < bytes.size() ? table[(n >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? table[n & 63] : '=';
  }
  return out;
}

inline std::string write_gltf(const std::string& name, const nlohmann::json& doc) {
  const auto path = prt::test::output_path(name);
  std::ofstream(path) << doc.dump();
  return path.string();
}

// The same document as a .glb (JSON chunk only; the buffer stays a data URI).
inline std::string write_glb(const std::string& name, const nlohmann::json& doc) {
  std::string text = doc.dump();
  while (text.size() % 4) text += ' ';
  const uint32_t header[5] = {0x46546C67u, 2u, uint32_t(12 + 8 + text.size()),
                              uint32_t(text.size()), 0x4E4F534Au};
  const auto path = prt::test::output_path(name);
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(header), sizeof header);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  return path.string();
}

}  // namespace gltf_test
