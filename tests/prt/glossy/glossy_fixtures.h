// Shared fixtures of the glossy runtime tests: an unshadowed glossy sphere built in memory (M is
// the SH rotation from the global frame to each vertex's tangent frame), band-limited test
// lighting, and an independent Monte Carlo estimate of the rendering integral.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "prt/brdf/material.h"
#include "prt/glossy/transfer.h"
#include "prt/lighting/sh_lighting.h"

namespace glossy_test {

// Rows t, b, n of vertex v's frame (the convention of prt/glossy/transfer.h, w = +1).
std::array<double, 9> frame_rows(const prt::GlossyTransferData& data, std::size_t v);

// `count` vertices on the unit sphere (Fibonacci spiral) with normal = position, tangent from
// Duff et al.'s frame of the normal, every vertex `material`, and M_v = the dense SH rotation
// (order² × order²) taking global-frame lighting into the local frame: unshadowed transfer.
prt::GlossyTransferData unshadowed_sphere(int order, std::size_t count,
                                          const prt::brdf::Material& material);

// Band-limited RGB lighting of `order`: a bright zonal lobe towards `towards` (Gaussian-like band
// weights), a constant sky and small fixed pseudo-random coefficients in every band.
prt::ShLighting band_limited_lighting(int order, const std::array<double, 3>& towards,
                                      uint64_t seed = 7);

// ∫ L(ω) f(ω, ωo) cos⁺θ dω at vertex v for the eye point, by importance sampling the BRDF with
// strata × strata jittered draws; L evaluated straight from its SH at each sample direction
// (global frame). *standard_error gets the per-channel maximum of σ/√N (conservative for
// stratified draws).
std::array<double, 3> monte_carlo_exit(const prt::GlossyTransferData& data,
                                       const prt::ShLighting& light, const double eye[3],
                                       std::size_t v, int strata, double* standard_error);

}  // namespace glossy_test
