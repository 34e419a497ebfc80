#include "relight/radiosity_pipeline.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

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
  if (r.output_path.empty() && r.vertex_colors_path.empty() && r.csv_path.empty())
    throw std::runtime_error("nothing to write: give -o IMAGE, --vertex-colors or --csv");
  check_output(r.output_path, r.scene_path, {".exr", ".hdr", ".png"});
  check_output(r.vertex_colors_path, r.scene_path, {".glb"});
  check_output(r.csv_path, r.scene_path, {});
  if (r.max_edge && !(*r.max_edge > 0.0 && std::isfinite(*r.max_edge)))
    throw std::invalid_argument("--max-edge " + std::to_string(*r.max_edge) +
                                ": the target edge length must be a finite positive number");
  if (!(r.solve.tolerance > 0.0 && r.solve.tolerance < 1.0))
    throw std::invalid_argument("--tolerance " + std::to_string(r.solve.tolerance) +
                                ": must be in (0, 1)");
}

// Loads the scene and applies and checks its materials; throws when nothing emits.
scene::Scene prepare_scene(const RadiosityRequest& r) {
  scene::Scene scene = scene::load_scene(r.scene_path);
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

void solve(const RadiosityRequest& r, const std::vector<radiosity::Patch>& patches,
           const scene::RayCaster& caster, RadiositySummary* summary) {
  if (r.solve.solver == radiosity::SolverKind::Progressive) {
    const Clock::time_point t = Clock::now();
    summary->solution = radiosity::solve_progressive(patches, caster, r.form_factors, r.solve);
    summary->solve_seconds = since(t);  // includes the rows computed on the fly
    return;
  }
  Clock::time_point t = Clock::now();
  const radiosity::FormFactorMatrix f =
      radiosity::compute_form_factors(patches, caster, r.form_factors);
  summary->form_factor_seconds = since(t);
  t = Clock::now();
  summary->solution = radiosity::solve_matrix(patches, f, r.solve);
  summary->solve_seconds = since(t);
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

RadiositySummary run_radiosity(const RadiosityRequest& r) {
  check_request(r);
  scene::Scene scene = prepare_scene(r);
  if (scene.triangles.size() > radiosity::kMaxPatches)
    throw std::runtime_error(r.scene_path + ": " + std::to_string(scene.triangles.size()) +
                             " patches (at most " + std::to_string(radiosity::kMaxPatches) +
                             ": form factors are stored densely); use a longer --max-edge");
  RadiositySummary summary;
  const float aspect = float(r.render.width) / float(r.render.height);
  const Camera camera = parse_camera(r.camera, scene, aspect);
  std::vector<radiosity::Patch> patches = radiosity::make_patches(scene);
  if (radiosity::has_unit_albedo(scene)) {
    const scene::RayCaster probe(scene);
    summary.escape_probe = radiosity::escape_fraction(patches, probe, 64, 7);
    if (summary.escape_probe == 0.0)
      throw std::runtime_error(r.scene_path +
                               ": albedo 1 in a closed scene (no probe ray escapes): the "
                               "radiosity grows without bound; lower it with --albedo "
                               "MATERIAL=r,g,b");
  }
  if (r.adaptive) patches = solve_adaptive(r, &scene, &summary);
  const scene::RayCaster caster(scene);
  if (!r.adaptive) solve(r, patches, caster, &summary);
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
