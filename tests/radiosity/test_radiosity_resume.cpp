// Resuming a radiosity solution: the form-factor cache (round trip, refusals), re-solving after
// an emission or albedo change with the same gather matrix, the partial form-factor update
// after a block moves (against a full recomputation), and thread-count independence.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <catch2/catch.hpp>

#include "fixtures/radiosity/radiosity_fixtures.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/form_factor_update.h"
#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"

using namespace prt::radiosity;
using prt::test::max_relative_difference;
namespace fs = std::filesystem;

namespace {

// A closed-on-five-sides room (open top) with two blocks and a lamp; block A's corner at
// `a_offset` (x, z), block B fixed in the far corner.
prt::scene::Scene room_with_blocks(glm::vec2 a_offset) {
  using prt::scene::make_quad;
  prt::scene::Scene s;
  prt::test::append_open_room_walls(s, 3);
  const glm::vec3 a(a_offset.x, 0.f, a_offset.y);
  prt::test::append(s,
                    prt::scene::make_box(a, a + glm::vec3(0.2f, 0.3f, 0.2f), 1, false,
                                         glm::vec3(0.6f), "block_a"),
                    "white");
  prt::test::append(s,
                    prt::scene::make_box({0.75f, 0, 0.75f}, {0.9f, 0.15f, 0.9f}, 1, false,
                                         glm::vec3(0.6f), "block_b"),
                    "white");
  prt::test::append(
      s, make_quad({0.4f, 0.9f, 0.4f}, {0.2f, 0, 0}, {0, 0, 0.2f}, 1, 1, glm::vec3(0.5f), "lamp"),
      "light", glm::vec3(10.f));
  return s;
}

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(PRT_TEST_OUTPUT_DIR) / "radiosity_resume" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string load_error(const std::string& path, uint64_t key) {
  try {
    load_form_factors(path, key);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

FormFactorOptions ray_options() {
  FormFactorOptions ff;
  ff.method = FormFactorMethod::Rays;
  ff.rays_per_patch = 500;
  return ff;
}

}  // namespace

TEST_CASE("form-factor cache: round trip gives the same matrix and a bit-identical solution",
          "[radiosity][cache]") {
  const prt::scene::Scene room = room_with_blocks({0.2f, 0.2f});
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  const FormFactorOptions ff = ray_options();
  const FormFactorMatrix f = compute_form_factors(patches, caster, ff);
  const fs::path path = scratch("round_trip") / "room.ffm";
  const uint64_t key = form_factor_key(patches, ff);
  save_form_factors(path.string(), f, key);
  REQUIRE(fs::file_size(path) == 104 + 4 * f.f.size());
  CHECK(form_factor_cache_revision(path.string()) == kFormFactorRevision);
  const FormFactorMatrix loaded = load_form_factors(path.string(), key);
  REQUIRE(loaded.size == f.size);
  CHECK(loaded.f == f.f);
  SolveOptions so;
  so.tolerance = 1e-8;
  CHECK(solve_matrix(patches, loaded, so).radiance == solve_matrix(patches, f, so).radiance);
}

TEST_CASE("form-factor cache: another scene, other options, truncation and corruption refused",
          "[radiosity][cache]") {
  const prt::scene::Scene room = room_with_blocks({0.2f, 0.2f});
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  FormFactorOptions ff = ray_options();
  ff.rays_per_patch = 50;
  const FormFactorMatrix f = compute_form_factors(patches, caster, ff);
  const fs::path dir = scratch("refused");
  const std::string path = (dir / "room.ffm").string();
  const uint64_t key = form_factor_key(patches, ff);
  save_form_factors(path, f, key);

  // Keys: another scene (block moved by a thousandth) and other options give other keys.
  const std::vector<Patch> moved = make_patches(room_with_blocks({0.201f, 0.2f}));
  FormFactorOptions more = ff;
  more.rays_per_patch = 51;
  FormFactorOptions other_seed = ff;
  other_seed.seed = 2;
  FormFactorOptions analytic;
  // Another sampler or other emitter rows estimate F differently: a cache of one is refused
  // for the other.
  FormFactorOptions other_sampling = ff;
  other_sampling.sampling =
      ff.sampling == RaySampling::Sobol ? RaySampling::Independent : RaySampling::Sobol;
  FormFactorOptions reciprocal = ff, reciprocal_one = ff;
  reciprocal.emitter_rows = EmitterRows::Reciprocal;
  reciprocal_one.emitter_rows = EmitterRows::Reciprocal;
  reciprocal_one.quadrature_points = 1;
  CHECK(form_factor_key(patches, reciprocal) != form_factor_key(patches, reciprocal_one));
  for (uint64_t other :
       {form_factor_key(moved, ff), form_factor_key(patches, more),
        form_factor_key(patches, other_seed), form_factor_key(patches, analytic),
        form_factor_key(patches, other_sampling), form_factor_key(patches, reciprocal)}) {
    CHECK(other != key);
    const std::string error = load_error(path, other);
    CHECK(error.find(path) == 0);
    CHECK(error.find("another scene or other form-factor options") != std::string::npos);
  }
  // Options the method does not use do not change the key.
  FormFactorOptions unused = ff;
  unused.hemicube_resolution = 32;
  unused.quadrature_points = 1;
  CHECK(form_factor_key(patches, unused) == key);
  // More rays from emitters: part of the key, and so is which patches emit, but not how much.
  FormFactorOptions emitter = ff;
  emitter.emitter_rays_per_patch = 400;
  const uint64_t emitter_key = form_factor_key(patches, emitter);
  CHECK(emitter_key != key);
  std::vector<Patch> brighter = patches, other_emitters = patches;
  for (Patch& p : brighter)
    if (p.emission.x > 0.0) p.emission *= 3.0;
  other_emitters[0].emission = glm::dvec3(1.0);
  CHECK(form_factor_key(brighter, emitter) == emitter_key);
  CHECK(form_factor_key(other_emitters, emitter) != emitter_key);
  CHECK(form_factor_key(other_emitters, ff) == key);  // without emitter rays it does not matter
  // An emitter's row with emitter rays is the row of that many rays.
  const FormFactorMatrix fe = compute_form_factors(patches, caster, emitter);
  FormFactorOptions many = ff;
  many.rays_per_patch = 400;
  for (uint32_t i = 0; i < patches.size(); ++i) {
    std::vector<float> row;
    form_factor_row(patches, caster, i, patches[i].emission.x > 0.0 ? many : ff, &row);
    CHECK(std::equal(row.begin(), row.end(), fe.f.begin() + i * fe.size));
  }

  std::string bytes;
  {
    std::ifstream in(path, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), {});
  }
  const auto write = [&](const std::string& name, const std::string& content) {
    std::ofstream(dir / name, std::ios::binary) << content;
    return (dir / name).string();
  };
  CHECK(load_error(write("short.ffm", bytes.substr(0, bytes.size() - 5)), key).find("truncated") !=
        std::string::npos);
  CHECK(load_error(write("header.ffm", bytes.substr(0, 30)), key).find("truncated") !=
        std::string::npos);
  std::string flipped = bytes;
  flipped[64 + 4 * 17 + 2] ^= 0x10;
  CHECK(load_error(write("flipped.ffm", flipped), key).find("checksum mismatch") !=
        std::string::npos);
  std::string magic = bytes;
  magic[0] = 'X';
  CHECK(load_error(write("magic.ffm", magic), key).find("bad magic") != std::string::npos);
  CHECK(load_error(write("long.ffm", bytes + "x"), key).find("unexpected bytes") !=
        std::string::npos);
  // A cache of an earlier (or a later) revision of the algorithms is refused under any key,
  // with one line naming its revision; its revision is read without the matrix.
  for (uint32_t revision : {1u, kFormFactorRevision + 1}) {
    const std::string other = (dir / ("revision" + std::to_string(revision) + ".ffm")).string();
    save_form_factors(other, f, key, &ff, revision);
    CHECK(form_factor_cache_revision(other) == revision);
    const std::string error = load_error(other, key);
    CHECK(error.find(other + ": form factors of algorithm revision " + std::to_string(revision) +
                     ", this prt computes revision " + std::to_string(kFormFactorRevision)) == 0);
    CHECK(error.find('\n') == std::string::npos);
  }
  // The untouched file still loads.
  CHECK(load_form_factors(path, key).f == f.f);
}

TEST_CASE("re-solving after an emission or albedo change equals a fresh solve",
          "[radiosity][resume]") {
  const prt::scene::Scene room = room_with_blocks({0.2f, 0.2f});
  const prt::scene::RayCaster caster(room);
  std::vector<Patch> patches = make_patches(room);
  const FormFactorOptions ff = ray_options();
  const FormFactorMatrix f = compute_form_factors(patches, caster, ff);
  const GatherMatrix k = make_gather_matrix(patches, f);
  SolveOptions so;
  so.tolerance = 1e-9;
  const Solution before = solve_matrix(patches, k, so);
  // New lamp colour and a darker floor: K is reused; the fresh solve recomputes F and K.
  for (Patch& p : patches) {
    if (p.emission.x > 0.0) p.emission = glm::dvec3(3.0, 6.0, 9.0);
    if (std::abs(p.normal.y - 1.0) < 1e-9 && p.centroid.y < 1e-6) p.albedo = glm::dvec3(0.3);
  }
  const Solution resolved = solve_matrix(patches, k, so);
  const Solution fresh = solve_matrix(patches, compute_form_factors(patches, caster, ff), so);
  REQUIRE(resolved.converged);
  REQUIRE(fresh.converged);
  // Same F (per-row seeds) and the same K: the same iterates. The tolerance of the brief
  // ("equal to solver tolerance") is met with room to spare: the two agree exactly.
  CHECK(max_relative_difference(resolved.radiance, fresh.radiance) <= 1e-9);
  CHECK(resolved.radiance == fresh.radiance);
  CHECK(max_relative_difference(resolved.radiance, before.radiance) > 0.1);  // it did change
  CHECK(resolved.energy.balance_error() < 1e-9);
}

TEST_CASE("after a block moves, the partial form-factor update equals a full recomputation",
          "[radiosity][resume]") {
  const prt::scene::Scene before_scene = room_with_blocks({0.15f, 0.2f});
  const prt::scene::Scene after_scene = room_with_blocks({0.3f, 0.25f});
  const prt::scene::RayCaster before_caster(before_scene), after_caster(after_scene);
  const std::vector<Patch> before = make_patches(before_scene);
  const std::vector<Patch> after = make_patches(after_scene);
  REQUIRE(before.size() == after.size());
  FormFactorOptions hemicube;
  hemicube.method = FormFactorMethod::Hemicube;
  hemicube.hemicube_resolution = 16;
  for (const FormFactorOptions& ff : {FormFactorOptions{}, ray_options(), hemicube}) {
    INFO("method " << int(ff.method));
    FormFactorMatrix f = compute_form_factors(before, before_caster, ff);
    const FormFactorMatrix full = compute_form_factors(after, after_caster, ff);
    REQUIRE(f.f != full.f);  // the move changed something
    const FormFactorUpdate u = update_form_factors(before, after, after_caster, ff, &f);
    CHECK(u.moved_patches == 12);  // block A: 6 faces × 2 triangles
    CHECK(f.f == full.f);
    INFO("rows " << u.rows_recomputed << ", entries " << u.entries_recomputed << " of "
                 << after.size());
    // Rays and analytic did less than a full recomputation: rows of patches facing away from
    // the block (analytic: most entries) were kept. The hemicube recomputes everything.
    if (ff.method == FormFactorMethod::Hemicube)  // pairs combine both hemicubes: all rows
      CHECK(u.rows_recomputed == after.size());
    else
      CHECK(u.rows_recomputed < after.size());
    if (ff.method == FormFactorMethod::Analytic)
      CHECK(u.rows_recomputed * after.size() + u.entries_recomputed <
            after.size() * after.size() / 2);
  }
}

TEST_CASE("form factors and Gauss-Seidel do not depend on the thread count",
          "[radiosity][solver][threads]") {
  const prt::scene::Scene room = room_with_blocks({0.2f, 0.2f});
  const prt::scene::RayCaster caster(room);
  const std::vector<Patch> patches = make_patches(room);
  SolveOptions so;
  so.tolerance = 1e-8;
  std::vector<FormFactorMatrix> many;
  std::vector<Solution> many_solutions;
  for (const FormFactorOptions& ff : {FormFactorOptions{}, ray_options()}) {
    many.push_back(compute_form_factors(patches, caster, ff));
    many_solutions.push_back(solve_matrix(patches, many.back(), so));
  }
  tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
  std::size_t m = 0;
  for (const FormFactorOptions& ff : {FormFactorOptions{}, ray_options()}) {
    const FormFactorMatrix one = compute_form_factors(patches, caster, ff);
    CHECK(one.f == many[m].f);
    const Solution s = solve_matrix(patches, one, so);
    CHECK(s.radiance == many_solutions[m].radiance);
    CHECK(s.energy.absorbed == many_solutions[m].energy.absorbed);
    ++m;
  }
}
