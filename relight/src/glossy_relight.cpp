// relight/src/glossy_relight.cpp — view-dependent relighting of glossy files
// (relight/glossy_relight.h).
#include "relight/glossy_relight.h"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "prt/formats/cpca_file.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/glossy_transfer_file.h"
#include "relight/glossy_material_override.h"
#include "relight/shown_window.h"
#include "relight_frames.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "sh/rotation.h"

namespace prt::relight {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

glm::vec3 turn(const std::array<double, 9>& m, const glm::vec3& v) {
  return {float(m[0] * v.x + m[1] * v.y + m[2] * v.z), float(m[3] * v.x + m[4] * v.y + m[5] * v.z),
          float(m[6] * v.x + m[7] * v.y + m[8] * v.z)};
}

// The first frame's extras: the exposure (given or automatic, from the image's shading) and the
// CSV and vertex colours toward options.eye.
void write_first_frame_extras(const RelightRequest& request, const GlossyRelightOptions& options,
                              const scene::Scene& scene, const prt::GlossyRelighter& relighter,
                              const prt::ShLighting& lighting, const std::vector<float>& radiance,
                              const GlossyEmitterLight* emitters, RelightSummary* summary) {
  summary->exposure_auto = !request.exposure_ev.has_value();
  summary->exposure_ev =
      request.exposure_ev ? *request.exposure_ev : choose_auto_exposure(radiance);
  if (request.csv_path.empty() && request.vertex_colors_path.empty()) return;
  std::vector<float> at_eye = shade_glossy_vertices(relighter, lighting, *options.eye);
  if (emitters) add_glossy_emitters(*emitters, relighter.projections(), *options.eye, at_eye);
  if (!request.vertex_colors_path.empty()) {
    const std::vector<glm::vec3> colors =
        detail::vertex_colors(at_eye, request.vertex_colors_tonemapped, summary->exposure_ev);
    scene::write_glb(request.vertex_colors_path, scene, &colors);
    summary->files_written.push_back(request.vertex_colors_path);
  }
  if (!request.csv_path.empty()) {
    write_vertex_csv(request.csv_path, scene, at_eye);
    summary->files_written.push_back(request.csv_path);
  }
}

}  // namespace

prt::GlossyTransferData load_glossy_for_scene(const std::string& path, const scene::Scene& scene) {
  prt::Result<prt::GlossyTransferData> data = prt::read_glossy_transfer_file(path);
  if (!data.ok()) {
    const std::string message = data.status().message();
    if (message.rfind(path, 0) == 0) throw std::runtime_error(message);
    throw std::runtime_error(path + ": " + message);
  }
  prt::TransferData header;  // what check_geometry reads: count, fingerprint, positions
  header.vertex_count = data->vertex_count;
  header.fingerprint = data->fingerprint;
  header.positions = data->positions;
  check_transfer_matches_scene(header, path, scene);
  return std::move(data).value();
}

LoadedGlossy load_glossy_any_for_scene(const std::string& path, const scene::Scene& scene) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  if (!(in.read(magic, 4) && prt::is_cpca_transfer_file(magic, 4)))
    return LoadedGlossy{load_glossy_for_scene(path, scene), std::nullopt};
  in.close();
  prt::Result<prt::CpcaFile> file = prt::read_cpca_file_with_source(path);
  if (!file.ok()) {
    const std::string message = file.status().message();
    if (message.rfind(path, 0) == 0) throw std::runtime_error(message);
    throw std::runtime_error(path + ": " + message);
  }
  if (!file->has_source)
    throw std::runtime_error(path +
                             ": a CPCA file without its source section (geometry, frames, "
                             "materials): make it with prt compress");
  prt::TransferData header;
  header.vertex_count = file->source.vertex_count;
  header.fingerprint = file->source.fingerprint;
  header.positions = file->source.positions;
  check_transfer_matches_scene(header, path, scene);
  return LoadedGlossy{std::move(file->source), std::move(file->cpca)};
}

prt::GlossyRelighter make_glossy_relighter(LoadedGlossy&& loaded, const std::string& path,
                                           const prt::BrdfProjectionOptions& projection) {
  prt::Result<prt::GlossyRelighter> relighter =
      loaded.cpca
          ? prt::GlossyRelighter::create_cpca(std::move(loaded.data), *loaded.cpca, projection)
          : prt::GlossyRelighter::create(std::move(loaded.data), projection);
  if (!relighter.ok()) throw std::runtime_error(path + ": " + relighter.status().message());
  return std::move(relighter).value();
}

Camera orbit_camera(const Camera& camera, const glm::vec3& centre, int frame, int frame_count) {
  if (frame_count <= 0) return camera;
  const std::array<double, 9> m =
      sh::rotation_from_yaw_pitch_roll(360.0 * frame / frame_count, 0.0, 0.0);
  Camera out = camera;
  out.eye = centre + turn(m, camera.eye - centre);
  out.target = centre + turn(m, camera.target - centre);
  out.up = turn(m, camera.up);
  return out;
}

std::vector<float> shade_glossy_vertices(const prt::GlossyRelighter& relighter,
                                         const prt::ShLighting& lighting, const glm::vec3& eye) {
  const std::size_t count = relighter.vertex_count();
  std::vector<float> radiance(3 * count, 0.f);
  constexpr std::size_t kRange = 1024;
  const std::size_t ranges = (count + kRange - 1) / kRange;
  std::vector<std::string> errors(ranges);
  const float eye_xyz[3] = {eye.x, eye.y, eye.z};
  prt::GlossyFrame frame;
  if (const prt::Status s = relighter.prepare(lighting, &frame); !s.ok())
    throw std::runtime_error("glossy shading: " + s.message());
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t r) {
    const std::size_t first = r * kRange, n = std::min(kRange, count - first);
    const prt::Status s = relighter.shade(frame, eye_xyz, first, n, &radiance[3 * first]);
    if (!s.ok()) errors[r] = s.message();
  });
  for (const std::string& error : errors)
    if (!error.empty()) throw std::runtime_error("glossy shading: " + error);
  return radiance;
}

void check_glossy_request(const RelightRequest& request, const GlossyRelightOptions& options) {
  if (options.eye) {
    const glm::vec3& e = *options.eye;
    if (!std::isfinite(e.x) || !std::isfinite(e.y) || !std::isfinite(e.z))
      throw std::runtime_error("--eye: not a finite point");
    return;
  }
  if (!request.csv_path.empty() || !request.vertex_colors_path.empty())
    throw std::runtime_error(request.transfer_path +
                             ": is a glossy file, whose vertex values depend on the view: "
                             "--csv and --vertex-colors need --eye x,y,z");
}

RelightSummary run_glossy_relight(const RelightRequest& request,
                                  const GlossyRelightOptions& options) {
  check_relight_outputs(request);
  check_glossy_request(request, options);
  RelightSummary summary;
  scene::Scene scene = scene::load_scene(request.scene_path);
  if (request.max_edge) scene = scene::subdivide_to_edge_length(scene, *request.max_edge);
  LoadedGlossy loaded = load_glossy_any_for_scene(request.transfer_path, scene);
  override_glossy_materials(loaded.data, scene, options.material_overrides);
  const std::optional<GlossyEmitterLight> emitters =
      prepare_glossy_emitters(request, scene, loaded.data, options.gather_emitters);
  const prt::GlossyTransferData& data = loaded.data;
  detail::ShEnvironment lit = detail::read_sh_environment(request, static_cast<int>(data.order),
                                                          scene.vertex_count(), &summary);
  const sh::EnvMap& env = lit.env;
  prt::ShLighting& base = lit.base;
  const bool window_on_vertices = lit.window_on_vertices;
  const prt::GlossyRelighter relighter =
      make_glossy_relighter(std::move(loaded), request.transfer_path, options.projection);

  const float aspect = static_cast<float>(request.render.width) /
                       static_cast<float>(std::max(1, request.render.height));
  const scene::RayCaster caster(scene);
  const Camera camera = resolve_camera(request.camera, scene, caster, aspect, &summary.camera_note);
  make_camera_basis(camera, aspect);
  const std::array<double, 9> rotation = sh::rotation_from_yaw_pitch_roll(
      request.lighting.yaw_pitch_roll_deg[0], request.lighting.yaw_pitch_roll_deg[1],
      request.lighting.yaw_pitch_roll_deg[2]);
  const int frames = std::max(1, request.turntable_frames);
  const bool turn_light = options.turntable != GlossyTurntable::kCamera;
  const bool orbit = options.turntable != GlossyTurntable::kLight;
  const glm::vec3 orbit_centre =
      options.orbit_centre.value_or(0.5f * (scene.bounds_min() + scene.bounds_max()));
  if (window_on_vertices) {  // chosen on every frame's view, and --eye's (relight/shown_window.h)
    ShownWindowSearch search(base.order());
    const auto add_view = [&](const std::array<double, 9>& m, const glm::vec3& eye) {
      search.add_view(rotate_lighting(base, m), [&](const prt::ShLighting& lighting) {
        return shade_glossy_vertices(relighter, lighting, eye);
      });
    };
    for (int frame = 0; frame < frames; ++frame) {
      const bool table = request.turntable_frames > 0;
      add_view(table && turn_light ? turntable_rotation(rotation, frame, frames) : rotation,
               table && orbit ? orbit_camera(camera, orbit_centre, frame, frames).eye : camera.eye);
    }
    if (options.eye && (!request.csv_path.empty() || !request.vertex_colors_path.empty()))
      add_view(rotation, *options.eye);
    summary.window_note = apply_shown_window(search.choose(), &base);
  }
  if (emitters) {
    const std::size_t count = emitters->radiance.emitter_count();
    char note[96];
    std::snprintf(note, sizeof note, "; %zu emitter%s gathered in %.2f s", count,
                  count == 1 ? "" : "s", emitters->gather_seconds);
    summary.window_note += note;
  }
  for (int frame = 0; frame < frames; ++frame) {
    const bool table = request.turntable_frames > 0;
    const std::array<double, 9> m =
        table && turn_light ? turntable_rotation(rotation, frame, frames) : rotation;
    const Camera view = table && orbit ? orbit_camera(camera, orbit_centre, frame, frames) : camera;
    const prt::ShLighting lighting = rotate_lighting(base, m);
    auto start = Clock::now();
    std::vector<float> radiance = shade_glossy_vertices(relighter, lighting, view.eye);
    if (emitters) add_glossy_emitters(*emitters, relighter.projections(), view.eye, radiance);
    summary.shade_seconds += seconds_since(start);
    const std::size_t negative = detail::count_negative_vertices(radiance);
    summary.negative_vertices = std::max(summary.negative_vertices, negative);
    summary.negative_frames += negative > 0 ? 1 : 0;
    if (frame == 0)
      write_first_frame_extras(request, options, scene, relighter, lighting, radiance,
                               emitters ? &*emitters : nullptr, &summary);
    start = Clock::now();
    const Image image = render(scene, caster, radiance, &env, m, view, request.render);
    summary.render_seconds += seconds_since(start);
    const std::string path =
        table ? turntable_frame_path(request.output_path, frame) : request.output_path;
    write_rendered_image(path, image, summary.exposure_ev);
    summary.files_written.push_back(path);
    if (request.image_written) request.image_written(frame + 1, frames);
  }
  return summary;
}

}  // namespace prt::relight
