// Procedural meshes (scene/procedural_mesh.h): counts, layout, normals, areas, winding.
#include <cmath>
#include <map>
#include <utility>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "scene/mesh_normals.h"
#include "scene/procedural_mesh.h"
#include "sh/constants.h"

using prt::scene::Scene;

namespace {

using prt::sh::kPi;
// Positions are stored as float: relative rounding about 6e-8, so 1e-5 relative leaves room for
// the trigonometry of the builders and the summations below.
constexpr double kFloatTolerance = 1e-5;

double triangle_area(const Scene& s, const glm::uvec3& t) {
  const glm::dvec3 a(s.positions[t.x]), b(s.positions[t.y]), c(s.positions[t.z]);
  return 0.5 * glm::length(glm::cross(b - a, c - a));
}

double total_area(const Scene& s) {
  double area = 0.0;
  for (const glm::uvec3& t : s.triangles) area += triangle_area(s, t);
  return area;
}

// Signed volume by the divergence theorem: positive for a closed mesh wound outward.
double signed_volume(const Scene& s) {
  double volume = 0.0;
  for (const glm::uvec3& t : s.triangles) {
    const glm::dvec3 a(s.positions[t.x]), b(s.positions[t.y]), c(s.positions[t.z]);
    volume += glm::dot(a, glm::cross(b, c)) / 6.0;
  }
  return volume;
}

// Every triangle's geometric normal agrees with each of its vertex normals (cos > 0.5).
void check_winding_matches_normals(const Scene& s) {
  for (const glm::uvec3& t : s.triangles) {
    const glm::dvec3 a(s.positions[t.x]), b(s.positions[t.y]), c(s.positions[t.z]);
    const glm::dvec3 face = glm::normalize(glm::cross(b - a, c - a));
    for (int k = 0; k < 3; ++k) REQUIRE(glm::dot(face, glm::dvec3(s.normals[t[k]])) > 0.5);
  }
}

// Every directed edge appears once and its reverse once: closed and consistently wound.
void check_closed_and_consistent(const Scene& s) {
  std::map<std::pair<uint32_t, uint32_t>, int> edges;
  for (const glm::uvec3& t : s.triangles) {
    for (int k = 0; k < 3; ++k) ++edges[{t[k], t[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : edges) {
    REQUIRE(count == 1);
    REQUIRE(edges.count({edge.second, edge.first}) == 1);
  }
}

void check_basic_invariants(const Scene& s) {
  REQUIRE(s.normals.size() == s.positions.size());
  REQUIRE(s.albedo.size() == s.positions.size());
  uint32_t vertices = 0, triangles = 0;
  for (const auto& p : s.primitives) {
    REQUIRE(p.first_vertex == vertices);
    REQUIRE(p.first_triangle == triangles);
    vertices += p.vertex_count;
    triangles += p.triangle_count;
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v) {
      REQUIRE(s.albedo[v] == p.albedo);
    }
  }
  REQUIRE(vertices == s.positions.size());
  REQUIRE(triangles == s.triangles.size());
  const double extent = s.extent();
  for (const glm::vec3& n : s.normals) REQUIRE(glm::length(n) == Approx(1.0).margin(1e-6));
  for (const glm::uvec3& t : s.triangles) {
    REQUIRE(std::max({t.x, t.y, t.z}) < s.positions.size());
    REQUIRE_FALSE(prt::scene::is_degenerate_triangle(s.positions[t.x], s.positions[t.y],
                                                     s.positions[t.z], extent));
  }
}

}  // namespace

TEST_CASE("make_quad lays out a (u+1)x(v+1) grid with the documented index and normal") {
  const glm::vec3 corner(1, 2, 3), eu(2, 0, 0), ev(0, 0, -3);
  const Scene s = prt::scene::make_quad(corner, eu, ev, 4, 3, glm::vec3(0.5f), "floor");
  check_basic_invariants(s);
  REQUIRE(s.primitives.size() == 1);
  CHECK(s.primitives[0].name == "floor");
  REQUIRE(s.positions.size() == 5 * 4);
  REQUIRE(s.triangles.size() == 2 * 4 * 3);
  // cross(+X, -Z) = +Y.
  for (const glm::vec3& n : s.normals) CHECK(glm::distance(n, glm::vec3(0, 1, 0)) < 1e-6f);
  for (int j = 0; j <= 3; ++j) {
    for (int i = 0; i <= 4; ++i) {
      const glm::vec3 expected =
          corner + eu * (static_cast<float>(i) / 4.0f) + ev * (static_cast<float>(j) / 3.0f);
      CHECK(glm::distance(s.positions[static_cast<std::size_t>(j * 5 + i)], expected) < 1e-6f);
    }
  }
  // Area of the parallelogram |cross(eu, ev)| = 6, exactly tiled by the grid.
  CHECK(total_area(s) == Approx(6.0).epsilon(kFloatTolerance));
  check_winding_matches_normals(s);
}

TEST_CASE("make_box has 6 separate face grids, outward or inward, closed with the box's area") {
  const glm::vec3 lo(-1, 0, 2), hi(1, 3, 2.5f);
  const glm::dvec3 centre = (glm::dvec3(lo) + glm::dvec3(hi)) / 2.0;
  for (const bool inward : {false, true}) {
    const Scene s = prt::scene::make_box(lo, hi, 5, inward, glm::vec3(0.3f));
    check_basic_invariants(s);
    REQUIRE(s.primitives.size() == 1);
    REQUIRE(s.positions.size() == 6 * 6 * 6);
    REQUIRE(s.triangles.size() == 6 * 2 * 25);
    // 2(2*3 + 3*0.5 + 0.5*2) = 17.
    CHECK(total_area(s) == Approx(17.0).epsilon(kFloatTolerance));
    // Closed box of volume 2*3*0.5 = 3; the sign says which way it is wound.
    CHECK(signed_volume(s) == Approx(inward ? -3.0 : 3.0).epsilon(kFloatTolerance));
    for (std::size_t v = 0; v < s.positions.size(); ++v) {
      const glm::dvec3 n(s.normals[v]);
      // Axis-aligned normal; the vertex lies on the face the normal belongs to.
      CHECK(std::abs(n.x) + std::abs(n.y) + std::abs(n.z) == Approx(1.0));
      const glm::dvec3 outward = inward ? -n : n;
      const glm::dvec3 offset = glm::dvec3(s.positions[v]) - centre;
      const glm::dvec3 half = (glm::dvec3(hi) - glm::dvec3(lo)) / 2.0;
      CHECK(glm::dot(offset, outward) == Approx(glm::dot(half, glm::abs(outward))).margin(1e-6));
    }
    check_winding_matches_normals(s);
  }
}

TEST_CASE("make_uv_sphere: vertices on the sphere, radial normals, closed, area converges") {
  const glm::vec3 c(0.5f, -1.f, 2.f);
  const float r = 1.5f;
  const Scene s = prt::scene::make_uv_sphere(c, r, 24, 48, false, glm::vec3(0.9f, 0.1f, 0.1f));
  check_basic_invariants(s);
  REQUIRE(s.positions.size() == 2 + 23 * 48);
  REQUIRE(s.triangles.size() == 2 * 48 * 23);
  CHECK(s.positions.front().y == Approx(c.y + r));
  CHECK(s.positions.back().y == Approx(c.y - r));
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const glm::dvec3 d = glm::dvec3(s.positions[v]) - glm::dvec3(c);
    REQUIRE(glm::length(d) == Approx(r).epsilon(kFloatTolerance));
    REQUIRE(glm::distance(glm::dvec3(s.normals[v]), d / glm::length(d)) < 1e-5);
  }
  check_closed_and_consistent(s);
  check_winding_matches_normals(s);
  // Inscribed polyhedron: its area is below 4 pi r^2 and the gap shrinks as O(h^2), so a 2x
  // finer mesh must cut the relative deficit by ~4 (accept > 3). At 24x48 the deficit is
  // about (pi/24)^2/3 ~ 0.6%; accept below 1%.
  const double exact = 4.0 * kPi * r * r;
  const double coarse = 1.0 - total_area(s) / exact;
  const Scene fine = prt::scene::make_uv_sphere(c, r, 48, 96, false, glm::vec3(0.5f));
  const double finer = 1.0 - total_area(fine) / exact;
  CHECK(coarse > 0.0);
  CHECK(coarse < 0.01);
  CHECK(finer > 0.0);
  CHECK(coarse / finer > 3.0);
  // Outward winding: positive volume (origin-independent for a closed mesh), below 4/3 pi r^3.
  const double volume = signed_volume(s);
  CHECK(volume > 0.0);
  CHECK(volume < 4.0 / 3.0 * kPi * r * r * r);
  CHECK(volume > 0.97 * 4.0 / 3.0 * kPi * r * r * r);

  const Scene in = prt::scene::make_uv_sphere(c, r, 24, 48, true, glm::vec3(0.5f));
  check_winding_matches_normals(in);
  CHECK(signed_volume(in) == Approx(-volume).epsilon(kFloatTolerance));
  for (std::size_t v = 0; v < in.positions.size(); ++v) {
    CHECK(glm::distance(in.normals[v], -s.normals[v]) < 1e-6f);
  }
}

TEST_CASE("make_spherical_cavity: vertices on the sphere, normals toward the centre, rim at a") {
  const float r = 2.0f;
  const float a = static_cast<float>(kPi / 6);
  const Scene s = prt::scene::make_spherical_cavity(r, a, 30, 64, glm::vec3(0.99f));
  check_basic_invariants(s);
  REQUIRE(s.primitives.size() == 1);
  REQUIRE(s.positions.size() == 30 * 64 + 1);
  REQUIRE(s.triangles.size() == 2 * 64 * 29 + 64);
  const double rim_y = r * std::cos(static_cast<double>(a));
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const glm::dvec3 p(s.positions[v]);
    REQUIRE(glm::length(p) == Approx(r).epsilon(kFloatTolerance));
    // Normals point to the centre.
    REQUIRE(glm::distance(glm::dvec3(s.normals[v]), -p / glm::length(p)) < 1e-5);
    // Nothing lies inside the opening's cap.
    REQUIRE(p.y <= rim_y + 1e-5);
  }
  for (int k = 0; k < 64; ++k) CHECK(s.positions[static_cast<std::size_t>(k)].y == Approx(rim_y));
  check_winding_matches_normals(s);
  // Area of the sphere minus the cap, 2 pi r^2 (1 + cos a); the inscribed mesh falls short by
  // O(h^2), about 0.1% at this resolution: accept 0.5%.
  const double exact = 2.0 * kPi * r * r * (1.0 + std::cos(static_cast<double>(a)));
  CHECK(total_area(s) < exact);
  CHECK(total_area(s) == Approx(exact).epsilon(5e-3));

  // A closed cavity (a = 0) is a closed mesh wound inward: negative volume.
  const Scene closed = prt::scene::make_spherical_cavity(r, 0.f, 20, 40, glm::vec3(0.5f));
  check_basic_invariants(closed);
  check_closed_and_consistent(closed);
  check_winding_matches_normals(closed);
  CHECK(signed_volume(closed) < -0.95 * 4.0 / 3.0 * kPi * r * r * r);
}

TEST_CASE("make_well: wall and bottom disc with exact prism/polygon areas and documented layout") {
  const float r = 1.0f, h = 2.0f;
  const int segments = 48, rings = 6;
  const Scene s = prt::scene::make_well(r, h, segments, rings, glm::vec3(0.6f));
  check_basic_invariants(s);
  REQUIRE(s.primitives.size() == 2);
  const auto& wall = s.primitives[0];
  const auto& bottom = s.primitives[1];
  CHECK(wall.name == "well_wall");
  CHECK(bottom.name == "well_bottom");
  REQUIRE(wall.vertex_count == (rings + 1) * segments);
  REQUIRE(bottom.vertex_count == 1 + rings * segments);
  CHECK(glm::distance(s.positions[bottom.first_vertex], glm::vec3(0, -h, 0)) < 1e-6f);

  double wall_area = 0.0, bottom_area = 0.0;
  for (uint32_t t = 0; t < s.triangles.size(); ++t) {
    (t < wall.triangle_count ? wall_area : bottom_area) += triangle_area(s, s.triangles[t]);
  }
  // The wall is a prism inscribed in the cylinder: lateral area n * 2r sin(pi/n) * h exactly;
  // the bottom is the inscribed n-gon, area n/2 r^2 sin(2 pi/n). Float rounding only.
  const double n = segments;
  CHECK(wall_area == Approx(n * 2.0 * r * std::sin(kPi / n) * h).epsilon(kFloatTolerance));
  CHECK(bottom_area == Approx(n / 2.0 * r * r * std::sin(2.0 * kPi / n)).epsilon(kFloatTolerance));

  for (uint32_t v = wall.first_vertex; v < wall.first_vertex + wall.vertex_count; ++v) {
    const glm::dvec3 p(s.positions[v]), nrm(s.normals[v]);
    CHECK(std::hypot(p.x, p.z) == Approx(r).epsilon(kFloatTolerance));
    CHECK(p.y <= 1e-6);
    CHECK(p.y >= -h - 1e-6);
    CHECK(nrm.y == Approx(0.0).margin(1e-7));
    // Inward: the normal points to the axis.
    CHECK(glm::dot(nrm, glm::dvec3(p.x, 0, p.z)) == Approx(-r).epsilon(kFloatTolerance));
  }
  for (uint32_t v = bottom.first_vertex; v < bottom.first_vertex + bottom.vertex_count; ++v) {
    CHECK(s.positions[v].y == Approx(-h));
    CHECK(glm::distance(s.normals[v], glm::vec3(0, 1, 0)) < 1e-6f);
  }
  check_winding_matches_normals(s);
}

TEST_CASE("append_scene offsets indices and primitive ranges and sums the counters") {
  Scene a = prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 2, 2, glm::vec3(0.1f), "a");
  a.skipped_degenerate_triangles = 2;
  Scene b = prt::scene::make_box({0, 0, 0}, {1, 1, 1}, 1, false, glm::vec3(0.2f), "b");
  b.computed_normal_vertices = 5;
  b.cameras.push_back({});
  const Scene a_copy = a;
  prt::scene::append_scene(a, b);
  check_basic_invariants(a);
  REQUIRE(a.primitives.size() == 2);
  CHECK(a.primitives[1].first_vertex == a_copy.positions.size());
  CHECK(a.primitives[1].first_triangle == a_copy.triangles.size());
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    CHECK(a.triangles[a_copy.triangles.size() + t] ==
          b.triangles[t] + static_cast<uint32_t>(a_copy.positions.size()));
  }
  CHECK(a.cameras.size() == 1);
  CHECK(a.skipped_degenerate_triangles == 2);
  CHECK(a.computed_normal_vertices == 5);
}

TEST_CASE("make_demo_scene is small, coloured, framed by its camera and clean") {
  const Scene s = prt::scene::make_demo_scene();
  check_basic_invariants(s);
  CHECK(s.positions.size() <= 20000);
  CHECK(s.positions.size() >= 8000);  // dense enough for per-vertex shadows
  std::map<std::string, glm::vec3> albedo;
  for (const auto& p : s.primitives) albedo[p.name] = p.albedo;
  REQUIRE(albedo.count("ground") == 1);
  REQUIRE(albedo.count("red_wall") == 1);
  REQUIRE(albedo.count("green_wall") == 1);
  CHECK(albedo["red_wall"].r > 3 * albedo["red_wall"].g);
  CHECK(albedo["green_wall"].g > 3 * albedo["green_wall"].r);
  for (const auto& [name, rho] : albedo) {
    CHECK(glm::all(glm::lessThan(rho, glm::vec3(1.f))));
    CHECK(glm::all(glm::greaterThan(rho, glm::vec3(0.f))));
  }
  REQUIRE(s.cameras.size() == 1);
  const auto& cam = s.cameras[0];
  // Looks slightly down; the sphere, the box and the walls' corner edge fit inside a 16:9
  // frame of the camera's vertical field of view.
  const glm::dvec3 forward = glm::normalize(glm::dvec3(cam.target) - glm::dvec3(cam.eye));
  CHECK(forward.y < 0.0);
  CHECK(forward.y > -0.6);
  const glm::dvec3 right = glm::normalize(glm::cross(forward, glm::dvec3(cam.up)));
  const glm::dvec3 up = glm::cross(right, forward);
  const double tan_half = std::tan(0.5 * cam.yfov_radians);
  const auto check_in_frame = [&](const glm::dvec3& point) {
    const glm::dvec3 d = point - glm::dvec3(cam.eye);
    const double depth = glm::dot(d, forward);
    REQUIRE(depth > 0.0);
    CHECK(std::abs(glm::dot(d, up) / depth) < tan_half);
    CHECK(std::abs(glm::dot(d, right) / depth) < tan_half * 16.0 / 9.0);
  };
  for (const auto& p : s.primitives) {
    if (p.name != "sphere" && p.name != "box") continue;
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v) {
      check_in_frame(glm::dvec3(s.positions[v]));
    }
  }
  check_in_frame({-2.5, 0.0, -2.5});
  check_in_frame({-2.5, 1.8, -2.5});
}
