// relight/src/relight_frames.h (private) — the frame loop shared by run_relight (SH) and
// run_haar_relight (Haar wavelets): for one image, or for each turntable frame, light, shade,
// render and write (relight/relight_pipeline.h).
//
// Conventions: glTF frame (+Y up); frame i of an N-frame turntable is lit by
// M_i = Ry(360°·i/N)·M with M the --rotate matrix (row-major, lighting "rotated by M" is
// g(ω) = f(Mᵀω), sh/rotation.h). Radiance is 3 floats per vertex, linear.
// Errors throw std::runtime_error "PATH: problem".
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "relight/auto_camera.h"
#include "relight/auto_exposure.h"
#include "relight/camera.h"
#include "relight/environment_input.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "relight/tone_map.h"
#include "scene/glb_writer.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"
#include "sh/env_map.h"
#include "sh/rotation.h"

namespace prt::relight::detail {

// Vertices with a negative channel in `radiance` (3 floats per vertex).
inline std::size_t count_negative_vertices(const std::vector<float>& radiance) {
  std::size_t count = 0;
  for (std::size_t v = 0; v + 2 < radiance.size(); v += 3)
    count += (radiance[v] < 0.f || radiance[v + 1] < 0.f || radiance[v + 2] < 0.f) ? 1 : 0;
  return count;
}

// COLOR_0 for the vertex-coloured GLB: the radiance itself, or (tonemapped) exposure and the
// filmic curve without the sRGB step, in [0, 1] (relight/relight_pipeline.h RelightRequest).
inline std::vector<glm::vec3> vertex_colors(const std::vector<float>& radiance, bool tonemapped,
                                            float exposure_ev) {
  std::vector<glm::vec3> colors(radiance.size() / 3);
  const float scale = std::exp2(exposure_ev);
  for (std::size_t v = 0; v < colors.size(); ++v) {
    for (int c = 0; c < 3; ++c) {
      const float x = radiance[3 * v + c];
      colors[v][c] = tonemapped ? apply_aces_filmic(x * scale) : x;
    }
  }
  return colors;
}

// The environment of an SH relight (run_relight, run_glossy_relight): request.environment_path
// read and screened for SH order `order`, and projected at that order with request.lighting,
// except that --window auto is left for the vertices as shaded (relight/shown_window.h): then
// `base` is unwindowed and `window_on_vertices` is set. Fills summary->layout_note,
// vertex_count, order and window_note.
struct ShEnvironment {
  sh::EnvMap env;
  prt::ShLighting base;
  bool window_on_vertices = false;
};

inline ShEnvironment read_sh_environment(const RelightRequest& request, int order,
                                         std::size_t vertex_count, RelightSummary* summary) {
  EnvironmentUse use;
  use.sh_order = order;
  EnvironmentInput input = read_checked_environment(request.environment_path, request.layout, use);
  ShEnvironment out;
  out.env = std::move(input.env);
  summary->layout_note = input.layout_note;
  summary->vertex_count = vertex_count;
  summary->order = order;
  LightingOptions lighting_options = request.lighting;
  out.window_on_vertices = lighting_options.window == sh::Window::Auto;
  if (out.window_on_vertices) lighting_options.window = sh::Window::None;
  out.base = project_lighting(out.env, order, lighting_options, &summary->window_note);
  return out;
}

// Resolves the camera (relight/auto_camera.h), then for each frame: lighting = light_for(M_i)
// (not timed), radiance = shade(lighting) (timed as shade_seconds, must return 3 floats per
// vertex), render (timed as render_seconds) and write the image (OUT_iii for a turntable).
// Every frame counts its vertices with a negative channel (summary: the most in a frame and the
// number of frames with any). The first frame fixes the exposure (given or automatic) and
// writes the vertex-coloured GLB and the CSV if asked. With request.render.multiply_albedo the
// shaded values are per unit albedo: the renderer multiplies by the albedo per sub-pixel, the
// GLB, the CSV's r,g,b and the automatic exposure use the vertex's own albedo × the value (exit
// radiance at the vertex), and the CSV adds the values themselves. Every file written is appended
// to summary->files_written; request.image_written (if set) is called after each image.
template <class LightFor, class Shade>
void render_relight_frames(const RelightRequest& request, const scene::Scene& scene,
                           const sh::EnvMap& env, LightFor light_for, Shade shade,
                           RelightSummary* summary) {
  using Clock = std::chrono::steady_clock;
  const auto seconds_since = [](Clock::time_point start) {
    return std::chrono::duration<double>(Clock::now() - start).count();
  };
  const float aspect = static_cast<float>(request.render.width) /
                       static_cast<float>(std::max(1, request.render.height));
  const scene::RayCaster caster(scene);
  const Camera camera =
      resolve_camera(request.camera, scene, caster, aspect, &summary->camera_note);
  make_camera_basis(camera, aspect);  // throws for a degenerate scene camera
  const std::array<double, 9> rotation = sh::rotation_from_yaw_pitch_roll(
      request.lighting.yaw_pitch_roll_deg[0], request.lighting.yaw_pitch_roll_deg[1],
      request.lighting.yaw_pitch_roll_deg[2]);

  const int frames = std::max(1, request.turntable_frames);
  for (int frame = 0; frame < frames; ++frame) {
    const std::array<double, 9> m =
        request.turntable_frames > 0 ? turntable_rotation(rotation, frame, frames) : rotation;
    const auto lighting = light_for(m);
    auto start = Clock::now();
    const std::vector<float> radiance = shade(lighting);
    summary->shade_seconds += seconds_since(start);
    const std::size_t negative = count_negative_vertices(radiance);
    summary->negative_vertices = std::max(summary->negative_vertices, negative);
    summary->negative_frames += negative > 0 ? 1 : 0;
    if (frame == 0) {
      const bool apart = request.render.multiply_albedo;
      std::vector<float> exit = radiance;  // at the vertices
      if (apart)
        for (std::size_t v = 0; v < scene.vertex_count(); ++v)
          for (int c = 0; c < 3; ++c) exit[3 * v + c] *= scene.albedo[v][c];
      summary->exposure_auto = !request.exposure_ev.has_value();
      summary->exposure_ev =
          request.exposure_ev ? *request.exposure_ev : choose_auto_exposure(exit);
      if (!request.vertex_colors_path.empty()) {
        const std::vector<glm::vec3> colors =
            vertex_colors(exit, request.vertex_colors_tonemapped, summary->exposure_ev);
        scene::write_glb(request.vertex_colors_path, scene, &colors);
        summary->files_written.push_back(request.vertex_colors_path);
      }
      if (!request.csv_path.empty()) {
        write_vertex_csv(request.csv_path, scene, exit, apart ? &radiance : nullptr);
        summary->files_written.push_back(request.csv_path);
      }
    }
    start = Clock::now();
    const Image image = render(scene, caster, radiance, &env, m, camera, request.render);
    summary->render_seconds += seconds_since(start);
    const std::string path = request.turntable_frames > 0
                                 ? turntable_frame_path(request.output_path, frame)
                                 : request.output_path;
    write_rendered_image(path, image, summary->exposure_ev);
    summary->files_written.push_back(path);
    if (request.image_written) request.image_written(frame + 1, frames);
  }
}

}  // namespace prt::relight::detail
