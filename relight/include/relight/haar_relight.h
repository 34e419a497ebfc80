// relight/haar_relight.h — `prt relight` for Haar-wavelet coefficient files (all-frequency
// relighting, Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003, Sec. 4–6).
//
// Steps: resample the environment to the file's cube size with exact area weighting
// (prt::resample_to_cube), wavelet-transform it (prt::transform_cube), keep K terms
// (non-linear: the K largest area-weighted coefficients; linear: the K coarsest;
// prt/haar/approximation.h), shade every vertex with the sparse product of prt::HaarRelighter,
// then render as for SH (relight/renderer.h).
// Rotation (--rotate, --turntable): a wavelet-projected map has no cheap rotation (unlike SH,
// whose bands rotate among themselves, a rotated Haar basis function is not a short sum of
// Haar functions), so the *environment* is rotated by resampling: the map is first resampled
// to a cube of 2N (at most 128) texels, then each target texel averages 4×4 sub-directions ω,
// each reading that cube at Mᵀω (nearest texel), weighted by exact sub-texel solid angle.
// This costs 16·6N² look-ups per frame and blurs by about half a texel; with M = I the map is
// resampled directly (power exactly preserved).
// Conventions: glTF frame (+Y up); lighting "rotated by M" is g(ω) = f(Mᵀω), as for SH
// (relight/relight_pipeline.h). Errors throw std::runtime_error "PATH: problem".
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "prt/haar/approximation.h"
#include "prt/haar/cube_map.h"
#include "relight/relight_pipeline.h"
#include "sh/env_map.h"

namespace prt::relight {

struct HaarLightingOptions {
  int64_t terms = 200;  // K; ≤ 0 keeps every term
  bool linear = false;  // false: non-linear (largest area-weighted), true: K coarsest
};

// The cube map of `env` rotated by M (see above), N×N per face. Throws for invalid input.
prt::CubeMap make_rotated_cube(const sh::EnvMap& env, int size, const std::array<double, 9>& m);

// The K-term Haar lighting of `env` rotated by M, on an N-cube.
prt::SparseLighting project_haar_lighting(const sh::EnvMap& env, int size,
                                          const std::array<double, 9>& m,
                                          const HaarLightingOptions& options);

// `prt relight` for a Haar file: as run_relight (same request, same outputs and checks), with
// summary.order = the cube size and the window ignored.
RelightSummary run_haar_relight(const RelightRequest& request, const HaarLightingOptions& options);

}  // namespace prt::relight
