// scene/glb_writer.h — writing a Scene as binary glTF 2.0 (.glb) that any glTF viewer opens.
//
// Frame: glTF's (right-handed, +Y up, cameras look down -Z); positions are written as they are
// (world space, identity node transforms), so load_scene(write_glb(s)) gives s back.
// Layout: one mesh (with one node) per scene primitive, named after it, with POSITION (with
// min/max), NORMAL, u32 indices, and a material (named after the primitive's material, else
// the primitive) whose baseColorFactor is the primitive's albedo
// (alpha 1, metallic 0, roughness 1: a diffuse surface) — or, for a primitive whose BRDF is
// GGX with Schlick's Fresnel, the metallic-roughness material (+ KHR_materials_specular,
// KHR_materials_anisotropy) that the loader reads back as that BRDF (other models are written
// as their albedo only). A primitive's emission becomes the material's emissiveFactor (divided
// by its largest channel when that exceeds 1, which then goes to KHR_materials_emissive_strength,
// listed in extensionsUsed), as the loader reads it back. Primitives whose Scene::tangents
// are all valid (unit xyz, w = ±1) get TANGENT (float VEC4). With vertex_colors (one linear RGB
// float triple per scene vertex, e.g. baked exit radiance) each primitive also gets COLOR_0
// (float VEC3, linear as glTF requires) and the material becomes unlit (KHR_materials_unlit,
// listed in extensionsUsed) with a white baseColorFactor: a viewer then shows COLOR_0 as it is,
// instead of lighting the bake again and multiplying by the albedo a second time. Such a file
// is for display: loading it back gives an albedo of 1 (which the baker refuses); bake the
// original scene. Each SceneCamera becomes a perspective camera on its own node, rotated so
// that its -Z looks at the target with +Y as close to `up` as possible.
// Application-specific data (GlbCustomData, optional): per-vertex float attributes whose names
// begin with an underscore, as glTF 2.0 requires of application-specific attributes (§3.7.2.1),
// written on every primitive (its range of the values), and JSON objects written as every
// mesh's `extras` and as the scene's `extras` (glTF's place for application data).
// The file is written atomically: PATH.tmp-<pid> then rename; nothing is left on failure.
// Errors throw SceneError("PATH: problem").
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

struct GlbCustomAttribute {
  std::string name;           // "_NAME": must begin with '_'
  int components = 4;         // 1 (SCALAR) .. 4 (VEC4), float
  std::vector<float> values;  // components · vertex_count, scene vertex order
};

struct GlbCustomData {
  std::vector<GlbCustomAttribute> attributes;
  std::string mesh_extras_json;   // a JSON object, or empty
  std::string scene_extras_json;  // a JSON object, or empty
};

// Throws SceneError("PATH: problem") also for custom data that breaks the rules above (a name
// without '_', a size that does not match, JSON that is not an object).
void write_glb(const std::string& path, const Scene& scene,
               const std::vector<glm::vec3>* vertex_colors = nullptr,
               const GlbCustomData* custom = nullptr);

}  // namespace prt::scene
