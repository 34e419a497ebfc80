// relight/glossy_relight.h — `prt relight` for glossy transfer files (prt/glossy/transfer.h):
// view-dependent images in which the camera's eye point drives the view direction.
//
// Per frame: SH lighting of the environment at the file's order (windowed and rotated exactly as
// for coefficient files, relight/relight_pipeline.h), exit radiance of every vertex toward the
// camera's EYE POINT (prt::GlossyRelighter: ωo = normalize(eye − p) in the vertex's tangent
// frame, so highlights move when the camera moves), then the preview renderer
// (relight/renderer.h), which interpolates the vertex values across each triangle: ωo is taken
// PER VERTEX, not per pixel, so a highlight is as sharp as the mesh is fine.
// Turntable (--turntable N): frame i turns the light by Ry(360°·i/N) (as for coefficient files)
// AND orbits the camera (eye, target and up turned rigidly, so frame 0 is the camera itself) by
// the same Ry about the vertical axis through the orbit centre — the centre of the scene's
// bounding box, or GlossyRelightOptions::orbit_centre (--target) — both by
// default, so the object is seen from every side under a light that keeps its place relative
// to the camera; GlossyTurntable::kCamera orbits the camera under fixed light (the highlights
// then slide over the surface), kLight turns the light only, as coefficient files do.
// CSV and vertex-coloured GLB: exit radiance toward the eye point GlossyRelightOptions::eye
// (scene frame), under the first frame's lighting; asking for either without an eye point is
// an error raised before anything is written (the values depend on the view).
// Materials come from the file (the scene's own are not read); the albedo is inside the BRDF.
// Files: a glossy transfer file (.prtg, shaded through prt::GlossyKernel) or a CPCA file (.prtq)
// with a source section (prt/formats/cpca_file.h, made by `prt compress`), shaded through
// prt::CpcaKernel; both are checked against the scene's geometry the same way.
// GlossyRelightOptions::material_overrides replace some of them before shading (only the
// vertex's own BRDF changes; interreflections stay as baked: relight/glossy_material_override.h).
// Emitters (RelightRequest::emitters_path, a .prte computed on the same vertices: max_edge
// subdivides the scene as `prt bake --max-edge` did): their exit radiance toward each frame's eye
// is added to the environment's (relight/emitter_relight.h), for .prtg and .prtq alike.
// Errors throw std::runtime_error with one line "PATH: problem".
#pragma once

#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "prt/glossy/brdf_projection.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/relighter.h"
#include "prt/glossy/transfer.h"
#include "relight/camera.h"
#include "relight/emitter_relight.h"
#include "relight/relight_pipeline.h"
#include "scene/material_override.h"
#include "scene/scene.h"

namespace prt::relight {

enum class GlossyTurntable { kBoth, kCamera, kLight };

struct GlossyRelightOptions {
  std::optional<glm::vec3> eye;  // for the CSV and the vertex colours
  GlossyTurntable turntable = GlossyTurntable::kBoth;
  std::optional<glm::vec3> orbit_centre;  // --target; default: the centre of the scene's bounds
  prt::BrdfProjectionOptions projection;
  // `--material` overrides of the file's BRDFs (relight/glossy_material_override.h).
  std::vector<scene::MaterialOverride> material_overrides;
  // With RelightRequest::emitters_path: gathers the emitters' incident radiance at the file's
  // vertices (relight/emitter_relight.h; the CLI passes bake/glossy_emitter_gather.h's).
  GlossyEmitterGatherer gather_emitters;
};

// Reads a glossy transfer file and checks that it was baked for `scene` (prt::check_geometry).
prt::GlossyTransferData load_glossy_for_scene(const std::string& path, const scene::Scene& scene);

// A glossy file of either kind: `data` holds geometry, frames, materials and (for a .prtg) the
// matrices; `cpca` the compressed matrices of a .prtq (then data.matrices is empty).
struct LoadedGlossy {
  prt::GlossyTransferData data;
  std::optional<prt::CpcaTransfer> cpca;
};

// Reads a .prtg or a .prtq (by its magic) and checks it against `scene` as above. A .prtq
// without a source section is refused (it holds no frames or materials).
LoadedGlossy load_glossy_any_for_scene(const std::string& path, const scene::Scene& scene);

// The relighter of a loaded file (kernel paths). Throws "PATH: problem".
prt::GlossyRelighter make_glossy_relighter(LoadedGlossy&& loaded, const std::string& path,
                                           const prt::BrdfProjectionOptions& projection);

// The camera of turntable frame i of N: eye, target and up turned by Ry(360°·i/N) about the
// vertical line through `centre`.
Camera orbit_camera(const Camera& camera, const glm::vec3& centre, int frame, int frame_count);

// Exit radiance of every vertex toward `eye`, 3 floats per vertex, shaded in parallel (TBB).
std::vector<float> shade_glossy_vertices(const prt::GlossyRelighter& relighter,
                                         const prt::ShLighting& lighting, const glm::vec3& eye);

// Throws "PATH: ..." when the request asks for a CSV or vertex colours without options.eye.
void check_glossy_request(const RelightRequest& request, const GlossyRelightOptions& options);

// `prt relight` for a glossy file: same request, outputs and checks as run_relight.
RelightSummary run_glossy_relight(const RelightRequest& request,
                                  const GlossyRelightOptions& options);

}  // namespace prt::relight
