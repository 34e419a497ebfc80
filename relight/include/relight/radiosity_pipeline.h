// relight/radiosity_pipeline.h — the steps of `prt radiosity`: load a scene, set its emitters and
// albedos, subdivide it into patches, compute form factors, solve for patch radiance, and render
// it with the preview renderer (per-vertex radiance, area-weighted from the patches), writing an
// image, a vertex-coloured GLB and/or a CSV.
//
// Units: radiance in the units of the emission; glTF frame. PNG output is tone mapped
// (relight/tone_map.h) with an automatic exposure unless one is given: the exposure that maps
// the log-average luminance of the lit pixels to 0.18 (Reinhard et al.'s "key").
// Errors throw std::runtime_error / std::invalid_argument / scene::SceneError with one line
// naming the file or option; every input is checked before anything is written, and each file
// is written atomically, so a failed run leaves nothing behind.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "radiosity/emitter_solve.h"
#include "radiosity/form_factor_update.h"
#include "radiosity/adaptive.h"
#include "radiosity/form_factors.h"
#include "radiosity/materials.h"
#include "radiosity/solver.h"
#include "relight/renderer.h"

namespace prt::relight {

// Moves an object before solving: every primitive whose name is `object` (or whose glTF mesh
// part, before the '/', is) is translated by `offset` (scene units) before subdivision.
struct ObjectMove {
  std::string object;
  glm::dvec3 offset{0.0};
};

// Parses "OBJECT=dx,dy,dz"; throws std::invalid_argument "--move TEXT: problem".
ObjectMove parse_object_move(const std::string& text);

struct RadiosityRequest {
  std::string scene_path;
  std::string output_path;         // .exr, .hdr or .png; optional if another output is given
  std::string vertex_colors_path;  // .glb, optional
  std::string csv_path;            // optional
  // Optional: per-emitter responses (prt/emitters/emitter_responses.h, radiosity/emitter_solve.h), one
  // more solve per emitter on the same form factors; needs a full-matrix solver.
  std::string per_emitter_path;
  std::vector<radiosity::MaterialValue> emission, albedo;  // per-material overrides
  std::optional<double> max_edge;  // subdivide to this edge length (scene units)
  // Refine where the radiance changes fast (radiosity/adaptive.h), starting from max_edge.
  std::optional<radiosity::AdaptiveOptions> adaptive;
  radiosity::FormFactorOptions form_factors;
  radiosity::SolveOptions solve;
  std::string camera = "auto";
  RenderOptions render;
  std::optional<float> exposure_ev;  // PNG only; automatic when absent
  // Form-factor cache (radiosity/form_factor_cache.h) of the scene as loaded (before `moves`):
  // absent → computed and saved; present → loaded when its key matches, refused otherwise.
  std::string form_factor_cache;
  std::vector<ObjectMove> moves;  // form factors updated partially when a cache is loaded
};

struct RadiositySummary {
  std::size_t patches = 0, vertices = 0;
  double form_factor_seconds = 0, solve_seconds = 0, render_seconds = 0;
  double cache_seconds = 0;   // loading or saving the form-factor cache
  double update_seconds = 0;  // the partial update after --move
  double gather_seconds = 0;  // K from F (part of solve_seconds)
  enum class Cache { None, Loaded, Saved } cache = Cache::None;
  radiosity::FormFactorUpdate update;  // counts of the partial update
  radiosity::Solution solution;        // radiance vectors emptied; history and account kept
  double escape_probe = -1;            // escape fraction measured for albedo-1 scenes (else −1)
  std::vector<radiosity::AdaptivePass> adaptive_passes;  // with --adaptive: one per solve
  float exposure_ev = 0;
  double per_emitter_seconds = 0;                              // the per-emitter solves
  std::vector<radiosity::EmitterSolveReport> emitter_reports;  // one per emitter
  std::vector<std::string> files_written;
};

// The exposure (EV) mapping the log-average luminance of the pixels with luminance > 0 to 0.18;
// 0 for an image with no such pixel.
float automatic_exposure_ev(const Image& image);

RadiositySummary run_radiosity(const RadiosityRequest& request);

}  // namespace prt::relight
