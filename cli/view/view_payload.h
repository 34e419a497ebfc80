// cli/view/view_payload.h — what `prt view` serves about a scene: the manifest, the mesh, the
// transfer and the environment, built once at start-up from the files the command was given.
//
// Every binary payload is raw little-endian data, streamed as is (never JSON), laid out so that
// the page uploads it to WebGL without conversion; the manifest (JSON) gives the offsets:
//   mesh.bin      float32 sections "positions" (3·V), "normals" (3·V), "albedo" (3·V, the
//                 scene's per-vertex albedo), "ao" (V) and "bent_normals" (3·V) when the file
//                 has them, then uint32 "indices" (3·T); offsets in bytes, counts in elements.
//   transfer.bin  float16 (IEEE binary16) texels of an RGBA texture `transfer.width` texels
//                 wide, a multiple of P (whole vertices per row): vertex v owns texels v·P ..
//                 v·P+P−1 (P = transfer.texels_per_vertex = ⌈channels·order²/4⌉), holding its
//                 coefficients in the file's order (c·order² + k for channel c, SH index k),
//                 zero-padded; rows follow each other.
//   emitters.bin  (with emitter responses) float32 responses of each emitter at each vertex per
//                 unit emission, (e·V + v)·3 + c (prt/emitters/emitter_responses.h); the page adds
//                 Σ_e c_e ⊙ R_e,v to the exit radiance, as prt relight --emitters does
//   preview.bin   (scenes of more than kPreviewMinVertices vertices, without emitters) a coarse
//                 copy of the scene for the first frame (view_preview.h), manifest "preview"
//   environment.bin  float16 RGBA lat-long image (docs/CONVENTIONS.md: row 0 the zenith +Y,
//                 u = 0.5 + atan2(z, x)/2π), the map resampled by 4×4 sub-samples per texel
//                 (linear radiance, alpha 1; values above float16's 65504 are clamped to it:
//                 the background only, the lighting uses the SH coefficients).
// The manifest also carries what the page must show exactly as `prt relight` would, taken from
// the same functions (relight/): the SH lighting of the map (unwindowed, unrotated, channel-
// major radiance coefficients), the window `--window auto` chooses for it, the automatic camera
// (relight/auto_camera.h, at `aspect`) and the automatic exposure (relight/auto_exposure.h).
// A Haar-wavelet file gets the payload of haar_payload.h instead (its own transfer.bin and
// manifest.haar). Throws std::runtime_error "PATH: problem" for an unreadable or mismatched input,
// and prt::MemoryBudgetExceeded when the payloads (held for as long as the server runs) would
// take more than inputs.budget allows: each part is charged before it is built.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/core/memory_budget.h"
#include "relight/auto_camera.h"
#include "sh/env_map.h"

namespace prt::cli::view {

struct ViewInputs {
  std::string scene_path, transfer_path;
  std::string environment_path;  // empty: a uniform environment of radiance 1
  float aspect = 16.f / 9.f;     // the camera's aspect ratio (width / height)
  int background_width = 512;    // lat-long width of environment.bin (height = width / 2)
  // As prt relight --emitters R.prte --max-edge L: per-emitter radiosity responses computed on
  // the vertices of the scene subdivided to L (the bake's --max-edge).
  std::string emitters_path;
  std::optional<double> max_edge;
  // prt view --also: further SH files of the same scene, order, channels and albedo folding as
  // transfer_path, each served as its own transfer payload (also[i] at /api/also<i>.bin, the
  // layout of transfer.bin) and listed in the manifest's "also" (url, kind, file, layout).
  std::vector<std::string> also_paths;
  // What the payloads may take (prt view --memory-limit); none: no limit.
  prt::MemoryBudget* budget = nullptr;
};

struct ViewPayload {
  std::string manifest_json;
  std::vector<std::uint8_t> mesh, transfer, environment, emitters;  // emitters: maybe empty
  std::vector<std::uint8_t> glossy;             // glossy files only (glossy_payload.h)
  std::vector<std::uint8_t> preview;            // maybe empty
  std::vector<std::vector<std::uint8_t>> also;  // one per also_paths
  std::string summary;                          // one line for the terminal
};

ViewPayload build_view_payload(const ViewInputs& inputs);

}  // namespace prt::cli::view
