// Analytic test meshes and the demo scene (see scene/procedural_mesh.h).
#include "scene/procedural_mesh.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "scene/tangent_frames.h"
#include "sh/constants.h"

namespace prt::scene {
namespace {

using sh::kPi;

// Opens a primitive at the current end of the scene.
void begin_primitive(Scene& scene, std::string name, glm::vec3 albedo) {
  ScenePrimitive primitive;
  primitive.name = std::move(name);
  primitive.first_vertex = static_cast<uint32_t>(scene.positions.size());
  primitive.first_triangle = static_cast<uint32_t>(scene.triangles.size());
  primitive.albedo = albedo;
  scene.primitives.push_back(std::move(primitive));
}

// Closes the last primitive: sets its counts and fills the per-vertex albedo.
void end_primitive(Scene& scene) {
  ScenePrimitive& primitive = scene.primitives.back();
  primitive.vertex_count = static_cast<uint32_t>(scene.positions.size()) - primitive.first_vertex;
  primitive.triangle_count =
      static_cast<uint32_t>(scene.triangles.size()) - primitive.first_triangle;
  scene.albedo.resize(scene.positions.size(), primitive.albedo);
}

uint32_t add_vertex(Scene& scene, glm::dvec3 position, glm::dvec3 normal) {
  scene.positions.emplace_back(glm::vec3(position));
  scene.normals.emplace_back(glm::vec3(glm::normalize(normal)));
  return static_cast<uint32_t>(scene.positions.size() - 1);
}

// Adds triangle (a, b, c), flipped if needed so that its geometric normal agrees with the sum
// of its vertex normals (the builders' normals are exact, so this never misfires).
void add_triangle(Scene& scene, uint32_t a, uint32_t b, uint32_t c) {
  const glm::dvec3 pa(scene.positions[a]), pb(scene.positions[b]), pc(scene.positions[c]);
  const glm::dvec3 face = glm::cross(pb - pa, pc - pa);
  const glm::dvec3 vertex_normals =
      glm::dvec3(scene.normals[a]) + glm::dvec3(scene.normals[b]) + glm::dvec3(scene.normals[c]);
  if (glm::dot(face, vertex_normals) < 0.0) std::swap(b, c);
  scene.triangles.emplace_back(a, b, c);
}

// Appends a grid (no primitive bookkeeping) with normal `normal`.
void add_grid(Scene& scene, glm::dvec3 corner, glm::dvec3 edge_u, glm::dvec3 edge_v, int nu, int nv,
              glm::dvec3 normal) {
  const uint32_t base = static_cast<uint32_t>(scene.positions.size());
  for (int j = 0; j <= nv; ++j) {
    for (int i = 0; i <= nu; ++i) {
      const double s = static_cast<double>(i) / nu;
      const double t = static_cast<double>(j) / nv;
      add_vertex(scene, corner + s * edge_u + t * edge_v, normal);
    }
  }
  const auto index = [&](int i, int j) { return base + static_cast<uint32_t>(j * (nu + 1) + i); };
  for (int j = 0; j < nv; ++j) {
    for (int i = 0; i < nu; ++i) {
      add_triangle(scene, index(i, j), index(i + 1, j), index(i + 1, j + 1));
      add_triangle(scene, index(i, j), index(i + 1, j + 1), index(i, j + 1));
    }
  }
}

// Unit direction at polar angle theta from +Y and azimuth phi from +X toward +Z.
glm::dvec3 direction_from_y(double theta, double phi) {
  const double s = std::sin(theta);
  return {s * std::cos(phi), std::cos(theta), s * std::sin(phi)};
}

// Connects circle `first` (count vertices starting at index first) to circle `second`.
void add_band(Scene& scene, uint32_t first, uint32_t second, int count) {
  for (int s = 0; s < count; ++s) {
    const uint32_t s0 = static_cast<uint32_t>(s);
    const uint32_t s1 = static_cast<uint32_t>((s + 1) % count);
    add_triangle(scene, first + s0, first + s1, second + s1);
    add_triangle(scene, first + s0, second + s1, second + s0);
  }
}

// Connects a single apex vertex to a circle.
void add_fan(Scene& scene, uint32_t apex, uint32_t circle, int count) {
  for (int s = 0; s < count; ++s) {
    add_triangle(scene, apex, circle + static_cast<uint32_t>(s),
                 circle + static_cast<uint32_t>((s + 1) % count));
  }
}

// Triangulates a disc whose vertices are `centre` then nr circles of ns vertices (innermost
// first): a fan to the first circle, bands between the others; ends the primitive.
void close_disc(Scene& scene, uint32_t centre, int nr, int ns) {
  add_fan(scene, centre, centre + 1, ns);
  for (int k = 1; k < nr; ++k) {
    const uint32_t first = centre + 1 + static_cast<uint32_t>((k - 1) * ns);
    add_band(scene, first, first + static_cast<uint32_t>(ns), ns);
  }
  end_primitive(scene);
}

}  // namespace

Scene make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, int segments_u,
                int segments_v, glm::vec3 albedo, std::string name) {
  Scene scene;
  const glm::dvec3 normal = glm::normalize(glm::cross(glm::dvec3(edge_u), glm::dvec3(edge_v)));
  begin_primitive(scene, std::move(name), albedo);
  const int nu = std::max(segments_u, 1), nv = std::max(segments_v, 1);
  add_grid(scene, corner, edge_u, edge_v, nu, nv, normal);
  end_primitive(scene);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i)
      scene.texcoords.emplace_back(static_cast<float>(i) / static_cast<float>(nu),
                                   static_cast<float>(j) / static_cast<float>(nv));
  return scene;
}

Scene make_box(glm::vec3 min, glm::vec3 max, int segments, bool normals_inward, glm::vec3 albedo,
               std::string name) {
  Scene scene;
  const int n = std::max(segments, 1);
  const glm::dvec3 lo(min), hi(max), d = hi - lo;
  const glm::dvec3 ex(d.x, 0, 0), ey(0, d.y, 0), ez(0, 0, d.z);
  struct Face {
    glm::dvec3 corner, edge_u, edge_v, normal;
  };
  // Each face's edges satisfy cross(edge_u, edge_v) = outward normal (times area).
  const Face faces[6] = {
      {{hi.x, lo.y, lo.z}, ey, ez, {1, 0, 0}}, {{lo.x, lo.y, lo.z}, ez, ey, {-1, 0, 0}},
      {{lo.x, hi.y, lo.z}, ez, ex, {0, 1, 0}}, {{lo.x, lo.y, lo.z}, ex, ez, {0, -1, 0}},
      {{lo.x, lo.y, hi.z}, ex, ey, {0, 0, 1}}, {{lo.x, lo.y, lo.z}, ey, ex, {0, 0, -1}},
  };
  begin_primitive(scene, std::move(name), albedo);
  for (const Face& f : faces) {
    add_grid(scene, f.corner, f.edge_u, f.edge_v, n, n, normals_inward ? -f.normal : f.normal);
  }
  end_primitive(scene);
  return scene;
}

Scene make_uv_sphere(glm::vec3 center, float radius, int rings, int segments, bool normals_inward,
                     glm::vec3 albedo, std::string name) {
  Scene scene;
  const int nr = std::max(rings, 2), ns = std::max(segments, 3);
  const glm::dvec3 c(center);
  const double r = radius, sign = normals_inward ? -1.0 : 1.0;
  begin_primitive(scene, std::move(name), albedo);
  const uint32_t top = add_vertex(scene, c + glm::dvec3(0, r, 0), sign * glm::dvec3(0, 1, 0));
  for (int ring = 1; ring < nr; ++ring) {
    const double theta = kPi * ring / nr;
    for (int s = 0; s < ns; ++s) {
      const glm::dvec3 dir = direction_from_y(theta, 2.0 * kPi * s / ns);
      add_vertex(scene, c + r * dir, sign * dir);
    }
  }
  const uint32_t bottom = add_vertex(scene, c - glm::dvec3(0, r, 0), sign * glm::dvec3(0, -1, 0));
  add_fan(scene, top, top + 1, ns);
  for (int ring = 1; ring + 1 < nr; ++ring) {
    const uint32_t first = top + 1 + static_cast<uint32_t>((ring - 1) * ns);
    add_band(scene, first, first + static_cast<uint32_t>(ns), ns);
  }
  add_fan(scene, bottom, bottom - static_cast<uint32_t>(ns), ns);
  end_primitive(scene);
  return scene;
}

Scene make_spherical_cavity(float radius, float opening_half_angle, int rings, int segments,
                            glm::vec3 albedo) {
  Scene scene;
  const int nr = std::max(rings, 1), ns = std::max(segments, 3);
  const double r = radius;
  const double a = std::clamp(static_cast<double>(opening_half_angle), 0.0, kPi);
  const bool closed = opening_half_angle <= 0.0f;
  begin_primitive(scene, "cavity", albedo);
  // A closed cavity starts its circles one step below the pole (the pole itself is added last).
  const double theta0 = closed ? kPi / (nr + 1) : a;
  const double step = closed ? kPi / (nr + 1) : (kPi - a) / nr;
  for (int ring = 0; ring < nr; ++ring) {
    const double theta = theta0 + step * ring;
    for (int s = 0; s < ns; ++s) {
      const glm::dvec3 dir = direction_from_y(theta, 2.0 * kPi * s / ns);
      add_vertex(scene, r * dir, -dir);
    }
  }
  const uint32_t bottom = add_vertex(scene, {0, -r, 0}, {0, 1, 0});
  for (int ring = 0; ring + 1 < nr; ++ring) {
    const uint32_t first = static_cast<uint32_t>(ring * ns);
    add_band(scene, first, first + static_cast<uint32_t>(ns), ns);
  }
  add_fan(scene, bottom, bottom - static_cast<uint32_t>(ns), ns);
  if (closed) {
    const uint32_t top = add_vertex(scene, {0, r, 0}, {0, -1, 0});
    add_fan(scene, top, 0, ns);
  }
  end_primitive(scene);
  return scene;
}

Scene make_well(float radius, float depth, int segments, int rings, glm::vec3 albedo) {
  Scene scene;
  const int ns = std::max(segments, 3), nr = std::max(rings, 1);
  const double r = radius, h = depth;
  begin_primitive(scene, "well_wall", albedo);
  for (int k = 0; k <= nr; ++k) {
    const double y = -h + h * k / nr;
    for (int s = 0; s < ns; ++s) {
      const glm::dvec3 dir = direction_from_y(kPi / 2, 2.0 * kPi * s / ns);
      add_vertex(scene, glm::dvec3(r * dir.x, y, r * dir.z), -dir);
    }
  }
  for (int k = 0; k < nr; ++k) {
    const uint32_t first = static_cast<uint32_t>(k * ns);
    add_band(scene, first, first + static_cast<uint32_t>(ns), ns);
  }
  end_primitive(scene);

  begin_primitive(scene, "well_bottom", albedo);
  const glm::dvec3 up(0, 1, 0);
  const uint32_t centre = add_vertex(scene, {0, -h, 0}, up);
  for (int k = 1; k <= nr; ++k) {
    const double rk = r * k / nr;
    for (int s = 0; s < ns; ++s) {
      const glm::dvec3 dir = direction_from_y(kPi / 2, 2.0 * kPi * s / ns);
      add_vertex(scene, glm::dvec3(rk * dir.x, -h, rk * dir.z), up);
    }
  }
  close_disc(scene, centre, nr, ns);
  return scene;
}

void append_scene(Scene& into, const Scene& part) {
  const uint32_t vertex_offset = static_cast<uint32_t>(into.positions.size());
  const uint32_t triangle_offset = static_cast<uint32_t>(into.triangles.size());
  into.positions.insert(into.positions.end(), part.positions.begin(), part.positions.end());
  into.normals.insert(into.normals.end(), part.normals.begin(), part.normals.end());
  into.albedo.insert(into.albedo.end(), part.albedo.begin(), part.albedo.end());
  if (!into.texcoords.empty() || !part.texcoords.empty()) {  // zeros where a part has none
    into.texcoords.resize(vertex_offset, glm::vec2(0.f));
    if (part.texcoords.empty())
      into.texcoords.resize(into.positions.size(), glm::vec2(0.f));
    else
      into.texcoords.insert(into.texcoords.end(), part.texcoords.begin(), part.texcoords.end());
  }
  if (!into.tangents.empty() || !part.tangents.empty()) {  // zeros ("missing") where none
    into.tangents.resize(vertex_offset, glm::vec4(0.f));
    if (part.tangents.empty())
      into.tangents.resize(into.positions.size(), glm::vec4(0.f));
    else
      into.tangents.insert(into.tangents.end(), part.tangents.begin(), part.tangents.end());
  }
  for (const glm::uvec3& t : part.triangles) into.triangles.push_back(t + vertex_offset);
  for (ScenePrimitive primitive : part.primitives) {
    primitive.first_vertex += vertex_offset;
    primitive.first_triangle += triangle_offset;
    into.primitives.push_back(std::move(primitive));
  }
  into.cameras.insert(into.cameras.end(), part.cameras.begin(), part.cameras.end());
  into.skipped_degenerate_triangles += part.skipped_degenerate_triangles;
  into.computed_normal_vertices += part.computed_normal_vertices;
}

Scene make_demo_scene() {
  const glm::vec3 grey(0.7f), red(0.8f, 0.15f, 0.1f), green(0.15f, 0.7f, 0.15f), white(0.8f);
  const float wall_height = 1.8f, size = 6.0f, corner = -2.5f;
  Scene scene;
  // Ground: 6 x 6 units, 80 x 80 cells, normal +Y (cross(+Z, +X) = +Y); the walls stand on
  // its back and left edges.
  append_scene(scene,
               make_quad({corner, 0, corner}, {0, 0, size}, {size, 0, 0}, 80, 80, grey, "ground"));
  // Back wall (red) in the plane z = -2.5, facing +Z; left wall (green) in x = -2.5, facing +X.
  append_scene(scene, make_quad({corner, 0, corner}, {size, 0, 0}, {0, wall_height, 0}, 60, 16, red,
                                "red_wall"));
  append_scene(scene, make_quad({corner, 0, corner}, {0, wall_height, 0}, {0, 0, size}, 16, 60,
                                green, "green_wall"));
  // A sphere 0.3 from both walls and a box 0.3 from the red wall, both resting on the ground.
  append_scene(scene, make_uv_sphere({-1.5f, 0.7f, -1.5f}, 0.7f, 32, 64, false, white, "sphere"));
  append_scene(scene, make_box({0.1f, 0.0f, -2.2f}, {1.0f, 0.9f, -1.3f}, 10, false, white, "box"));

  SceneCamera camera;
  camera.name = "camera";
  camera.eye = {2.6f, 1.8f, 3.0f};
  camera.target = {-0.9f, 0.5f, -1.0f};
  camera.up = {0.f, 1.f, 0.f};
  camera.yfov_radians = 0.75f;
  scene.cameras.push_back(camera);
  scene.source_path = "procedural:demo";
  return scene;
}

Scene make_disc(glm::vec3 center, glm::vec3 axis_u, glm::vec3 axis_v, float radius, int rings,
                int segments, glm::vec3 albedo, std::string name) {
  Scene scene;
  const int ns = std::max(segments, 3), nr = std::max(rings, 1);
  const glm::dvec3 c(center), e1 = glm::normalize(glm::dvec3(axis_u));
  const glm::dvec3 normal = glm::normalize(glm::cross(e1, glm::dvec3(axis_v)));
  const glm::dvec3 e2 = glm::cross(normal, e1);
  begin_primitive(scene, std::move(name), albedo);
  const uint32_t centre = add_vertex(scene, c, normal);
  scene.tangents.emplace_back(glm::vec3(e2), 1.f);  // the φ = 0 circle's direction
  for (int k = 1; k <= nr; ++k) {
    for (int s = 0; s < ns; ++s) {
      const double phi = 2.0 * kPi * s / ns, rk = double(radius) * k / nr;
      add_vertex(scene, c + rk * (std::cos(phi) * e1 + std::sin(phi) * e2), normal);
      scene.tangents.emplace_back(glm::vec3(-std::sin(phi) * e1 + std::cos(phi) * e2), 1.f);
    }
  }
  close_disc(scene, centre, nr, ns);
  return scene;
}

brdf::Material gltf_brdf(brdf::Rgb base, double metallic, double alpha_x, double alpha_y) {
  brdf::Material m;
  m.model = brdf::MaterialModel::kGltf;
  m.distribution = brdf::NormalDistribution::kGgx;
  m.fresnel = brdf::FresnelMode::kSchlick;
  m.specular = brdf::grey(0.04);
  m.diffuse = base;
  m.metallic = metallic;
  m.alpha_x = alpha_x;
  m.alpha_y = alpha_y;
  return m;
}

namespace {

void name_material(Scene& part, const std::string& material, std::optional<brdf::Material> b) {
  for (ScenePrimitive& p : part.primitives) {
    p.material = material;
    p.brdf = b;
  }
}

}  // namespace

Scene make_glossy_scene() {
  Scene scene;
  // Floor: 6 x 6 units, 60 x 60 cells, Lambert grey, normal +Y.
  Scene floor =
      make_quad({-3.f, 0.f, -3.f}, {0, 0, 6.f}, {6.f, 0, 0}, 60, 60, glm::vec3(0.6f), "floor");
  name_material(floor, "floor", std::nullopt);
  append_scene(scene, floor);
  // A glossy red dielectric sphere: roughness 0.3 (α 0.09), F0 0.04 over a red diffuse layer.
  const glm::vec3 red(0.7f, 0.08f, 0.06f);
  Scene sphere = make_uv_sphere({-1.3f, 0.6f, 0.2f}, 0.6f, 32, 64, false, red, "glossy_sphere");
  name_material(sphere, "glossy_red", gltf_brdf(brdf::Rgb{red.x, red.y, red.z}, 0.0, 0.09, 0.09));
  append_scene(scene, sphere);
  // A brushed-metal disc standing on its rim, facing +Z: tangents along concentric circles,
  // roughness 0.35 (α 0.1225) and anisotropy strength 0.8: α_x = 0.1225 + 0.8775 × 0.64 along
  // the circles.
  const glm::vec3 steel(0.9f, 0.9f, 0.88f);
  Scene disc =
      make_disc({0.2f, 0.75f, -1.0f}, {1, 0, 0}, {0, 1, 0}, 0.7f, 16, 96, steel, "brushed_disc");
  name_material(
      disc, "brushed_steel",
      gltf_brdf(brdf::Rgb{steel.x, steel.y, steel.z}, 1.0, 0.1225 + 0.8775 * 0.64, 0.1225));
  append_scene(scene, disc);
  // A rough gold box: metallic, roughness 0.5 (α 0.25).
  const glm::vec3 gold(0.95f, 0.74f, 0.33f);
  Scene box = make_box({1.0f, 0.f, -0.3f}, {1.8f, 0.8f, 0.5f}, 8, false, gold, "gold_box");
  name_material(box, "rough_gold", gltf_brdf(brdf::Rgb{gold.x, gold.y, gold.z}, 1.0, 0.25, 0.25));
  append_scene(scene, box);
  scene.tangents = tangent_frames(scene);  // the disc's own, the others from UVs or normals

  SceneCamera camera;
  camera.name = "camera";
  camera.eye = {0.4f, 1.9f, 4.2f};
  camera.target = {0.1f, 0.5f, -0.3f};
  camera.yfov_radians = 0.75f;
  scene.cameras.push_back(camera);
  scene.source_path = "procedural:glossy";
  return scene;
}

}  // namespace prt::scene
