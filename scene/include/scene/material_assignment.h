// scene/material_assignment.h — "NAME=VALUE" assignments to a scene's materials from the command
// line: the one syntax and the one name matching of every such option:
//   --material NAME=MODEL[:KEY=VALUE,...]   a BRDF (scene/material_override.h)
//   --emission NAME=r,g,b, --albedo NAME=r,g,b   a colour (prt radiosity, prt bake --albedo,
//                                                prt report --radiosity)
//   --emitter NAME=r,g,b                    a colour for an emitter of a responses file
// NAME: a material name (glTF material name, OBJ `newmtl`), else a primitive name ("mesh/0", an
// OBJ shape); `*` is every primitive (matched_primitives). NAME ends at the first '=' for a BRDF
// (its parameters hold '=') and at the last '=' for a colour (which holds none, so a material
// name may contain one). A colour is "r,g,b" or one grey value "v"; every component finite,
// non-negative and at most 3e38 (a float).
// Errors throw std::invalid_argument with one line "OPTION TEXT: problem", OPTION as given
// (e.g. "--emission").
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

struct MaterialAssignment {
  std::string name;   // material or primitive name, or "*"
  std::string value;  // the text after NAME's '='
  std::string text;   // as given, for messages
  std::string option = "--material";
};

// What an assignment's VALUE is: where NAME ends and what a malformed one is told to look like.
enum class AssignedValue {
  // MODEL[:KEY=VALUE,...]: NAME ends at the first '='; "expected NAME=MODEL[:KEY=VALUE,...]".
  Brdf,
  // r,g,b or v: NAME ends at the last '=', VALUE not empty; "expected MATERIAL=r,g,b".
  Colour,
};

// Splits TEXT into NAME and VALUE. Throws "OPTION TEXT: expected …" without '=', with an empty
// NAME or (a colour) an empty VALUE.
MaterialAssignment parse_material_assignment(const std::string& option, const std::string& text,
                                             AssignedValue kind);

// Indices of the primitives `a` applies to: those whose material is a.name (every one for
// "*"), else those whose primitive name is a.name. Throws std::invalid_argument
// "OPTION TEXT: no material or primitive named 'NAME' in PATH (materials: 'a', 'b')" when none is.
std::vector<std::size_t> matched_primitives(const Scene& scene, const MaterialAssignment& a);

struct MaterialColour : MaterialAssignment {
  glm::vec3 rgb{0.f};
};

// "NAME=r,g,b" or "NAME=v". Throws "OPTION TEXT: problem" for a malformed assignment ("expected
// MATERIAL=r,g,b"), a component that is not a number ("'x' is not a number"), a count other than
// 1 or 3, or a negative, NaN, infinite or out-of-float-range component.
MaterialColour parse_material_colour(const std::string& option, const std::string& text);

// Sets the emission (exit radiance, ScenePrimitive::emission) of every primitive each colour
// matches, in order (a later one wins). Throws as matched_primitives.
void apply_emission(Scene& scene, const std::vector<MaterialColour>& colours);

// Sets the albedo of every primitive each colour matches, the primitive's and its vertices'
// (textures are kept), in order. Throws as matched_primitives.
void apply_albedo(Scene& scene, const std::vector<MaterialColour>& colours);

}  // namespace prt::scene
