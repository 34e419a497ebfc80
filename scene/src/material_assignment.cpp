// scene/src/material_assignment.cpp — see scene/material_assignment.h.
#include "scene/material_assignment.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <stdexcept>

namespace prt::scene {

MaterialAssignment parse_material_assignment(const std::string& option, const std::string& text,
                                             AssignedValue kind) {
  const bool colour = kind == AssignedValue::Colour;
  const std::size_t eq = colour ? text.rfind('=') : text.find('=');
  if (eq == std::string::npos || eq == 0 || (colour && eq + 1 == text.size()))
    throw std::invalid_argument(option + " " + text + ": expected " +
                                (colour ? "MATERIAL=r,g,b" : "NAME=MODEL[:KEY=VALUE,...]"));
  MaterialAssignment a;
  a.name = text.substr(0, eq);
  a.value = text.substr(eq + 1);
  a.text = text;
  a.option = option;
  return a;
}

std::vector<std::size_t> matched_primitives(const Scene& scene, const MaterialAssignment& a) {
  std::vector<std::size_t> matched;
  for (std::size_t i = 0; i < scene.primitives.size(); ++i)
    if (a.name == "*" || scene.primitives[i].material == a.name) matched.push_back(i);
  if (matched.empty())
    for (std::size_t i = 0; i < scene.primitives.size(); ++i)
      if (scene.primitives[i].name == a.name) matched.push_back(i);
  if (matched.empty()) {
    std::string names;
    for (const ScenePrimitive& p : scene.primitives)
      if (!p.material.empty() && names.find("'" + p.material + "'") == std::string::npos)
        names += (names.empty() ? "'" : ", '") + p.material + "'";
    throw std::invalid_argument(a.option + " " + a.text + ": no material or primitive named '" +
                                a.name + "' in " + scene.source_path +
                                " (materials: " + (names.empty() ? "none" : names) + ")");
  }
  return matched;
}

MaterialColour parse_material_colour(const std::string& option, const std::string& text) {
  MaterialColour out;
  static_cast<MaterialAssignment&>(out) =
      parse_material_assignment(option, text, AssignedValue::Colour);
  const std::string bad = option + " " + text + ": ";
  std::vector<double> numbers;
  const std::string& value = out.value;
  std::size_t at = 0;
  while (at <= value.size()) {
    const std::size_t comma = std::min(value.find(',', at), value.size());
    const std::string item = value.substr(at, comma - at);
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

void apply_emission(Scene& scene, const std::vector<MaterialColour>& colours) {
  for (const MaterialColour& c : colours)
    for (std::size_t i : matched_primitives(scene, c)) scene.primitives[i].emission = c.rgb;
}

void apply_albedo(Scene& scene, const std::vector<MaterialColour>& colours) {
  for (const MaterialColour& c : colours)
    for (std::size_t i : matched_primitives(scene, c)) {
      ScenePrimitive& p = scene.primitives[i];
      p.albedo = c.rgb;
      for (uint32_t v = 0; v < p.vertex_count; ++v) scene.albedo[p.first_vertex + v] = c.rgb;
    }
}

}  // namespace prt::scene
