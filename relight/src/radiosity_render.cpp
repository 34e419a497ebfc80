// relight/src/radiosity_render.cpp — see relight/radiosity_render.h.
#include "relight/radiosity_render.h"

#include <chrono>
#include <stdexcept>

#include "relight/auto_exposure.h"
#include "relight/relight_pipeline.h"
#include "scene/glb_writer.h"
#include "scene/output_path.h"
#include "scene/ray_caster.h"

namespace prt::relight {

void check_radiosity_outputs(const RadiosityRenderRequest& r) {
  scene::check_output_path(r.output_path, r.scene_path, {".exr", ".hdr", ".png"});
  scene::check_output_path(r.vertex_colors_path, r.scene_path, {".glb"});
  scene::check_output_path(r.csv_path, r.scene_path, {});
}

CameraChoice radiosity_camera(const RadiosityRenderRequest& r, const scene::Scene& scene) {
  const float aspect = float(r.render.width) / float(r.render.height);
  const scene::RayCaster caster(scene);
  return choose_camera(r.camera, scene, caster, aspect);
}

RadiosityRenderSummary render_radiosity(const RadiosityRenderRequest& r, const scene::Scene& scene,
                                        const std::vector<float>& radiance, const Camera& camera) {
  if (radiance.size() != 3 * scene.vertex_count())
    throw std::invalid_argument(r.scene_path + ": radiance count does not match the vertices");
  RadiosityRenderSummary summary;
  if (!r.output_path.empty()) {
    const scene::RayCaster caster(scene);
    const auto t = std::chrono::steady_clock::now();
    const Image image =
        render(scene, caster, radiance, nullptr, kIdentityRotation, camera, r.render);
    summary.render_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
    summary.exposure_auto = !r.exposure_ev.has_value();
    summary.exposure_ev = r.exposure_ev ? *r.exposure_ev : choose_auto_exposure(radiance);
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
