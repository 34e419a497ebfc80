// The solve of `prt radiosity` from a scene file (radiosity/scene_solve.h): the same vertex
// radiance as its steps run by hand, the patch scene handed to the caller before any ray, its
// refusals before anything is written, and the files it writes.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "numerics/hash.h"
#include "prt/formats/crc32c.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "radiosity/scene_solve.h"
#include "radiosity/solver.h"
#include "scene/material_assignment.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

using namespace prt::radiosity;
namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(PRT_TEST_OUTPUT_DIR) / "scene_solve" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string slurp_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A folder made read-only (0555) for the guard's life, writable again after (so that a failed
// check does not leave a folder the next run cannot clear).
struct ReadOnlyFolder {
  explicit ReadOnlyFolder(const fs::path& p) : path(p) { fs::permissions(path, fs::perms(0555)); }
  ~ReadOnlyFolder() { fs::permissions(path, fs::perms(0755)); }
  fs::path path;
};

// A room open at the front (z = 0), 1 unit wide: white walls, a lamp under the ceiling
// (material `lamp`, Ke 5) and a panel on the back wall (material `panel`, no emission).
std::string write_room(const fs::path& dir) {
  std::ofstream(dir / "room.mtl") << "newmtl white\nKd 0.7 0.6 0.5\n"
                                     "newmtl lamp\nKd 0.5 0.5 0.5\nKe 5 5 5\n"
                                     "newmtl panel\nKd 0.3 0.3 0.3\n";
  std::ofstream(dir / "room.obj")
      << "mtllib room.mtl\n"
         "v 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nv 0 1 0\nv 1 1 0\nv 1 1 1\nv 0 1 1\n"
         "v 0.4 0.99 0.4\nv 0.6 0.99 0.4\nv 0.6 0.99 0.6\nv 0.4 0.99 0.6\n"
         "v 0.2 0.1 0.99\nv 0.2 0.3 0.99\nv 0.6 0.3 0.99\nv 0.6 0.1 0.99\n"
         "o walls\nusemtl white\n"
         "f 1 4 3 2\nf 5 6 7 8\nf 1 5 8 4\nf 2 3 7 6\nf 4 8 7 3\n"
         "o lamp\nusemtl lamp\nf 9 10 11 12\n"
         "o panel\nusemtl panel\nf 13 14 15 16\n";
  return (dir / "room.obj").string();
}

// A request to solve write_room's room, written in `dir`, subdivided to `max_edge`.
SceneSolveRequest room_request(const fs::path& dir, double max_edge) {
  SceneSolveRequest request;
  request.scene_path = write_room(dir);
  request.max_edge = max_edge;
  return request;
}

// The patches solve_scene makes of `request` (no moves): the scene loaded, its materials
// overridden and subdivided.
std::vector<Patch> patches_of(const SceneSolveRequest& request) {
  prt::scene::Scene scene = prt::scene::load_scene(request.scene_path);
  prt::scene::apply_emission(scene, request.emission);
  prt::scene::apply_albedo(scene, request.albedo);
  if (request.max_edge) scene = prt::scene::subdivide_to_edge_length(scene, *request.max_edge);
  return make_patches(scene);
}

// The key of ray form factors with Sobol' samples and reciprocal emitter rows as docs/FORMAT.md
// ("Key") gives it: without the revision word (`revision1`), the key a prt before revisions
// were recorded computed; with it, form_factor_key's.
uint64_t ray_reciprocal_key(const std::vector<Patch>& patches, const FormFactorOptions& o,
                            bool revision1) {
  prt::numerics::WordHash h;
  h.add_u64(patches.size());
  for (const Patch& p : patches)
    for (const glm::dvec3& c : p.corners)
      for (int k = 0; k < 3; ++k) h.add_float(static_cast<float>(c[k]));
  h.add_word(1);  // rays
  h.add_word(static_cast<uint32_t>(o.rays_per_patch));
  h.add_u64(o.seed);
  h.add_word(static_cast<uint32_t>(o.emitter_rays_per_patch));
  for (std::size_t i = 0; i < patches.size(); ++i)
    if (patches[i].emission != glm::dvec3(0.0)) h.add_u64(i);
  h.add_word(0x50000000u + 1);  // Sobol'
  h.add_word(0x45000000u + 1);  // reciprocal
  h.add_word(static_cast<uint32_t>(o.quadrature_points));
  if (!revision1) h.add_word(0x52000000u + kFormFactorRevision);
  return h.finish();
}

// A version-2 cache (revision 1, the layout before revisions were recorded) of N × N factors
// all `value`, under `key`: what an earlier prt wrote and would load again.
void write_version2_cache(const std::string& path, uint64_t key, uint64_t n, float value) {
  std::vector<unsigned char> bytes(96 + 4 * n * n, 0);
  const char magic[8] = {'P', 'R', 'T', 'F', 'F', 'M', '1', '\n'};
  std::memcpy(bytes.data(), magic, 8);
  const uint32_t version = 2, header = 96, method = 1, flags = 0;
  const uint64_t size = bytes.size();
  std::memcpy(&bytes[8], &version, 4);
  std::memcpy(&bytes[12], &header, 4);
  std::memcpy(&bytes[16], &key, 8);
  std::memcpy(&bytes[24], &n, 8);
  std::memcpy(&bytes[32], &size, 8);
  std::memcpy(&bytes[40], &method, 4);
  std::memcpy(&bytes[44], &flags, 4);
  for (uint64_t k = 0; k < n * n; ++k) std::memcpy(&bytes[96 + 4 * k], &value, 4);
  const uint32_t crc = prt::crc32c(bytes.data(), bytes.size());
  std::memcpy(&bytes[48], &crc, 4);
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
}

}  // namespace

TEST_CASE("solve_scene equals its steps run by hand and hands the patch scene over first",
          "[radiosity][scene-solve]") {
  const fs::path dir = scratch("by_hand");
  SceneSolveRequest request;
  request.scene_path = write_room(dir);
  request.emission = {prt::scene::parse_material_colour("--emission", "panel=0.5,1,2")};
  request.albedo = {prt::scene::parse_material_colour("--albedo", "white=0.6")};
  request.max_edge = 0.3;
  request.solve.tolerance = 1e-6;
  std::size_t calls = 0, triangles_seen = 0;
  const SceneSolution s = solve_scene(request, [&](const prt::scene::Scene& scene) {
    ++calls;
    triangles_seen = scene.triangles.size();
  });
  CHECK(calls == 1);
  CHECK(triangles_seen == s.scene.triangles.size());
  CHECK(s.patches == s.scene.triangles.size());
  CHECK(s.solution.radiance.empty());  // emptied: the vertex radiance is the result
  CHECK(s.solution.converged);
  CHECK(s.files_written.empty());
  CHECK(s.cache == SceneSolution::Cache::None);

  // The same steps by hand: deterministic code on the same input, so equal bit for bit.
  prt::scene::Scene scene = prt::scene::load_scene(request.scene_path);
  prt::scene::apply_emission(scene, request.emission);
  prt::scene::apply_albedo(scene, request.albedo);
  scene = prt::scene::subdivide_to_edge_length(scene, *request.max_edge);
  const std::vector<Patch> patches = make_patches(scene);
  const prt::scene::RayCaster caster(scene);
  const Solution solution = solve_matrix(
      patches, compute_form_factors(patches, caster, request.form_factors), request.solve);
  CHECK(s.vertex_radiance == vertex_radiance(scene, patches, solution.display_radiance));
  CHECK(s.solution.iterations == solution.iterations);
  REQUIRE(s.scene.vertex_count() == scene.vertex_count());
  CHECK(s.vertex_radiance.size() == 3 * scene.vertex_count());
}

TEST_CASE("solve_scene refuses before writing: a bad request, a caller's check, a bad scene",
          "[radiosity][scene-solve]") {
  const fs::path dir = scratch("refused");
  SceneSolveRequest request;
  request.scene_path = write_room(dir);
  request.form_factor_cache = (dir / "cache.ff").string();
  request.per_emitter_path = (dir / "responses.prte").string();
  // The caller's own check fails: nothing computed, nothing written.
  CHECK_THROWS_WITH(
      solve_scene(request, [](const prt::scene::Scene&) { throw std::runtime_error("camera"); }),
      "camera");
  CHECK_FALSE(fs::exists(request.form_factor_cache));
  CHECK_FALSE(fs::exists(request.per_emitter_path));
  // Refused by check_scene_solve, before the scene is read.
  SceneSolveRequest bad = request;
  bad.per_emitter_path = (dir / "responses.csv").string();
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("unsupported output type '.csv'"));
  bad = request;
  bad.solve.solver = SolverKind::Progressive;
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("--per-emitter needs a full-matrix solver"));
  bad = request;
  bad.refinement = PatchRefinementOptions{};
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("--adaptive: not with --form-factor-cache"));
  bad = request;
  bad.form_factor_cache.clear();
  bad.per_emitter_path.clear();
  bad.refinement = PatchRefinementOptions{};
  bad.form_factors.method = FormFactorMethod::Hemicube;
  bad.solve.solver = SolverKind::Progressive;
  CHECK_THROWS_WITH(check_scene_solve(bad, {}),
                    Catch::Contains("--adaptive with --form-factors hemicube needs --solver"));
  bad.solve.solver = SolverKind::Jacobi;
  CHECK_NOTHROW(check_scene_solve(bad, {}));
  CHECK_THROWS_WITH(check_scene_solve(request, {request.form_factor_cache}),
                    Catch::Contains("may not overwrite the form-factor cache"));
  bad = request;
  bad.per_emitter_path = request.scene_path;
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("unsupported output type '.obj'"));
  bad.per_emitter_path = (dir / "room.prte").string();
  bad.moves = {parse_object_move("nosuch=0,1,0")};
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("--move nosuch: no object of"));
  bad = request;
  bad.emission = {prt::scene::parse_material_colour("--emission", "lamp=0")};
  CHECK_THROWS_WITH(solve_scene(bad), Catch::Contains("nothing emits light"));
  // Only the scene files are there.
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    CHECK((name == "room.obj" || name == "room.mtl"));
  }
}

TEST_CASE("solve_scene writes the cache, then loads it, and the per-emitter responses",
          "[radiosity][scene-solve]") {
  const fs::path dir = scratch("files");
  SceneSolveRequest request = room_request(dir, 0.4);
  request.form_factor_cache = (dir / "cache.ff").string();
  request.per_emitter_path = (dir / "responses.prte").string();
  const SceneSolution saved = solve_scene(request);
  CHECK(saved.cache == SceneSolution::Cache::Saved);
  CHECK(saved.files_written ==
        std::vector<std::string>{request.form_factor_cache, request.per_emitter_path});
  REQUIRE(saved.emitter_reports.size() == 1);
  CHECK(saved.emitter_reports[0].name == "lamp");
  const SceneSolution loaded = solve_scene(request);
  CHECK(loaded.cache == SceneSolution::Cache::Loaded);
  CHECK(loaded.form_factor_seconds == 0.0);  // nothing computed
  CHECK(loaded.vertex_radiance == saved.vertex_radiance);
}

// Reciprocal emitter rows changed (revision 2: checked against the emitter's rays), so a cache
// an earlier prt saved for the same patches and options, under the key it computed, holds other
// rows. It must be recomputed and saved over, with a notice, not loaded: the radiance then
// equals a run without a cache, and the file is a current one that the next run loads. (The
// stale rows here are all 1/(2N), far from any room's F, so loading them would show.)
TEST_CASE("solve_scene recomputes a cache of an earlier algorithm revision and saves over it",
          "[radiosity][scene-solve][cache]") {
  const fs::path dir = scratch("stale_cache");
  SceneSolveRequest request = room_request(dir, 0.4);
  request.solve.tolerance = 1e-8;
  request.form_factors.method = FormFactorMethod::Rays;
  request.form_factors.rays_per_patch = 64;
  request.form_factors.emitter_rows = EmitterRows::Reciprocal;
  const std::vector<Patch> patches = patches_of(request);
  const uint64_t n = patches.size();
  // The key replayed here is form_factor_key's, so the one without the revision word is the
  // earlier prt's.
  REQUIRE(ray_reciprocal_key(patches, request.form_factors, false) ==
          form_factor_key(patches, request.form_factors));
  const uint64_t old_key = ray_reciprocal_key(patches, request.form_factors, true);
  CHECK(old_key != form_factor_key(patches, request.form_factors));
  const SceneSolution fresh = solve_scene(request);  // no cache

  request.form_factor_cache = (dir / "room.ffm").string();
  write_version2_cache(request.form_factor_cache, old_key, n, 0.5f / float(n));
  const FormFactorCacheInfo stale = read_form_factor_cache_info(request.form_factor_cache);
  REQUIRE(stale.key == old_key);  // a well-formed file an earlier prt would have loaded
  REQUIRE(stale.revision == 1);
  REQUIRE(stale.patches == n);

  const SceneSolution recomputed = solve_scene(request);
  CHECK(recomputed.cache == SceneSolution::Cache::Saved);
  CHECK(recomputed.cache_notice.find(request.form_factor_cache +
                                     ": form factors of algorithm "
                                     "revision 1, earlier than this prt's 2") == 0);
  CHECK(recomputed.cache_notice.find('\n') == std::string::npos);
  CHECK(recomputed.files_written == std::vector<std::string>{request.form_factor_cache});
  CHECK(recomputed.vertex_radiance == fresh.vertex_radiance);
  const FormFactorCacheInfo saved = read_form_factor_cache_info(request.form_factor_cache);
  CHECK(saved.revision == kFormFactorRevision);
  CHECK(saved.key == form_factor_key(patches, request.form_factors));

  const SceneSolution loaded = solve_scene(request);
  CHECK(loaded.cache == SceneSolution::Cache::Loaded);
  CHECK(loaded.cache_notice.empty());
  CHECK(loaded.vertex_radiance == fresh.vertex_radiance);
}

// A stale cache whose folder cannot be written (a shared, read-only cache folder): the run goes
// on with the recomputed factors (radiance equal to a run without a cache), its notice names the
// file and why it could not be updated, and the old file is left as it was. The folder is
// read-only (0555) and the cache's name so long that its temporary's name passes NAME_MAX, so
// that the save fails for root too (tests may run as root, for whom 0555 does not stop writes).
// A cache that was absent is an output: its failed save still fails the run (scene_solve.h).
TEST_CASE("solve_scene goes on when a stale cache cannot be updated, with a notice",
          "[radiosity][scene-solve][cache]") {
  const fs::path dir = scratch("stale_read_only");
  SceneSolveRequest request = room_request(dir, 0.4);
  request.form_factors.method = FormFactorMethod::Rays;
  request.form_factors.rays_per_patch = 64;
  request.form_factors.emitter_rows = EmitterRows::Reciprocal;
  const std::vector<Patch> patches = patches_of(request);
  const uint64_t n = patches.size();
  const uint64_t old_key = ray_reciprocal_key(patches, request.form_factors, true);
  const SceneSolution fresh = solve_scene(request);  // no cache

  const fs::path shared = dir / "shared";
  fs::create_directories(shared);
  request.form_factor_cache = (shared / (std::string(246, 'c') + ".ffm")).string();
  write_version2_cache(request.form_factor_cache, old_key, n, 0.5f / float(n));
  const std::string before = slurp_bytes(request.form_factor_cache);
  SceneSolution recomputed;
  {
    const ReadOnlyFolder read_only(shared);
    REQUIRE_NOTHROW(recomputed = solve_scene(request));
  }
  CHECK(recomputed.cache == SceneSolution::Cache::None);
  CHECK(recomputed.files_written.empty());
  CHECK(recomputed.vertex_radiance == fresh.vertex_radiance);
  INFO(recomputed.cache_notice);
  CHECK(recomputed.cache_notice.find(request.form_factor_cache +
                                     ": form factors of algorithm revision 1, earlier than this "
                                     "prt's 2: recomputed; the cache could not be updated (" +
                                     request.form_factor_cache + ": cannot create ") == 0);
  CHECK(recomputed.cache_notice.find('\n') == std::string::npos);
  CHECK(slurp_bytes(request.form_factor_cache) == before);
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(shared)) files += e.is_regular_file();
  CHECK(files == 1);  // no temporary left

  // Absent, in the same folder: an output not written, so the run fails naming it.
  request.form_factor_cache = (shared / (std::string(246, 'd') + ".ffm")).string();
  {
    const ReadOnlyFolder read_only(shared);
    CHECK_THROWS_WITH(solve_scene(request),
                      Catch::Contains(request.form_factor_cache + ": cannot create "));
  }
  CHECK_FALSE(fs::exists(request.form_factor_cache));
}

TEST_CASE("the default form factors: analytic up to the patch limit, rays above",
          "[radiosity][scene-solve][form-factor-choice]") {
  FormFactorOptions given;
  given.seed = 7;
  given.quadrature_points = 1;
  given.rays_per_patch = 3;  // the choice sets its own ray count
  given.emitter_rows = EmitterRows::Rays;
  const FormFactorChoice small = choose_form_factors(kAnalyticPatchLimit, given);
  CHECK(small.options.method == FormFactorMethod::Analytic);
  CHECK(small.options.quadrature_points == 3);
  CHECK(small.reason.rfind("form factors: analytic (", 0) == 0);
  CHECK(small.reason.find('\n') == std::string::npos);
  const FormFactorChoice large = choose_form_factors(kAnalyticPatchLimit + 1, given);
  CHECK(large.options.method == FormFactorMethod::Rays);
  CHECK(large.options.rays_per_patch == kDefaultRaysPerPatch);
  CHECK(large.options.emitter_rays_per_patch == 0);
  CHECK(large.options.sampling == RaySampling::Sobol);
  CHECK(large.options.emitter_rows == EmitterRows::Reciprocal);
  CHECK(large.options.seed == 7);  // what the choice does not decide is kept
  CHECK(large.reason.rfind("form factors: rays, 1024 per patch (1501 patches", 0) == 0);
  CHECK(choose_form_factors(1, given).options.method == FormFactorMethod::Analytic);
  CHECK(choose_form_factors(kMaxPatches, given).options.method == FormFactorMethod::Rays);
}

TEST_CASE("the default above the patch limit stays within its stated error of analytic",
          "[radiosity][scene-solve][form-factor-choice]") {
  // The room of write_room at max edge 0.11: more patches than kAnalyticPatchLimit, so the
  // default is rays; analytic on the same patches is still cheap here (a few CPU seconds).
  const fs::path dir = scratch("choice");
  SceneSolveRequest request = room_request(dir, 0.11);
  request.choose_method = true;
  request.solve.tolerance = 1e-6;
  const SceneSolution chosen = solve_scene(request);
  INFO(chosen.form_factor_choice);
  REQUIRE(chosen.patches > kAnalyticPatchLimit);
  CHECK(chosen.form_factor_choice.rfind("form factors: rays", 0) == 0);
  request.choose_method = false;
  request.form_factors.method = FormFactorMethod::Analytic;
  const SceneSolution analytic = solve_scene(request);
  CHECK(analytic.form_factor_choice.empty());
  REQUIRE(analytic.vertex_radiance.size() == chosen.vertex_radiance.size());
  // Relative RMS over every vertex and channel but the lamp's (radiance 5 and more), as
  // scripts/radiosity_compare.py --exclude-above 2.5 computes it.
  double difference = 0.0, reference = 0.0;
  for (std::size_t v = 0; v < analytic.vertex_radiance.size(); v += 3) {
    if (analytic.vertex_radiance[v] > 2.5f) continue;
    for (std::size_t c = v; c < v + 3; ++c) {
      const double d = double(chosen.vertex_radiance[c]) - analytic.vertex_radiance[c];
      difference += d * d;
      reference += double(analytic.vertex_radiance[c]) * analytic.vertex_radiance[c];
    }
  }
  const double error = std::sqrt(difference / reference);
  INFO(chosen.patches << " patches: rays against analytic, relative RMS " << error);
  CHECK(error <= kDefaultRaysError);
  CHECK(error > 1e-4);  // they are different methods: a zero would mean analytic twice
}
