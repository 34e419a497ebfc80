// scene/src/output_path.cpp — see scene/output_path.h.
#include "scene/output_path.h"

#include <cctype>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace prt::scene {

void check_output_path(const std::string& path, const std::string& scene_path,
                       const std::vector<std::string>& extensions) {
  if (path.empty()) return;
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  bool known = extensions.empty();
  for (const std::string& e : extensions) known = known || ext == e;
  if (!known) throw std::runtime_error(path + ": unsupported output type '" + ext + "'");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(path + ": directory " + parent.string() + " does not exist");
  std::error_code ec;
  if (std::filesystem::equivalent(path, scene_path, ec))
    throw std::runtime_error(path + ": an output may not overwrite the input scene");
}

}  // namespace prt::scene
