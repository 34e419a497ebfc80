#include "relight/radiosity_pipeline.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "prt/emitters/emitter_responses.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/patches.h"
#include "relight/camera.h"
#include "relight/relight_pipeline.h"
#include "scene/glb_writer.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace prt::relight {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string extension_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_output(const std::string& path, const std::string& input,
                  const std::vector<std::string>& extensions) {
  if (path.empty()) return;
  const std::string ext = extension_of(path);
  bool known = extensions.empty();
  for (const std::string& e : extensions) known = known || ext == e;
  if (!known) throw std::runtime_error(path + ": unsupported output type '" + ext + "'");
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(path + ": directory " + parent.string() + " does not exist");
  std::error_code ec;
  if (std::filesystem::equivalent(path, input, ec))
    throw std::runtime_error(path + ": an output may not overwrite the input scene");
}

void check_request(const RadiosityRequest& r) {
  if (r.output_path.empty() && r.vertex_colors_path.empty() && r.csv_path.empty() &&
      r.per_emitter_path.empty())
    throw std::runtime_error(
        "nothing to write: give -o IMAGE, --vertex-colors, --csv or --per-emitter");
  check_output(r.per_emitter_path, r.scene_path, {".prte"});
  if (!r.per_emitter_path.empty() && r.solve.solver == radiosity::SolverKind::Progressive)
    throw std::invalid_argument(
        "--per-emitter needs a full-matrix solver (--solver gauss-seidel or jacobi)");
  check_output(r.output_path, r.scene_path, {".exr", ".hdr", ".png"});
  check_output(r.vertex_colors_path, r.scene_path, {".glb"});
  check_output(r.csv_path, r.scene_path, {});
  if (r.max_edge && !(*r.max_edge > 0.0 && std::isfinite(*r.max_edge)))
    throw std::invalid_argument("--max-edge " + std::to_string(*r.max_edge) +
                                ": the target edge length must be a finite positive number");
  if (!r.form_factor_cache.empty()) {
    check_output(r.form_factor_cache, r.scene_path, {});
    if (r.solve.solver == radiosity::SolverKind::Progressive)
      throw std::invalid_argument("--form-factor-cache " + r.form_factor_cache +
                                  ": needs a full-matrix solver (gauss-seidel or jacobi)");
    for (const std::string& out : {r.output_path, r.vertex_colors_path, r.csv_path}) {
      std::error_code ec;
      if (!out.empty() &&
          (out == r.form_factor_cache || std::filesystem::equivalent(out, r.form_factor_cache, ec)))
        throw std::invalid_argument(out + ": an output may not overwrite the form-factor cache");
    }
  }
  if (r.adaptive) {
    const char* other = !r.form_factor_cache.empty() ? "--form-factor-cache"
                        : !r.moves.empty()           ? "--move"
                        : !r.per_emitter_path.empty() ? "--per-emitter"
                                                      : nullptr;
    if (other)
      throw std::invalid_argument(std::string("--adaptive: not with ") + other +
                                  " (the patches change from pass to pass)");
  }
  if (!(r.solve.tolerance > 0.0 && r.solve.tolerance < 1.0))
    throw std::invalid_argument("--tolerance " + std::to_string(r.solve.tolerance) +
                                ": must be in (0, 1)");
}

void apply_moves(scene::Scene& scene, const RadiosityRequest& r) {
  for (const ObjectMove& move : r.moves) {
    bool found = false;
    std::string names;
    for (const scene::ScenePrimitive& p : scene.primitives) {
      const std::string mesh = p.name.substr(0, p.name.find('/'));
      if (names.size() < 200) names += (names.empty() ? "" : ", ") + p.name;
      if (p.name != move.object && mesh != move.object) continue;
      found = true;
      for (uint32_t v = 0; v < p.vertex_count; ++v)
        scene.positions[p.first_vertex + v] += glm::vec3(move.offset);
    }
    if (!found)
      throw std::invalid_argument("--move " + move.object + ": no object of " + r.scene_path +
                                  " has this name (objects: " + names + ")");
  }
}

// Loads the scene and applies and checks its materials; throws when nothing emits. With
// `moved`, the objects of --move are translated before subdivision.
scene::Scene prepare_scene(const RadiosityRequest& r, bool moved) {
  scene::Scene scene = scene::load_scene(r.scene_path);
  if (moved) apply_moves(scene, r);
  radiosity::apply_emission(scene, r.emission);
  radiosity::apply_albedo(scene, r.albedo);
  radiosity::check_materials(scene);
  bool emits = false;
  for (const scene::ScenePrimitive& p : scene.primitives)
    emits = emits || (p.triangle_count > 0 && p.emission != glm::vec3(0.f));
  if (!emits)
    throw std::runtime_error(
        r.scene_path +
        ": nothing emits light (give a material glTF emissiveFactor or OBJ Ke, "
        "or --emission MATERIAL=r,g,b)");
  if (r.max_edge) scene = scene::subdivide_to_edge_length(scene, *r.max_edge);
  return scene;
}

// The form factors of `after`. With a cache: those of the scene as loaded (`before`), loaded
// when the cache exists, else computed and saved, then brought up to date for --move.
radiosity::FormFactorMatrix form_factors(const RadiosityRequest& r, const scene::Scene& before,
                                         const std::vector<radiosity::Patch>& after,
                                         const scene::RayCaster& caster,
                                         RadiositySummary* summary) {
  Clock::time_point t = Clock::now();
  if (r.form_factor_cache.empty()) {
    radiosity::FormFactorMatrix f = radiosity::compute_form_factors(after, caster, r.form_factors);
    summary->form_factor_seconds = since(t);
    return f;
  }
  const std::vector<radiosity::Patch> unmoved = radiosity::make_patches(before);
  if (unmoved.size() != after.size())
    throw std::runtime_error(r.scene_path + ": --move changed how the scene subdivides (" +
                             std::to_string(unmoved.size()) + " patches before, " +
                             std::to_string(after.size()) + " after); use it without a cache");
  const uint64_t key = radiosity::form_factor_key(unmoved, r.form_factors);
  radiosity::FormFactorMatrix f;
  if (std::filesystem::exists(r.form_factor_cache)) {
    f = radiosity::load_form_factors(r.form_factor_cache, key);
    summary->cache_seconds = since(t);
    summary->cache = RadiositySummary::Cache::Loaded;
  } else {
    if (r.moves.empty()) {
      f = radiosity::compute_form_factors(after, caster, r.form_factors);
    } else {
      const scene::RayCaster unmoved_caster(before);
      f = radiosity::compute_form_factors(unmoved, unmoved_caster, r.form_factors);
    }
    summary->form_factor_seconds = since(t);
    t = Clock::now();
    radiosity::save_form_factors(r.form_factor_cache, f, key);
    summary->cache_seconds = since(t);
    summary->cache = RadiositySummary::Cache::Saved;
    summary->files_written.push_back(r.form_factor_cache);
  }
  if (!r.moves.empty()) {
    t = Clock::now();
    summary->update = radiosity::update_form_factors(unmoved, after, caster, r.form_factors, &f);
    summary->update_seconds = since(t);
  }
  return f;
}

void solve(const RadiosityRequest& r, const scene::Scene& scene,
           const std::vector<radiosity::Patch>& patches, const radiosity::FormFactorMatrix& f,
           RadiositySummary* summary) {
  Clock::time_point t = Clock::now();
  const radiosity::GatherMatrix k = radiosity::make_gather_matrix(patches, f);
  summary->gather_seconds = since(t);
  summary->solution = radiosity::solve_matrix(patches, k, r.solve);
  summary->solve_seconds = since(t);
  if (!r.per_emitter_path.empty()) {  // the same form factors, one solve per emitter
    t = Clock::now();
    const prt::EmitterResponses responses =
        radiosity::solve_emitter_responses(scene, patches, f, r.solve, &summary->emitter_reports);
    summary->per_emitter_seconds = since(t);
    const prt::Status written = prt::write_emitter_responses(r.per_emitter_path, responses);
    if (!written.ok()) throw std::runtime_error(written.message());
    summary->files_written.push_back(r.per_emitter_path);
  }
}

void check_patch_count(const RadiosityRequest& r, const scene::Scene& scene) {
  const std::size_t n = scene.triangles.size();
  if (n <= radiosity::kMaxPatches) return;
  std::string advice;
  if (r.max_edge) {
    // Patches grow as 1/edge²: this edge gives about kMaxPatches, rounded up with a margin.
    const double edge = *r.max_edge * std::sqrt(double(n) / radiosity::kMaxPatches) * 1.1;
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", edge);
    advice = "use a larger --max-edge (about " + std::string(text) + " or more)";
  } else {
    advice = "the scene itself has that many triangles: simplify it (--max-edge only splits)";
  }
  throw std::runtime_error(r.scene_path + ": " + std::to_string(n) + " patches, more than the " +
                           std::to_string(radiosity::kMaxPatches) +
                           " that dense form-factor storage allows (8·N² bytes); " + advice);
}

void check_unit_albedo(const RadiosityRequest& r, const scene::Scene& scene,
                       const std::vector<radiosity::Patch>& patches, RadiositySummary* summary) {
  if (!radiosity::has_unit_albedo(scene)) return;
  const scene::RayCaster probe(scene);
  summary->escape_probe = radiosity::escape_fraction(patches, probe, 64, 7);
  if (summary->escape_probe == 0.0)
    throw std::runtime_error(r.scene_path +
                             ": albedo 1 in a closed scene (no probe ray escapes): the "
                             "radiosity grows without bound; lower it with --albedo "
                             "MATERIAL=r,g,b");
}

// Adaptive refinement: replaces `scene` with the refined one and returns its patches.
std::vector<radiosity::Patch> solve_adaptive(const RadiosityRequest& r, scene::Scene* scene,
                                             RadiositySummary* summary) {
  radiosity::AdaptiveResult result =
      radiosity::solve_adaptive(std::move(*scene), r.form_factors, r.solve, *r.adaptive);
  *scene = std::move(result.scene);
  summary->solution = std::move(result.solution);
  summary->adaptive_passes = result.passes;
  for (const radiosity::AdaptivePass& pass : result.passes) {
    summary->form_factor_seconds += pass.form_factor_seconds;
    summary->solve_seconds += pass.solve_seconds;
  }
  return std::move(result.patches);
}

}  // namespace

float automatic_exposure_ev(const Image& image) {
  double log_sum = 0.0;
  std::size_t count = 0;
  for (std::size_t p = 0; p + 2 < image.rgb.size(); p += 3) {
    const double y = 0.2126 * image.rgb[p] + 0.7152 * image.rgb[p + 1] + 0.0722 * image.rgb[p + 2];
    if (y > 0.0 && std::isfinite(y)) log_sum += std::log(y), ++count;
  }
  if (count == 0) return 0.f;
  return static_cast<float>(std::log2(0.18 / std::exp(log_sum / double(count))));
}

ObjectMove parse_object_move(const std::string& text) {
  const std::size_t eq = text.find('=');
  ObjectMove m;
  char extra = 0;
  if (eq == std::string::npos || eq == 0 ||
      std::sscanf(text.c_str() + eq + 1, "%lf,%lf,%lf%c", &m.offset.x, &m.offset.y, &m.offset.z,
                  &extra) != 3 ||
      !std::isfinite(m.offset.x) || !std::isfinite(m.offset.y) || !std::isfinite(m.offset.z))
    throw std::invalid_argument("--move " + text + ": expected OBJECT=dx,dy,dz (finite numbers)");
  m.object = text.substr(0, eq);
  return m;
}

RadiositySummary run_radiosity(const RadiosityRequest& r) {
  check_request(r);
  const scene::Scene before = prepare_scene(r, false);
  scene::Scene scene = r.moves.empty() ? before : prepare_scene(r, true);
  check_patch_count(r, scene);
  if (!r.per_emitter_path.empty()) radiosity::emitter_groups(scene);  // refused before solving
  RadiositySummary summary;
  const float aspect = float(r.render.width) / float(r.render.height);
  const Camera camera = parse_camera(r.camera, scene, aspect);
  std::vector<radiosity::Patch> patches = radiosity::make_patches(scene);
  check_unit_albedo(r, scene, patches, &summary);
  if (r.adaptive) patches = solve_adaptive(r, &scene, &summary);
  const scene::RayCaster caster(scene);
  if (r.adaptive) {
    // solved above, pass by pass
  } else if (r.solve.solver == radiosity::SolverKind::Progressive) {
    const Clock::time_point t = Clock::now();
    summary.solution = radiosity::solve_progressive(patches, caster, r.form_factors, r.solve);
    summary.solve_seconds = since(t);  // includes the rows computed on the fly
  } else {
    solve(r, scene, patches, form_factors(r, before, patches, caster, &summary), &summary);
  }
  summary.patches = patches.size();
  summary.vertices = scene.vertex_count();
  const std::vector<float> radiance =
      radiosity::vertex_radiance(scene, patches, summary.solution.display_radiance);
  summary.solution.radiance.clear();
  summary.solution.display_radiance.clear();

  if (!r.output_path.empty()) {
    const Clock::time_point t = Clock::now();
    const Image image =
        render(scene, caster, radiance, nullptr, kIdentityRotation, camera, r.render);
    summary.render_seconds = since(t);
    summary.exposure_ev = r.exposure_ev ? *r.exposure_ev : automatic_exposure_ev(image);
    write_rendered_image(r.output_path, image, summary.exposure_ev);
    summary.files_written.push_back(r.output_path);
  }
  if (!r.vertex_colors_path.empty()) {
    std::vector<glm::vec3> colors(scene.vertex_count());
    for (std::size_t v = 0; v < colors.size(); ++v)
      colors[v] = glm::vec3(radiance[3 * v], radiance[3 * v + 1], radiance[3 * v + 2]);
    scene::write_glb(r.vertex_colors_path, scene, &colors);
    summary.files_written.push_back(r.vertex_colors_path);
  }
  if (!r.csv_path.empty()) {
    write_vertex_csv(r.csv_path, scene, radiance);
    summary.files_written.push_back(r.csv_path);
  }
  return summary;
}

}  // namespace prt::relight
