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
#include <string>
#include <vector>

#include "relight/camera.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "scene/glb_writer.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"
#include "sh/env_map.h"
#include "sh/rotation.h"

namespace prt::relight::detail {

// Checks the camera, then for each frame: lighting = light_for(M_i) (not timed), radiance =
// shade(lighting) (timed as shade_seconds, must return 3 floats per vertex), render (timed as
// render_seconds) and write the image (OUT_iii for a turntable). The first frame also counts
// the vertices with a negative channel and writes the vertex-coloured GLB and the CSV if asked.
// With request.render.multiply_albedo the shaded values are per unit albedo: the renderer
// multiplies by the albedo per sub-pixel, the GLB and the CSV's r,g,b get the vertex's own
// albedo × the value (exit radiance at the vertex), and the CSV adds the values themselves.
// Every file written is appended to summary->files_written.
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
  const Camera camera = parse_camera(request.camera, scene, aspect);
  make_camera_basis(camera, aspect);  // throws for a degenerate scene camera
  const std::array<double, 9> rotation = sh::rotation_from_yaw_pitch_roll(
      request.lighting.yaw_pitch_roll_deg[0], request.lighting.yaw_pitch_roll_deg[1],
      request.lighting.yaw_pitch_roll_deg[2]);
  const scene::RayCaster caster(scene);

  const int frames = std::max(1, request.turntable_frames);
  for (int frame = 0; frame < frames; ++frame) {
    const std::array<double, 9> m =
        request.turntable_frames > 0 ? turntable_rotation(rotation, frame, frames) : rotation;
    const auto lighting = light_for(m);
    auto start = Clock::now();
    const std::vector<float> radiance = shade(lighting);
    summary->shade_seconds += seconds_since(start);
    if (frame == 0) {
      for (std::size_t v = 0; v < scene.vertex_count(); ++v)
        if (radiance[3 * v] < 0.f || radiance[3 * v + 1] < 0.f || radiance[3 * v + 2] < 0.f)
          ++summary->negative_vertices;
      const bool apart = request.render.multiply_albedo;
      std::vector<float> exit = radiance;  // at the vertices
      if (apart)
        for (std::size_t v = 0; v < scene.vertex_count(); ++v)
          for (int c = 0; c < 3; ++c) exit[3 * v + c] *= scene.albedo[v][c];
      if (!request.vertex_colors_path.empty()) {
        std::vector<glm::vec3> colors(scene.vertex_count());
        for (std::size_t v = 0; v < colors.size(); ++v)
          colors[v] = glm::vec3(exit[3 * v], exit[3 * v + 1], exit[3 * v + 2]);
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
    write_rendered_image(path, image, request.exposure_ev);
    summary->files_written.push_back(path);
  }
}

}  // namespace prt::relight::detail
