// radiosity/materials.h — the emitters and albedos of a radiosity scene: per-material overrides
// from the command line and the checks that make the radiosity equation solvable.
//
// Emission is the exit radiance of a Lambertian emitter's front face, linear RGB (see
// scene::ScenePrimitive::emission); emitters also reflect with their own albedo.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::radiosity {

struct MaterialValue {
  std::string material;
  glm::vec3 rgb{0.f};
};

// Parses "MATERIAL=r,g,b" or "MATERIAL=v" (grey). Throws std::invalid_argument with one line
// "OPTION TEXT: problem" for a malformed value or a negative, NaN or infinite component.
MaterialValue parse_material_value(const std::string& option, const std::string& text);

// Sets the emission (or albedo: primitive and per-vertex) of every primitive whose material is
// named `material`. Throws std::invalid_argument "OPTION NAME: no primitive of PATH uses this
// material (materials: a, b, …)" when none does.
void apply_emission(scene::Scene& scene, const std::vector<MaterialValue>& values);
void apply_albedo(scene::Scene& scene, const std::vector<MaterialValue>& values);

// Throws std::invalid_argument "PATH: material M: problem" for a negative, NaN or infinite
// emission, or an albedo outside [0, 1] (per-vertex albedo included).
void check_materials(const scene::Scene& scene);

// "(r, g, b)" with %g components: how the radiosity errors name a colour.
std::string describe_colour(const glm::vec3& v);

// True when some patch has an albedo component ≥ 1 (a closed scene then cannot be solved).
bool has_unit_albedo(const scene::Scene& scene);

}  // namespace prt::radiosity
