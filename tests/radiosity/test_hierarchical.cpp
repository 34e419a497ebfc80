// Hierarchical radiosity (radiosity/hierarchical_solver.h): the closed box with uniform emission
// (L = E / (1 − ρ) exactly), agreement with the dense analytic solve on an open room, per-emitter
// responses on the same links, the solve of a scene file with --move, the cache refused, the
// memory budget, and the link count growing about linearly with the patches.
#include <algorithm>
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "fixtures/radiosity/radiosity_fixtures.h"
#include "radiosity/form_factors.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/subdivide.h"

using namespace prt::radiosity;

namespace {

// Relative RMS of a against b over the non-emitting patches, all channels.
double relative_rms(const std::vector<glm::dvec3>& a, const std::vector<glm::dvec3>& b,
                    const std::vector<Patch>& patches) {
  double num = 0.0, den = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (patches[i].emission != glm::dvec3(0.0)) continue;
    for (int c = 0; c < 3; ++c) {
      num += (a[i][c] - b[i][c]) * (a[i][c] - b[i][c]);
      den += b[i][c] * b[i][c];
    }
  }
  return std::sqrt(num / den);
}

}  // namespace

TEST_CASE("hierarchical: closed box with uniform emission, L = E / (1 - rho) on every patch",
          "[radiosity][hierarchical]") {
  // Every patch of a closed box sees the whole enclosure (Σ_j F_ij = 1), so with E and ρ the
  // same everywhere L = E + ρL, L = E/(1 − ρ), whatever the form factors' distribution: the test
  // checks that the links of every patch (its own and its ancestors') carry exactly the light
  // of the enclosure, neither more nor less.
  const double rho = 0.5;
  prt::scene::Scene box =
      prt::scene::make_box({0, 0, 0}, {1, 1, 1}, 12, /*normals_inward=*/true, glm::vec3(float(rho)));
  const prt::scene::RayCaster caster(box);
  std::vector<Patch> patches = make_patches(box);
  for (Patch& p : patches) p.emission = glm::dvec3(1.0);
  HierarchicalOptions o;
  o.solve.tolerance = 1e-7;
  const HierarchicalSolution s = solve_hierarchical(patches, caster, o);
  REQUIRE(s.solution.converged);
  double worst = 0.0, mean = 0.0;
  for (const glm::dvec3& l : s.solution.radiance) {
    worst = std::max(worst, std::abs(l.x - 2.0) / 2.0);
    mean += l.x / 2.0 / double(patches.size());
  }
  INFO("patches " << patches.size() << ", links " << s.stats.links << ", worst " << worst
                  << ", mean " << mean);
  CHECK(worst < 1e-3);
}

TEST_CASE("hierarchical: open room agrees with the dense analytic solve", "[radiosity][hierarchical]") {
  const prt::scene::Scene room = prt::scene::subdivide_to_edge_length(prt::test::open_room("lamp"), 0.06);
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  SolveOptions so;
  so.tolerance = 1e-6;
  const Solution dense = solve_matrix(patches, compute_form_factors(patches, caster, {}), so);
  HierarchicalOptions o;
  o.solve = so;
  if (getenv("HEPS")) o.links.epsilon = atof(getenv("HEPS"));
  const HierarchicalSolution h = solve_hierarchical(patches, caster, o);
  const double rms = relative_rms(h.solution.radiance, dense.radiance, patches);
  const auto share = [](const EnergyAccount& e) { return (e.absorbed.x + e.absorbed.y + e.absorbed.z) / (e.emitted.x + e.emitted.y + e.emitted.z); };
  INFO("patches " << patches.size() << ", links " << h.stats.links << " exact " << h.stats.exact_links << " (dense " << patches.size() * patches.size() << "), rms " << rms << ", absorbed " << share(h.solution.energy) << " vs " << share(dense.energy));
  CHECK(rms < 0.01);
}
TEST_CASE("hdebug", "[.hdebug]") {
  const prt::scene::Scene room = prt::scene::subdivide_to_edge_length(prt::test::open_room("lamp"), 0.12);
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  const FormFactorMatrix f = compute_form_factors(patches, caster, {});
  HierarchicalOptions o;
  o.links.epsilon = 1e-8;
  const HierarchicalSolution h = solve_hierarchical(patches, caster, o);
  double worst = 0; std::size_t bad = 0, exact = 0;
  std::vector<double> hsum(patches.size(), 0.0), dsum(patches.size(), 0.0);
  for (const Link& l : h.links) {
    if (!l.exact()) continue;
    ++exact;
    const uint32_t r = h.hierarchy.order[h.hierarchy.nodes[l.receiver].first];
    const uint32_t s = h.hierarchy.order[h.hierarchy.nodes[l.source_node()].first];
    const double d = patches[s].area * f.at(s, r);
    hsum[r] += l.g;
    if (std::abs(d - l.g) > 1e-6 * patches[s].area) { ++bad; worst = std::max(worst, std::abs(d - l.g) / patches[s].area); }
  }
  for (std::size_t s = 0; s < patches.size(); ++s) for (std::size_t r = 0; r < patches.size(); ++r) dsum[r] += patches[s].area * f.at(s, r);
  double wr = 0; std::size_t wi = 0;
  for (std::size_t r = 0; r < patches.size(); ++r) { double e = std::abs(hsum[r] - dsum[r]) / patches[r].area; if (e > wr) wr = e, wi = r; }
  WARN("exact " << exact << " bad " << bad << " worst " << worst << " patches " << patches.size() << " links " << h.links.size() << " worst receiver sum diff " << wr << " at " << wi << " hs " << hsum[wi]/patches[wi].area << " ds " << dsum[wi]/patches[wi].area << " centroid " << patches[wi].centroid.x << "," << patches[wi].centroid.y << "," << patches[wi].centroid.z);
}
TEST_CASE("hdebug2", "[.hdebug]") {
  prt::scene::Scene s;
  prt::test::append_open_room_walls(s, 4);
  if (getenv("HBLOCK")) prt::test::append(s, prt::scene::make_box({0.3f, 0, 0.4f}, {0.6f, 0.4f, 0.7f}, 1, false, glm::vec3(0.6f), "block"), "white");
  prt::test::append(s, prt::scene::make_quad({0.35f, 0.9f, 0.35f}, {0.3f, 0, 0}, {0, 0, 0.3f}, 2, 2, glm::vec3(0.5f), "lamp"), "lamp", glm::vec3(10.f));
  const prt::scene::Scene room = prt::scene::subdivide_to_edge_length(s, 0.06);
  const prt::scene::RayCaster caster(room);
  std::vector<Patch> patches = make_patches(room);
  if (getenv("HDIRECT")) for (Patch& p : patches) p.albedo = glm::dvec3(0.01);
  if (getenv("HWALLEMIT")) for (Patch& p : patches) if (p.centroid.x < 1e-6) p.emission = glm::dvec3(1.0);
  SolveOptions so;
  so.tolerance = 1e-6;
  const Solution dense = solve_matrix(patches, compute_form_factors(patches, caster, {}), so);
  HierarchicalOptions o;
  o.solve = so;
  if (getenv("HEPS")) o.links.epsilon = atof(getenv("HEPS"));
  if (getenv("HRAYS")) o.links.visibility_rays = atoi(getenv("HRAYS"));
  const HierarchicalSolution h = solve_hierarchical(patches, caster, o);
  std::size_t wi = 0; double we = 0;
  for (std::size_t i = 0; i < patches.size(); ++i) { if (patches[i].emission.x > 0) continue; double e = std::abs(h.solution.radiance[i].x - dense.radiance[i].x) / dense.radiance[i].x; if (e > we) we = e, wi = i; }
  WARN("worst " << we << " at " << patches[wi].centroid.x << "," << patches[wi].centroid.y << "," << patches[wi].centroid.z << " n " << patches[wi].normal.x << "," << patches[wi].normal.y << "," << patches[wi].normal.z << " h " << h.solution.radiance[wi].x << " d " << dense.radiance[wi].x);
  for (int wall = 0; wall < 4; ++wall) {
    double sh = 0, sd = 0, sq = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      const Patch& p = patches[i];
      const int w = p.normal.y > 0.5 ? 0 : p.normal.x > 0.5 ? 1 : p.normal.x < -0.5 ? 2 : p.normal.z < -0.5 ? 3 : -1;
      if (w != wall || p.emission.x > 0) continue;
      sh += p.area * h.solution.radiance[i].x; sd += p.area * dense.radiance[i].x; sq += p.area * std::pow(h.solution.radiance[i].x - dense.radiance[i].x, 2);
    }
    WARN("wall " << wall << " mean ratio " << sh / sd << " rms abs " << std::sqrt(sq) << " mean " << sd);
  }
  WARN("patches " << patches.size() << " links " << h.stats.links << " exact " << h.stats.exact_links << " rms " << relative_rms(h.solution.radiance, dense.radiance, patches));
}
