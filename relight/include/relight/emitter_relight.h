// relight/emitter_relight.h — `prt relight` for per-emitter radiosity responses (".prte",
// prt/emitters/emitter_responses.h): recolour the emitters, L_v = Σ_e c_e ⊙ R_e,v, and render; and
// adding such a file to the exit radiance of a coefficient file (environment + emitters in one
// image).
//
// Units: radiance in the units of the emission; glTF frame. The mesh is the one stored in the
// responses file (the subdivided scene the radiosity was solved on): positions, normals,
// triangles; its exit radiance already includes the albedo, so it is rendered as it is.
// Errors throw std::runtime_error / std::invalid_argument with one line naming the file or
// option; every input is checked before anything is written, and files are written atomically.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/emitters/emitter_responses.h"
#include "prt/emitters/glossy_emitter_radiance.h"
#include "prt/glossy/brdf_projection.h"
#include "prt/glossy/transfer.h"
#include "relight/relight_pipeline.h"
#include "scene/scene.h"

namespace prt::relight {

// Reads a responses file; throws "PATH: problem".
prt::EmitterResponses load_emitter_responses(const std::string& path);

// A scene holding the responses' mesh (one primitive "responses", albedo 1: the stored radiance
// is exit radiance), for the camera and the renderer. source_path = `path`.
scene::Scene scene_from_responses(const prt::EmitterResponses& data, const std::string& path);

// Throws "PATH: was not computed for SCENE: …" unless the responses were computed on exactly
// the vertices of `scene` (equal vertex counts and geometry fingerprints,
// prt/formats/geometry_check.h); the message suggests --max-edge when the counts differ.
void check_responses_match_scene(const prt::EmitterResponses& data, const std::string& path,
                                 const scene::Scene& scene);

// Σ_e c_e ⊙ R_e,v for every vertex (3 floats per vertex), c_e the stored emission unless
// `colors` names the emitter; throws "PATH: emitter NAME: …" for an unknown name or a bad value.
std::vector<float> emitter_radiance(const prt::EmitterResponses& data, const std::string& path,
                                    const std::vector<prt::EmitterColor>& colors);

// `prt relight RESPONSES.prte -o OUT`: request.transfer_path is the responses file;
// scene_path and environment_path must be empty; lighting and turntable options do not apply.
// Writes the image, and the vertex-coloured GLB and CSV if asked (relight_frames: the same
// exposure rules as SH relighting).
RelightSummary run_emitter_relight(const RelightRequest& request,
                                   const std::vector<prt::EmitterColor>& colors);

// --- Glossy files with emitters (`prt relight SCENE FILE.prtg|.prtq ENV --emitters R.prte`) ---
// The exit radiance adds Σ_e c_e ⊙ (b(ωo) · G_e,v) to the environment's glossy result, G the
// emitters' incident radiance in the vertex's local SH frame (prt/emitters/
// glossy_emitter_radiance.h), gathered from the responses at the file's vertices. The gather
// casts rays (bake/glossy_emitter_gather.h), which relight/ does not link: the caller passes it.
using GlossyEmitterGatherer = std::function<prt::GlossyEmitterRadiance(
    const scene::Scene&, const prt::GlossyTransferData&, const prt::EmitterResponses&)>;

struct GlossyEmitterLight {
  prt::GlossyEmitterRadiance radiance;
  std::vector<float> colors;         // 3 per emitter: stored emission or --emitter
  prt::GlossyTransferData geometry;  // positions, frames, material_of_vertex (no matrices)
  double gather_seconds = 0;
};

// Nothing when request.emitters_path is empty. Otherwise reads the responses, checks them
// against `scene` (check_responses_match_scene) and request.emitter_colors against them, and
// gathers G at the vertices of `glossy` (whose geometry the caller checked against `scene`).
// Throws "PATH: problem" (one line) before any output is written.
std::optional<GlossyEmitterLight> prepare_glossy_emitters(const RelightRequest& request,
                                                          const scene::Scene& scene,
                                                          const prt::GlossyTransferData& glossy,
                                                          const GlossyEmitterGatherer& gather);

// Adds the emitters' exit radiance toward `eye` (scene frame) to `radiance` (3 floats per
// vertex), `projections` the relighter's (one per material, GlossyRelighter::projections()).
void add_glossy_emitters(const GlossyEmitterLight& light,
                         const std::vector<prt::BrdfProjection>& projections, const glm::vec3& eye,
                         std::vector<float>& radiance);

}  // namespace prt::relight
