// The bake benchmark field (see scene/field_scene.h).
#include "scene/field_scene.h"

#include <optional>
#include <string>
#include <utility>

#include "scene/procedural_mesh.h"

namespace prt::scene {
namespace {

// glTF's metallic-roughness BRDF (procedural_mesh.h's gltf_brdf) with α = roughness².
brdf::Material metallic_roughness(glm::vec3 base, double metallic, double roughness) {
  return gltf_brdf(brdf::Rgb{base.x, base.y, base.z}, metallic, roughness * roughness,
                   roughness * roughness);
}

struct Look {
  std::string material;
  glm::vec3 albedo;
  std::optional<brdf::Material> brdf;
};

Look look(bool glossy, const std::string& role) {
  const glm::vec3 grey(0.7f), red(0.75f, 0.15f, 0.1f), gold(0.95f, 0.74f, 0.33f);
  const glm::vec3 ground(0.5f), steel(0.9f);
  if (!glossy) {
    if (role == "ground") return {"ground", ground, std::nullopt};
    if (role == "red") return {"red", red, std::nullopt};
    return {"grey", grey, std::nullopt};
  }
  if (role == "ground") return {"ground", ground, metallic_roughness(ground, 0.0, 0.7)};
  if (role == "red") return {"glossy_red", red, metallic_roughness(red, 0.0, 0.25)};
  if (role == "metal") return {"metal", steel, metallic_roughness(steel, 1.0, 0.35)};
  if (role == "gold") return {"rough_gold", gold, metallic_roughness(gold, 1.0, 0.5)};
  return {"glossy_grey", grey, metallic_roughness(grey, 0.0, 0.3)};
}

LayoutPart field_part(bool glossy, std::string name, const std::string& role) {
  const Look l = look(glossy, role);
  LayoutPart p;
  p.name = std::move(name);
  p.material = l.material;
  p.albedo = l.albedo;
  p.brdf = l.brdf;
  return p;
}

}  // namespace

ShapeLayout make_field_layout(bool glossy) {
  ShapeLayout layout;
  layout.source_path = glossy ? "procedural:field-glossy" : "procedural:field";
  LayoutPart ground = field_part(glossy, "ground", "ground");
  // facing +Y: cross(+Z, +X)
  ground.panels.push_back(make_panel({-12.0, 0.0, -12.0}, {0, 0, 1}, 24.0, {1, 0, 0}, 24.0));
  layout.parts.push_back(std::move(ground));
  const auto sphere = [&](const char* name, const char* role, glm::dvec3 c, double r) {
    LayoutPart p = field_part(glossy, name, role);
    p.spheres.push_back({c, r});
    layout.parts.push_back(std::move(p));
  };
  sphere("sphere_large", "metal", {-3.0, 1.0, -1.0}, 1.0);
  sphere("sphere_red", "red", {0.5, 0.8, 1.5}, 0.8);
  sphere("sphere_medium", "grey", {3.5, 0.6, -2.0}, 0.6);
  sphere("sphere_small", "grey", {-1.2, 0.45, 2.6}, 0.45);
  const auto box = [&](const char* name, const char* role, glm::dvec3 lo, glm::dvec3 hi) {
    LayoutPart p = field_part(glossy, name, role);
    p.boxes.push_back({lo, hi, false});
    layout.parts.push_back(std::move(p));
  };
  box("box_wide", "gold", {-1.5, 0.0, -4.0}, {0.5, 1.6, -2.4});
  box("box_low", "gold", {2.0, 0.0, 1.0}, {3.2, 0.9, 2.2});
  box("box_red", "red", {-5.0, 0.0, 1.5}, {-4.0, 2.5, 2.5});

  SceneCamera camera;
  camera.name = "camera";
  camera.eye = {0.f, 3.5f, 11.f};
  camera.target = {0.f, 0.8f, 0.f};
  camera.yfov_radians = 0.75f;
  layout.cameras.push_back(camera);
  return layout;
}

}  // namespace prt::scene
