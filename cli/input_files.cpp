// The files an input argument reads (input_files.h).
#include "input_files.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "relight/image_io.h"
#include "scene/scene_loader.h"

namespace prt::cli {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string text) {
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

std::string read_all(const std::string& path, std::size_t limit) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::string bytes;
  bytes.resize(limit);
  in.read(bytes.data(), static_cast<std::streamsize>(limit));
  bytes.resize(static_cast<std::size_t>(in.gcount()));
  return bytes;
}

// The JSON of a .gltf, or the first (JSON) chunk of a .glb.
std::string gltf_json(const std::string& path) {
  constexpr std::size_t kLimit = std::size_t{64} << 20;  // a glTF's JSON is far smaller
  if (lower(fs::path(path).extension().string()) != ".glb") return read_all(path, kLimit);
  const std::string head = read_all(path, 20);
  if (head.size() < 20 || head.compare(0, 4, "glTF") != 0) return {};
  uint32_t length = 0, type = 0;
  std::memcpy(&length, head.data() + 12, 4);
  std::memcpy(&type, head.data() + 16, 4);
  if (type != 0x4E4F534Au || length > kLimit) return {};  // "JSON"
  const std::string all = read_all(path, 20 + static_cast<std::size_t>(length));
  return all.size() < 20 ? std::string() : all.substr(20);
}

void add_gltf_references(const std::string& path, std::vector<std::string>* files) {
  const nlohmann::json json = nlohmann::json::parse(gltf_json(path), nullptr, false);
  if (!json.is_object()) return;
  const fs::path folder = fs::path(path).parent_path();
  for (const char* key : {"buffers", "images"}) {
    const auto list = json.find(key);
    if (list == json.end() || !list->is_array()) continue;
    for (const auto& item : *list) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.rfind("data:", 0) == 0 || uri.find("://") != std::string::npos) continue;
      files->push_back((folder / scene::decode_uri(uri)).string());
    }
  }
}

// The whitespace-separated tokens after the first on each line whose first token is in `keys`.
std::vector<std::vector<std::string>> lines_starting_with(const std::string& path,
                                                          const std::vector<std::string>& keys) {
  std::vector<std::vector<std::string>> found;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::istringstream tokens(line);
    std::string key;
    if (!(tokens >> key) || std::find(keys.begin(), keys.end(), lower(key)) == keys.end()) continue;
    std::vector<std::string> rest;
    for (std::string token; tokens >> token;) rest.push_back(token);
    if (!rest.empty()) found.push_back(rest);
  }
  return found;
}

void add_obj_references(const std::string& path, std::vector<std::string>* files) {
  const fs::path folder = fs::path(path).parent_path();
  const std::vector<std::string> map_keys = {"map_kd",   "map_ka", "map_ks", "map_ns", "map_d",
                                             "map_bump", "bump",   "disp",   "decal",  "norm",
                                             "refl",     "map_pr", "map_pm", "map_ke"};
  for (const auto& names : lines_starting_with(path, {"mtllib"}))
    for (const std::string& name : names) {
      const fs::path mtl = folder / name;
      files->push_back(mtl.string());
      for (const auto& map : lines_starting_with(mtl.string(), map_keys))
        files->push_back((mtl.parent_path() / map.back()).string());
    }
}

}  // namespace

std::vector<std::string> scene_files(const std::string& scene_path) {
  std::vector<std::string> files = {scene_path};
  const std::string extension = lower(fs::path(scene_path).extension().string());
  try {
    if (extension == ".gltf" || extension == ".glb") add_gltf_references(scene_path, &files);
    if (extension == ".obj") add_obj_references(scene_path, &files);
  } catch (const std::exception&) {
    // Best effort (see the header): the loader reports what is wrong with the file.
  }
  return files;
}

std::vector<std::string> environment_files(const std::string& environment_path) {
  const std::size_t at = environment_path.find("%s");
  if (at == std::string::npos) return {environment_path};
  std::vector<std::string> files;
  for (const char* suffix : relight::kFaceSuffixes)
    files.push_back(environment_path.substr(0, at) + suffix + environment_path.substr(at + 2));
  return files;
}

}  // namespace prt::cli
