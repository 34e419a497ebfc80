#include "radiosity/materials.h"

#include <cmath>
#include <cstdio>
#include <set>
#include <stdexcept>

namespace prt::radiosity {

std::string describe_colour(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return buf;
}

namespace {

std::string material_list(const scene::Scene& scene) {
  std::set<std::string> names;
  for (const auto& p : scene.primitives) names.insert(p.material.empty() ? "<none>" : p.material);
  std::string out;
  for (const std::string& name : names) out += (out.empty() ? "" : ", ") + name;
  return out;
}

template <typename Apply>
void apply(scene::Scene& scene, const std::vector<MaterialValue>& values, const char* option,
           Apply&& set) {
  for (const MaterialValue& value : values) {
    bool found = false;
    for (scene::ScenePrimitive& p : scene.primitives)
      if (p.material == value.material) found = true, set(p, value.rgb);
    if (!found)
      throw std::invalid_argument(std::string(option) + " " + value.material +
                                  ": no primitive of " + scene.source_path +
                                  " uses this material (materials: " + material_list(scene) + ")");
  }
}

}  // namespace

MaterialValue parse_material_value(const std::string& option, const std::string& text) {
  const std::size_t eq = text.rfind('=');
  const std::string bad = option + " " + text + ": ";
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw std::invalid_argument(bad + "expected MATERIAL=r,g,b");
  MaterialValue out;
  out.material = text.substr(0, eq);
  std::vector<double> numbers;
  std::size_t at = eq + 1;
  while (at <= text.size()) {
    const std::size_t comma = std::min(text.find(',', at), text.size());
    const std::string item = text.substr(at, comma - at);
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || end != item.c_str() + item.size())
      throw std::invalid_argument(bad + "'" + item + "' is not a number");
    numbers.push_back(v);
    at = comma + 1;
  }
  if (numbers.size() == 1) numbers.assign(3, numbers[0]);
  if (numbers.size() != 3) throw std::invalid_argument(bad + "expected 1 or 3 numbers");
  for (int c = 0; c < 3; ++c) {
    if (!std::isfinite(numbers[c]) || numbers[c] < 0.0 || numbers[c] > 3.0e38)
      throw std::invalid_argument(bad + "every component must be finite and non-negative");
    out.rgb[c] = static_cast<float>(numbers[c]);
  }
  return out;
}

void apply_emission(scene::Scene& scene, const std::vector<MaterialValue>& values) {
  apply(scene, values, "--emission",
        [](scene::ScenePrimitive& p, const glm::vec3& rgb) { p.emission = rgb; });
}

void apply_albedo(scene::Scene& scene, const std::vector<MaterialValue>& values) {
  apply(scene, values, "--albedo", [&](scene::ScenePrimitive& p, const glm::vec3& rgb) {
    p.albedo = rgb;
    for (uint32_t v = 0; v < p.vertex_count; ++v) scene.albedo[p.first_vertex + v] = rgb;
  });
}

void check_materials(const scene::Scene& scene) {
  for (const scene::ScenePrimitive& p : scene.primitives) {
    const std::string where = scene.source_path + ": material " +
                              (p.material.empty() ? "<none>" : p.material) + " of " + p.name + ": ";
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p.emission[c]) || p.emission[c] < 0.f)
        throw std::invalid_argument(where + "emission " + describe_colour(p.emission) +
                                    " must be finite and non-negative");
      if (!std::isfinite(p.albedo[c]) || p.albedo[c] < 0.f || p.albedo[c] > 1.f)
        throw std::invalid_argument(where + "albedo " + describe_colour(p.albedo) +
                                    " must be in [0, 1]");
    }
    for (uint32_t v = 0; v < p.vertex_count && p.first_vertex + v < scene.albedo.size(); ++v) {
      const glm::vec3 a = scene.albedo[p.first_vertex + v];
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(a[c]) || a[c] < 0.f || a[c] > 1.f)
          throw std::invalid_argument(where + "vertex albedo " + describe_colour(a) +
                                      " must be in [0, 1]");
    }
  }
}

bool has_unit_albedo(const scene::Scene& scene) {
  for (const glm::vec3& a : scene.albedo)
    if (a.x >= 1.f || a.y >= 1.f || a.z >= 1.f) return true;
  return false;
}

}  // namespace prt::radiosity
