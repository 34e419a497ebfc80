// prt/brdf/energy_check.h — the white-furnace check: a material must not reflect more light
// than arrives.
//
// A BRDF conserves energy when its directional albedo a(ωo) = ∫ f(ωi, ωo) cos θi dωi (prt/brdf/
// brdf.h; for a reciprocal BRDF also the fraction of the light arriving from ωo that leaves) is
// at most 1 for every ωo. Interreflection (M = S + G(M)) converges only then; a material above 1
// makes the bounces grow without bound.
// Quadrature (deterministic, no random numbers): two product midpoint rules combined by the
// balance heuristic (multiple importance sampling, [13] of docs/REFERENCES.md):
//   - cosine: 32 × 64 cells of the unit square mapped to ωi by Malley's method
//     (density cos θi / π), for diffuse lobes;
//   - half vector: 128 × 64 cells (t, s) mapped to h by θh = (π/2) t², φh = 2π s (density
//     1 / (2π² t sin θh) per solid angle of h, concentrated at the normal) and ωi = reflect(ωo, h)
//     (density ÷ 4 ωo·h), for lobes around the mirror direction, down to α = 0.001;
//   a(ωo) ≈ Σ_k f cos θi / (N_c p_c + N_h p_h) over both grids' nodes.
// Angles: θo = 0°, 15°, 30°, 45°, 55°, 65°, 70°, 75°, 80°, 83°, 85°, 87°, 89° at azimuth 0
// (isotropic materials), and also at azimuths 45°, 90°, 135° for anisotropic ones. Measured
// accuracy (tests/prt/brdf/ test_brdf_energy_check.cpp, docs/BRDF.md): within
// kAlbedoQuadratureError of the exact albedo for Lambert, GGX (α 0.001 … 1), Beckmann, Ward,
// Blinn-Phong and the glTF model. Compiles as C++17.
#pragma once

#include "prt/brdf/brdf.h"
#include "prt/brdf/material.h"
#include "prt/core/status.h"

namespace prt::brdf {

// The quadrature's error bound (absolute, albedo units), measured on the analytic models.
inline constexpr double kAlbedoQuadratureError = 3e-3;
// A material is refused when its albedo exceeds 1 + kAlbedoTolerance at some angle: above the
// quadrature's error bound, so that no material whose albedo is at most 1 is refused.
inline constexpr double kAlbedoTolerance = 5e-3;

// a(ωo) per channel by the quadrature above.
Rgb furnace_albedo(const Brdf& brdf, const Vec3& wo);

struct AlbedoPeak {
  double albedo = 0;         // the largest channel's albedo at the worst angle
  double theta_degrees = 0;  // θo of that angle (from the normal)
  double phi_degrees = 0;    // its azimuth (from the tangent)
};

// The largest albedo over the angles above (every channel).
AlbedoPeak max_furnace_albedo(const Brdf& brdf, bool isotropic);

// Ok when the material's BRDF reflects at most 1 + kAlbedoTolerance at every angle; otherwise
// one line: "DESCRIPTION reflects 1.23x the light arriving at 75°: directional albedo must not
// exceed 1" (DESCRIPTION: describe(material)). make_brdf()'s errors are returned as they are.
// Lambert needs no quadrature (a = ρ, which make_brdf bounds by 1). MaterialModel::kGltf is
// not refused: it is glTF 2.0's own BRDF, defined for every parameter
// in range, and its (1 − F(ωo·h)) weighting lets it exceed 1 towards grazing angles (by up to
// 1.71x at 89° for a white base colour and roughness 0.1; docs/BRDF.md measures it). The
// glossy bake's divergence check is its guard. A MERL material's result is kept per path for the
// life of the process, so its file is read and integrated once.
Status check_energy_conservation(const Material& material);

}  // namespace prt::brdf
