#include "gltf_extensions.h"

#include <algorithm>
#include <cstdio>

#include "scene_file_errors.h"

namespace prt::scene::detail {
namespace {

bool contains(const std::vector<std::string>& list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

}  // namespace

const std::vector<std::string> kIgnorableExtensions = {
    "KHR_lights_punctual",
    "KHR_materials_anisotropy",
    "KHR_materials_clearcoat",
    "KHR_materials_diffuse_transmission",
    "KHR_materials_dispersion",
    "KHR_materials_emissive_strength",
    "KHR_materials_ior",
    "KHR_materials_iridescence",
    "KHR_materials_sheen",
    "KHR_materials_specular",
    "KHR_materials_transmission",
    "KHR_materials_unlit",
    "KHR_materials_variants",
    "KHR_materials_volume",
    "KHR_xmp_json_ld",
};

void check_required_extensions(const std::string& path, const std::vector<std::string>& required) {
  std::vector<std::string> unreadable;
  for (const std::string& name : required)
    if (!contains(kIgnorableExtensions, name) && !contains(unreadable, name))
      unreadable.push_back(name);
  if (unreadable.empty()) return;
  if (unreadable.size() == 1)
    fail(path, "requires glTF extension " + unreadable[0] + ", which prt cannot read");
  fail(path, "requires glTF extensions " + join(unreadable) + ", which prt cannot read");
}

void note_optional_extensions(const std::string& path, const std::vector<std::string>& used,
                              const std::vector<std::string>& required) {
  std::vector<std::string> ignored;
  for (const std::string& name : used)
    if (!contains(kIgnorableExtensions, name) && !contains(required, name) &&
        !contains(ignored, name))
      ignored.push_back(name);
  if (ignored.empty()) return;
  std::fprintf(stderr,
               "%s: note: optional glTF extension%s %s not read (the file's fallback data is "
               "used)\n",
               path.c_str(), ignored.size() == 1 ? "" : "s", join(ignored).c_str());
}

}  // namespace prt::scene::detail
