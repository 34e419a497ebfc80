// cli/view/haar_payload.h — `prt view`'s payload for a Haar-wavelet coefficient file (kind 3,
// docs/FORMAT.md): what the page needs to relight it as `prt relight` does
// (relight/haar_relight.h; Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003), the lighting side
// included, since a wavelet-projected map does not rotate in the wavelet domain.
//
// mesh.bin, environment.bin and the manifest's camera and exposure are those of view_payload.h
// (the exposure from the first frame's radiance with the default lighting terms, as prt relight
// chooses it). transfer.bin holds, at the offsets of manifest.haar.sections (bytes, each a
// multiple of 16; counts in elements), little-endian:
//   offsets    uint32 × (6N² + 1)  the entries of wavelet index i are [offsets[i], offsets[i+1])
//   vertices   uint32 × E          the vertex of each entry, ascending within each index's list
//   values     int16, int8 or float32 × E·C (manifest.haar.value_type), channels per entry
//   steps      float32 × V         per-vertex dequantisation step (1 for float32 values)
//   cube       float32 × 6N²·3     the map resampled to the file's N-cube with exact area
//                                  weighting (prt::resample_to_cube): the unrotated lighting
//   fine_cube  float32 × 6F²·3     the same at F = min(128, 2N), which rotated lighting is
//                                  resampled from (relight::make_rotated_cube)
// Cube layout and wavelet indices: prt/haar/cube_map.h, prt/haar/transform.h. manifest.haar
// also carries N, C, F, the quantisation bits and the default term count K (that of prt relight
// --terms). Throws std::runtime_error "PATH: problem" for bad input, and for options that do not
// apply to Haar files (emitters, --max-edge), or transfer of 2³² entries or more.
#pragma once

#include "view_payload.h"

namespace prt::cli::view {

// The default number of lighting terms, as `prt relight --terms`.
inline constexpr int kHaarDefaultTerms = 200;

ViewPayload build_haar_view_payload(const ViewInputs& inputs);

}  // namespace prt::cli::view
