// The preview of `prt view` (cli/view/view_preview.h): vertex clustering of a large scene for the
// page's first frame. Checked on grids whose answer is known: a unit square (area 1, boundary on
// x, z ∈ {0, 1}, facing +Y) and an open box corner (two squares at 90° with separate vertices).
#include <catch2/catch.hpp>

#include <cmath>
#include <set>

#include "view/view_preview.h"

namespace {

using prt::cli::view::build_preview_mesh;
using prt::cli::view::PreviewMesh;

// An n × n-vertex grid over the unit square, mapped by `place(u, v)`, normal `normal`.
template <class Place>
void add_grid(prt::scene::Scene* scene, int n, const glm::vec3& normal, Place place) {
  const auto first = std::uint32_t(scene->positions.size());
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      scene->positions.push_back(place(float(i) / float(n - 1), float(j) / float(n - 1)));
      scene->normals.push_back(normal);
      scene->albedo.emplace_back(0.5f);
    }
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const std::uint32_t a = first + std::uint32_t(j * n + i), b = a + 1, c = a + std::uint32_t(n),
                          d = c + 1;
      scene->triangles.emplace_back(a, c, b);  // counter-clockwise seen from +Y
      scene->triangles.emplace_back(b, c, d);
    }
}

glm::dvec3 face_normal(const prt::scene::Scene& s, const PreviewMesh& p, std::size_t t) {
  const glm::dvec3 a(s.positions[p.source_vertex[p.indices[3 * t]]]);
  const glm::dvec3 b(s.positions[p.source_vertex[p.indices[3 * t + 1]]]);
  const glm::dvec3 c(s.positions[p.source_vertex[p.indices[3 * t + 2]]]);
  return glm::cross(b - a, c - a);
}

}  // namespace

TEST_CASE("preview of a square: about the target's vertices, no hole, boundary kept, facing up",
          "[view][preview]") {
  prt::scene::Scene scene;
  add_grid(&scene, 201, {0, 1, 0}, [](float u, float v) { return glm::vec3(u, 0, v); });
  const PreviewMesh p = build_preview_mesh(scene, 1000);
  // Cells of √(1/1000) on a unit square: 32 per side, 1024 occupied (the target within the
  // rounding of the cell count per side).
  CHECK(p.source_vertex.size() >= 800);
  CHECK(p.source_vertex.size() <= 1300);
  std::set<std::uint32_t> distinct(p.source_vertex.begin(), p.source_vertex.end());
  CHECK(distinct.size() == p.source_vertex.size());  // each preview vertex a different one
  CHECK(*distinct.rbegin() < scene.vertex_count());
  // The boundary clusters take boundary vertices: the preview spans the square exactly.
  glm::vec3 lo(1e9f), hi(-1e9f);
  for (const std::uint32_t v : p.source_vertex) {
    lo = glm::min(lo, scene.positions[v]);
    hi = glm::max(hi, scene.positions[v]);
  }
  CHECK(lo.x == 0.f);
  CHECK(lo.z == 0.f);
  CHECK(hi.x == 1.f);
  CHECK(hi.z == 1.f);
  // Every triangle faces +Y, and together they cover the square once: area 1 (the corners'
  // clusters may pick vertices a little off the corner: within 1%).
  double area = 0.0;
  bool all_up = true;
  for (std::size_t t = 0; t < p.indices.size() / 3; ++t) {
    const glm::dvec3 n = face_normal(scene, p, t);
    all_up = all_up && n.y > 0.0;
    area += 0.5 * glm::length(n);
  }
  CHECK(all_up);
  CHECK(area == Approx(1.0).epsilon(0.01));
  // Deterministic.
  const PreviewMesh again = build_preview_mesh(scene, 1000);
  CHECK(again.source_vertex == p.source_vertex);
  CHECK(again.indices == p.indices);
}

TEST_CASE("preview of a box corner: no triangle joins the two faces", "[view][preview]") {
  prt::scene::Scene scene;
  add_grid(&scene, 101, {0, 1, 0}, [](float u, float v) { return glm::vec3(u, 0, v); });
  const std::size_t floor_vertices = scene.vertex_count();
  // The wall x = 0, facing +X, sharing the floor's edge positions but not its vertices.
  add_grid(&scene, 101, {1, 0, 0}, [](float u, float v) { return glm::vec3(0, v, u); });
  const PreviewMesh p = build_preview_mesh(scene, 500);
  REQUIRE(!p.indices.empty());
  std::size_t mixed = 0;
  double floor_area = 0.0, wall_area = 0.0;
  for (std::size_t t = 0; t < p.indices.size() / 3; ++t) {
    int on_floor = 0;
    for (int k = 0; k < 3; ++k) on_floor += p.source_vertex[p.indices[3 * t + k]] < floor_vertices;
    if (on_floor != 0 && on_floor != 3) ++mixed;
    (on_floor == 3 ? floor_area : wall_area) += 0.5 * glm::length(face_normal(scene, p, t));
  }
  CHECK(mixed == 0);
  CHECK(floor_area == Approx(1.0).epsilon(0.02));
  CHECK(wall_area == Approx(1.0).epsilon(0.02));
}

TEST_CASE("preview refuses a zero target", "[view][preview]") {
  prt::scene::Scene scene;
  CHECK_THROWS_AS(build_preview_mesh(scene, 0), std::invalid_argument);
}
