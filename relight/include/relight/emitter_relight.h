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

#include <string>
#include <vector>

#include "prt/emitters/emitter_responses.h"
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

}  // namespace prt::relight
