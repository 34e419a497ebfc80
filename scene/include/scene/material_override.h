// scene/material_override.h — replacing a scene material's BRDF from the command line.
//
// Syntax of one override (the value of `--material`, repeatable):
//   NAME=MODEL[:KEY=VALUE,KEY=VALUE,...]      NAME=merl:FILE
// NAME and its matching are those of every material assignment (scene/material_assignment.h:
// a material name, else a primitive name; `*` is every primitive). A colour is one grey value
// or r/g/b ("0.9/0.6/0.5"). MODEL and its keys (prt/brdf/*.h for the models and their ranges):
//   lambert      kd (or albedo): replaces the diffuse albedo (textures dropped) and removes
//                any BRDF; without kd only the BRDF is removed.
//   blinn-phong  kd (k_L, default 0), ks (k_G, required), s (exponent, required).
//   ward         rho_d (default 0), rho_s (required), ax, ay (or alpha for both; ay defaults
//                to ax), form = normalized (default) | duer | original.
//   ggx, beckmann  f0 (Schlick reflectance at normal incidence, default 0.04), kd (Lambert
//                layer, default 0), ax, ay, alpha, or roughness r (α = r², the glTF
//                convention), fresnel = schlick (default) | dielectric | none, eta (dielectric,
//                default 1.5).
//   gltf         base (baseColor, required), metallic (default 0), roughness (required, α = r²):
//                glTF 2.0's BRDF as its Appendix B mixes it (prt/brdf/gltf_pbr.h), what the
//                glTF loader makes.
//   gltf-additive  the same keys as a GGX lobe with F0 = mix(0.04, base, metallic) plus an added
//                Lambert layer base · (1 − metallic): prt's layering before it followed the spec.
//   merl         FILE: a MERL binary file ([40] of docs/REFERENCES.md).
// Every override is checked when parsed by building its BRDF (prt::brdf::make_brdf), so a
// roughness of 0 or NaN, a negative exponent, reflectances outside [0, 1] or a truncated MERL
// file are refused there, and by the white-furnace check (prt/brdf/energy_check.h): "material
// 'NAME' DESCRIPTION reflects 1.23x the light arriving at 75°: directional albedo must not
// exceed 1". Errors throw std::invalid_argument with one line
// "OPTION TEXT: problem" (OPTION as given, e.g. "--material").
// Applying: a non-Lambert override sets ScenePrimitive::brdf (and anisotropy_rotation 0, and
// drops the per-vertex variants and tangent rotations of textured parameters) and leaves the albedo
// of the diffuse path unchanged. Anisotropic overrides use the scene's tangent frames
// (scene/tangent_frames.h): the file's TANGENT, else the texture coordinates the loader kept (those
// of textured primitives and of glTF anisotropic materials), else the frame from the normal.
#pragma once

#include <string>
#include <vector>

#include "prt/brdf/material.h"
#include "scene/material_assignment.h"
#include "scene/scene.h"

namespace prt::scene {

struct MaterialOverride : MaterialAssignment {
  brdf::Material material;  // checked: make_brdf accepts it
  bool set_albedo = false;  // lambert with kd: the albedo to give
};

MaterialOverride parse_material_override(const std::string& text,
                                         const std::string& option = "--material");

// Applies the overrides in order (a later one wins). Throws std::invalid_argument
// "OPTION TEXT: no material or primitive named 'NAME' in PATH (materials: ...)" when an
// override matches nothing.
void apply_material_overrides(Scene& scene, const std::vector<MaterialOverride>& overrides);

// One line per primitive: "NAME (material M): describe(brdf)" or "lambert(albedo)".
std::vector<std::string> describe_materials(const Scene& scene);

}  // namespace prt::scene
