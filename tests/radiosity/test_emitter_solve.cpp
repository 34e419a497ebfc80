// Per-emitter responses (radiosity/emitter_solve.h): recombined with arbitrary colours they equal
// a direct solve with those emissions; the default colours reproduce the plain solve; emitters
// are grouped by material and a material that emits unevenly is refused.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include <catch2/catch.hpp>

#include "fixtures/radiosity/radiosity_fixtures.h"
#include "prt/emitters/emitter_responses.h"
#include "radiosity/emitter_solve.h"
#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"

using namespace prt::radiosity;
using prt::scene::make_quad;

namespace {

// An open-topped room with coloured walls, a block, a ceiling lamp (material "lamp") and a
// bluish panel low on the back wall (material "panel"): two emitters of different materials
// that light different parts of the room.
prt::scene::Scene two_emitter_room() {
  prt::scene::Scene s = prt::test::open_room("lamp");
  prt::test::append(
      s,
      make_quad({0.1f, 0.05f, 0.99f}, {0, 0.2f, 0}, {0.3f, 0, 0}, 1, 1, glm::vec3(0.3f), "panel"),
      "panel", {1.f, 2.f, 4.f});
  return s;
}

// Direct solve with every patch of material `m` emitting `emission[m]`, as vertex radiance.
std::vector<float> direct(const prt::scene::Scene& scene, const std::vector<Patch>& patches,
                          const FormFactorMatrix& f, const SolveOptions& so, const glm::vec3& lamp,
                          const glm::vec3& panel) {
  std::vector<Patch> lit = patches;
  for (const prt::scene::ScenePrimitive& p : scene.primitives)
    for (uint32_t k = 0; k < p.triangle_count; ++k)
      lit[p.first_triangle + k].emission = glm::dvec3(p.material == "lamp"    ? lamp
                                                      : p.material == "panel" ? panel
                                                                              : glm::vec3(0.f));
  const Solution s = solve_matrix(lit, f, so);
  REQUIRE(s.converged);
  return vertex_radiance(scene, lit, s.radiance);
}

// max |a − b| / max b over every vertex and channel.
double relative_difference(const std::vector<float>& a, const std::vector<float>& b) {
  REQUIRE(a.size() == b.size());
  double worst = 0, scale = 0;
  for (float x : b) scale = std::max(scale, double(x));
  for (std::size_t i = 0; i < a.size(); ++i)
    worst = std::max(worst, std::abs(double(a[i]) - double(b[i])));
  return worst / scale;
}

}  // namespace

TEST_CASE("per-emitter responses recombined with any colours equal a direct solve",
          "[radiosity][emitters]") {
  const prt::scene::Scene room = two_emitter_room();
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  const FormFactorMatrix f = compute_form_factors(patches, caster, FormFactorOptions{});
  SolveOptions so;
  so.tolerance = 1e-10;  // each solve's unshot power; the comparison allows 1e-5 of the peak
  std::vector<EmitterSolveReport> reports;
  const prt::EmitterResponses r = solve_emitter_responses(room, patches, f, so, &reports);
  REQUIRE(r.emitters.size() == 2);
  CHECK(r.emitters[0].name == "lamp");
  CHECK(r.emitters[1].name == "panel");
  CHECK(r.emitters[1].emission == std::array<float, 3>{1.f, 2.f, 4.f});
  CHECK(reports.size() == 2);
  CHECK(r.vertex_count() == room.vertex_count());
  CHECK(r.triangle_count() == room.triangles.size());
  REQUIRE(prt::validate_emitter_responses(r, "room").ok());

  // The stored emissions reproduce the plain solve of the scene as it is.
  const Solution plain = solve_matrix(patches, f, so);
  const std::vector<float> plain_vertex = vertex_radiance(room, patches, plain.radiance);
  std::vector<float> recombined(plain_vertex.size());
  REQUIRE(prt::recombine_emitters(r, *prt::emitter_colors(r, {}), recombined.data()).ok());
  CHECK(relative_difference(recombined, plain_vertex) < 1e-5);

  // Arbitrary colours, including a dark emitter and unequal channels.
  const std::vector<std::pair<glm::vec3, glm::vec3>> cases = {{{3.f, 0.5f, 7.f}, {0.2f, 4.f, 1.f}},
                                                              {{0.f, 0.f, 0.f}, {5.f, 5.f, 0.f}},
                                                              {{1.f, 2.f, 3.f}, {0.f, 0.f, 0.f}}};
  for (const auto& [lamp, panel] : cases) {
    const std::vector<prt::EmitterColor> colors = {{"lamp", {lamp.x, lamp.y, lamp.z}},
                                                   {"panel", {panel.x, panel.y, panel.z}}};
    REQUIRE(prt::recombine_emitters(r, *prt::emitter_colors(r, colors), recombined.data()).ok());
    const std::vector<float> expected = direct(room, patches, f, so, lamp, panel);
    INFO("lamp " << lamp.x << "," << lamp.y << "," << lamp.z);
    CHECK(relative_difference(recombined, expected) < 1e-5);
  }
  // The responses are not interchangeable: each emitter lights the room its own way (so a
  // recombination that mixed them up would fail above).
  double differ = 0;
  const std::size_t v = r.vertex_count();
  for (std::size_t i = 0; i < 3 * v; ++i)
    differ = std::max(differ, double(std::abs(r.responses[i] - r.responses[3 * v + i])));
  CHECK(differ > 0.01);
}

TEST_CASE("emitters are grouped by material and a material emitting unevenly is refused",
          "[radiosity][emitters]") {
  prt::scene::Scene s = two_emitter_room();
  prt::test::append(
      s,
      make_quad({0.6f, 0.05f, 0.99f}, {0, 0.2f, 0}, {0.3f, 0, 0}, 1, 1, glm::vec3(0.3f), "panel2"),
      "panel", {1.f, 2.f, 4.f});
  const std::vector<EmitterGroup> groups = emitter_groups(s);
  REQUIRE(groups.size() == 2);
  CHECK(groups[1].name == "panel");
  CHECK(groups[1].triangles.size() == 4);  // both panels, two triangles each
  s.primitives.back().emission = glm::vec3(2.f);
  CHECK_THROWS_WITH(emitter_groups(s), Catch::Contains("emit differently"));
  s.primitives.back().emission = glm::vec3(0.f);
  s.primitives.back().material = "";
  s.primitives.back().emission = glm::vec3(1.f);
  CHECK(emitter_groups(s).back().name == "<none>");
}
