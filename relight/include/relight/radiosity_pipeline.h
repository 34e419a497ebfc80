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

#include "radiosity/adaptive.h"
#include "radiosity/form_factors.h"
#include "radiosity/materials.h"
#include "radiosity/solver.h"
#include "relight/renderer.h"

namespace prt::relight {

struct RadiosityRequest {
  std::string scene_path;
  std::string output_path;         // .exr, .hdr or .png; optional if another output is given
  std::string vertex_colors_path;  // .glb, optional
  std::string csv_path;            // optional
  std::vector<radiosity::MaterialValue> emission, albedo;  // per-material overrides
  std::optional<double> max_edge;  // subdivide to this edge length (scene units)
  // Refine where the radiance changes fast (radiosity/adaptive.h), starting from max_edge.
  std::optional<radiosity::AdaptiveOptions> adaptive;
  radiosity::FormFactorOptions form_factors;
  radiosity::SolveOptions solve;
  std::string camera = "auto";
  RenderOptions render;
  std::optional<float> exposure_ev;  // PNG only; automatic when absent
};

struct RadiositySummary {
  std::size_t patches = 0, vertices = 0;
  double form_factor_seconds = 0, solve_seconds = 0, render_seconds = 0;
  radiosity::Solution solution;  // radiance vectors emptied; history and account kept
  std::vector<radiosity::AdaptivePass> adaptive_passes;  // with --adaptive: one per solve
  double escape_probe = -1;  // escape fraction measured for albedo-1 scenes (else −1)
  float exposure_ev = 0;
  std::vector<std::string> files_written;
};

// The exposure (EV) mapping the log-average luminance of the pixels with luminance > 0 to 0.18;
// 0 for an image with no such pixel.
float automatic_exposure_ev(const Image& image);

RadiositySummary run_radiosity(const RadiosityRequest& request);

}  // namespace prt::relight
