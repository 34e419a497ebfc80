// subdivision_quality — what conforming subdivision (scene::subdivide_to_edge_length) makes of
// the irregular octahedron of tests/radiosity and of the Cornell box: triangles, vertices,
// smallest angle, worst and mean aspect ratio (longest edge × perimeter / (4√3 · area): 1 for
// an equilateral triangle), edges not matched by a reverse edge (the box is open at the front
// and its parts do not share edges: its count is a baseline) and vertices inside another
// triangle's edge (T-junctions; counted below 20,000 triangles). docs/RADIOSITY.md,
// "Conforming subdivision".
// Usage: subdivision_quality [--quick] [CORNELL_OBJ]
//   --quick: one edge length per mesh (for the test suite); CORNELL_OBJ defaults to
//   ../shared/data/meshes/cornell_box.obj (skipped when missing).
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fixtures/radiosity/mesh_quality.h"
#include "fixtures/radiosity/radiosity_fixtures.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace {

// Edges (as position pairs) on other than one triangle in each direction, and vertices strictly
// inside another edge (when `t_junctions`; brute force).
std::pair<std::size_t, std::size_t> seams(const prt::scene::Scene& s, bool t_junctions) {
  using Key = std::array<float, 6>;
  std::map<Key, int> directed;
  for (const glm::uvec3& t : s.triangles)
    for (int k = 0; k < 3; ++k) {
      const glm::vec3 a = s.positions[t[k]], b = s.positions[t[(k + 1) % 3]];
      ++directed[Key{a.x, a.y, a.z, b.x, b.y, b.z}];
    }
  std::size_t unmatched = 0, inside = 0;
  for (const auto& [e, count] : directed) {
    const auto found = directed.find(Key{e[3], e[4], e[5], e[0], e[1], e[2]});
    if (count != 1 || found == directed.end() || found->second != 1) ++unmatched;
    if (!t_junctions) continue;
    const glm::dvec3 a(e[0], e[1], e[2]), b(e[3], e[4], e[5]);
    const double length2 = glm::dot(b - a, b - a);
    for (const glm::vec3& p : s.positions) {
      const double t = glm::dot(glm::dvec3(p) - a, b - a) / length2;
      const glm::dvec3 off = glm::dvec3(p) - (a + t * (b - a));
      if (t > 1e-6 && t < 1 - 1e-6 && glm::dot(off, off) < 1e-12 * length2) ++inside;
    }
  }
  return {unmatched, inside};
}

void print_row(const std::string& name, double max_edge, const prt::scene::Scene& out) {
  double worst = 0.0, mean = 0.0;
  for (const glm::uvec3& t : out.triangles) {
    double longest = 0.0, perimeter = 0.0;
    for (int k = 0; k < 3; ++k) {
      const double l =
          glm::length(glm::dvec3(out.positions[t[k]]) - glm::dvec3(out.positions[t[(k + 1) % 3]]));
      longest = std::max(longest, l), perimeter += l;
    }
    const double aspect =
        longest * perimeter / (4 * std::sqrt(3.0) * prt::test::triangle_area(out, t));
    worst = std::max(worst, aspect), mean += aspect / double(out.triangles.size());
  }
  const auto [unmatched, inside] = seams(out, out.triangles.size() < 20000);
  std::printf(
      "%-10s L=%-5g triangles %6zu vertices %6zu smallest angle %6.2f° aspect worst %6.2f mean "
      "%5.3f unmatched edges %5zu T-junction vertices %5zu\n",
      name.c_str(), max_edge, out.triangles.size(), out.positions.size(),
      prt::test::smallest_angle_degrees(out), worst, mean, unmatched, inside);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string box = std::string(PRT_SHARED_DATA_DIR) + "/meshes/cornell_box.obj";
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else if (argv[i][0] != '-')
      box = argv[i];
    else {
      std::fprintf(stderr, "usage: subdivision_quality [--quick] [CORNELL_OBJ]\n");
      return 2;
    }
  }
  std::vector<std::pair<std::string, prt::scene::Scene>> scenes;
  scenes.emplace_back("octahedron", prt::test::octahedron(false));
  if (std::filesystem::exists(box))
    scenes.emplace_back("cornell", prt::scene::load_scene(box));
  else
    std::printf("Cornell box: skipped, %s is missing\n", box.c_str());
  for (const auto& [name, scene] : scenes) {
    const bool cornell = name == "cornell";
    std::vector<double> edges =
        cornell ? std::vector<double>{100, 70, 50, 35, 29} : std::vector<double>{0.37, 0.2};
    if (quick) edges.resize(1);
    for (const double max_edge : edges)
      print_row(name, max_edge, prt::scene::subdivide_to_edge_length(scene, max_edge));
  }
  return 0;
}
