// The translucent scenes (see scene/translucent_scene.h).
#include "scene/translucent_scene.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "scene/mesh_normals.h"
#include "scene/procedural_mesh.h"

namespace prt::scene {
namespace {

int segments_for(float length, float cell) {
  return std::max(1, static_cast<int>(std::lround(length / cell)));
}

SceneCamera camera_at(glm::vec3 eye, glm::vec3 target, float yfov) {
  SceneCamera camera;
  camera.name = "camera";
  camera.eye = eye;
  camera.target = target;
  camera.yfov_radians = yfov;
  return camera;
}

// Merges every primitive of `parts` into one primitive named `name`.
Scene as_one_primitive(Scene parts, const std::string& name, glm::vec3 albedo) {
  ScenePrimitive p;
  p.name = name;
  p.material = name;
  p.albedo = albedo;
  p.vertex_count = static_cast<uint32_t>(parts.positions.size());
  p.triangle_count = static_cast<uint32_t>(parts.triangles.size());
  parts.primitives = {p};
  return parts;
}

}  // namespace

Scene make_closed_slab(glm::vec3 lo, glm::vec3 hi, float cell, glm::vec3 albedo, std::string name) {
  const glm::vec3 d = hi - lo;
  const int nx = segments_for(d.x, cell), ny = segments_for(d.y, cell),
            nz = segments_for(d.z, cell);
  const glm::vec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  Scene s;
  // make_quad's front is cross(edge_u, edge_v): every face below points out of the box.
  append_scene(s, make_quad({hi.x, lo.y, lo.z}, ey, ez, ny, nz, albedo, name));  // +X
  append_scene(s, make_quad(lo, ez, ey, nz, ny, albedo, name));                  // −X
  append_scene(s, make_quad({lo.x, hi.y, lo.z}, ez, ex, nz, nx, albedo, name));  // +Y
  append_scene(s, make_quad(lo, ex, ez, nx, nz, albedo, name));                  // −Y
  append_scene(s, make_quad({lo.x, lo.y, hi.z}, ex, ey, nx, ny, albedo, name));  // +Z
  append_scene(s, make_quad(lo, ey, ex, ny, nx, albedo, name));                  // −Z
  s.texcoords.clear();
  return as_one_primitive(std::move(s), name, albedo);
}

Scene make_fin(const FinShape& f, int rings, int segments, glm::vec3 albedo) {
  Scene s = make_uv_sphere({0, 0, 0}, 1.f, rings, segments, false, albedo, "fin");
  for (glm::vec3& p : s.positions) {
    const double x = double(f.semi_width) * p.x, y = double(f.semi_height) * p.y;
    const double z = double(f.half_thickness) * p.z + double(f.bend) * x * x;
    p = glm::vec3(glm::dvec3(x, y, z) + glm::dvec3(f.centre));
  }
  compute_vertex_normals(s, false);
  s.computed_normal_vertices = 0;  // built, not repaired
  s.primitives[0].material = "fin";
  return s;
}

Scene make_translucent_scene() {
  const glm::vec3 grey(0.5f), white(0.8f);
  Scene scene;
  append_scene(scene, make_quad({-80, 0, -50}, {0, 0, 100}, {160, 0, 0}, 25, 40, grey, "ground"));
  scene.primitives.back().material = "ground";
  append_scene(scene, make_closed_slab({-70, 0, -20}, {-20, 10, 20}, kSlabCell, white, "slab"));
  append_scene(scene, make_uv_sphere({0, 12, 0}, 12.f, 48, 96, false, white, "sphere"));
  scene.primitives.back().material = "sphere";
  append_scene(scene, make_fin(FinShape{}, 64, 128, white));
  scene.texcoords.clear();
  scene.cameras.push_back(camera_at({0, 45, 130}, {0, 12, 0}, 0.6f));
  scene.source_path = "procedural:translucent";
  return scene;
}

Scene make_translucent_slab() {
  Scene scene = make_closed_slab({-50, -20, -50}, {50, 0, 50}, kSlabCell, glm::vec3(0.8f), "slab");
  scene.cameras.push_back(camera_at({0, 90, 140}, {0, -10, 0}, 0.7f));
  scene.source_path = "procedural:translucent-slab";
  return scene;
}

Scene make_translucent_sphere() {
  Scene scene = make_uv_sphere({0, 0, 0}, 10.f, 64, 128, false, glm::vec3(0.8f), "sphere");
  scene.primitives.back().material = "sphere";
  scene.texcoords.clear();
  scene.cameras.push_back(camera_at({0, 0, 45}, {0, 0, 0}, 0.6f));
  scene.source_path = "procedural:translucent-sphere";
  return scene;
}

}  // namespace prt::scene
