// relight/radiosity_render.h — drawing a radiosity solution (radiosity/scene_solve.h computes it
// for `prt radiosity`): the per-vertex exit radiance of a patch scene, rendered with the preview
// renderer and written as an image, a vertex-coloured GLB and/or a CSV. A scene and plain
// per-vertex arrays in: relight does not depend on the radiosity library.
//
// Units: radiance in the units of the emission; glTF frame. PNG output is tone mapped
// (relight/tone_map.h) with an automatic exposure unless one is given: choose_auto_exposure
// (relight/auto_exposure.h) of the vertex radiance, the rule of every command, so prt relight
// of the solution's responses (.prte) with the same emitter colours picks the same exposure.
// The camera is choose_camera's (relight/auto_camera.h), the rule of every command.
// Errors throw std::runtime_error with one line naming the file or option;
// check_radiosity_outputs refuses bad outputs before any work, and each file is written
// atomically.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "relight/auto_camera.h"
#include "relight/camera.h"
#include "relight/renderer.h"
#include "scene/scene.h"

namespace prt::relight {

struct RadiosityRenderRequest {
  std::string scene_path;          // the scene file solved: no output may overwrite it
  std::string output_path;         // .exr, .hdr or .png; optional
  std::string vertex_colors_path;  // .glb, optional
  std::string csv_path;            // optional
  std::string camera = "auto";     // relight/auto_camera.h choose_camera()
  RenderOptions render;
  std::optional<float> exposure_ev;  // PNG only; automatic when absent
};

struct RadiosityRenderSummary {
  double render_seconds = 0;
  float exposure_ev = 0;
  bool exposure_auto = false;  // true: chosen by choose_auto_exposure
  std::vector<std::string> files_written;
};

// Refuses an image other than .exr, .hdr or .png, vertex colours other than .glb, an output in a
// missing directory or one that is the scene file (scene/output_path.h).
void check_radiosity_outputs(const RadiosityRenderRequest& request);

// The request's camera for `scene` at the image's aspect ratio (choose_camera).
CameraChoice radiosity_camera(const RadiosityRenderRequest& request, const scene::Scene& scene);

// Writes the request's outputs for `scene` with exit radiance `vertex_radiance` (3 floats per
// vertex, e.g. radiosity::SceneSolution's), the image seen from `camera`; files_written in the
// order image, vertex colours, CSV.
RadiosityRenderSummary render_radiosity(const RadiosityRenderRequest& request,
                                        const scene::Scene& scene,
                                        const std::vector<float>& vertex_radiance,
                                        const Camera& camera);

}  // namespace prt::relight
