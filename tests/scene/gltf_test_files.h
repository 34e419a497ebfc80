// Hand-written glTF test files (independent of prt's writer): base64 data URIs and writing a
// JSON document as .gltf or .glb into the test output folder.
#pragma once

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/base64.h"
#include "support/test_data.h"

namespace gltf_test {

using prt::test::base64;

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
