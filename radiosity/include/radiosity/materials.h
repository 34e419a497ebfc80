// radiosity/materials.h — the emitters and albedos of a radiosity scene: the checks that make the
// radiosity equation solvable (the command line's per-material values are
// scene/material_assignment.h's apply_emission and apply_albedo).
//
// Emission is the exit radiance of a Lambertian emitter's front face, linear RGB (see
// scene::ScenePrimitive::emission); emitters also reflect with their own albedo.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::radiosity {

// Throws std::invalid_argument "PATH: material M: problem" for a negative, NaN or infinite
// emission, or an albedo outside [0, 1] (per-vertex albedo included).
void check_materials(const scene::Scene& scene);

// "(r, g, b)" with %g components: how the radiosity errors name a colour.
std::string describe_colour(const glm::vec3& v);

// True when some patch has an albedo component ≥ 1 (a closed scene then cannot be solved).
bool has_unit_albedo(const scene::Scene& scene);

}  // namespace prt::radiosity
