// bake/brdf_projection.h — the SH projection of a BRDF toward a view direction,
//     b_c,i(ω_o) = ∫ y_i(ω_i) f_c(ω_i, ω_o) cos⁺θ_i dω_i,
// in the LOCAL shading frame of prt/brdf/brdf.h (+z the normal, +x the tangent), SH of
// sh/basis.h evaluated on local directions. This is the b of prt/glossy_transfer.h; the glossy
// baker uses it for the radiance a glossy surface sends back toward the vertex whose ray hit it.
//
// Lambert (ρ): exact, b_c,i = ρ_c/π · z_l for m = 0 (z_l the clamped-cosine zonal coefficient,
// sh/zonal.h), 0 otherwise — independent of ω_o (for ω_o above the horizon).
// Other models: tabulated on a grid over the upper hemisphere of ω_o — kThetaNodes polar angles
// θ_o = (π/2) · j/(kThetaNodes − ½) (the normal included, the last 3° above the horizon) and
// kPhiNodes azimuths 2π(k + ½)/kPhiNodes — each node by
// importance sampling the BRDF (Brdf::sample, samples × samples jittered strata, splitmix64
// from `seed`), and read back bilinearly (θ_o clamped to the outer nodes, φ_o periodic).
// The table error is the MC error of each node (a standard error of ~1/samples relative for
// smooth lobes) plus the bilinear interpolation error, which grows with the lobe's sharpness;
// it affects only the interreflected part of a glossy bake. ω_o at or below the horizon: b = 0
// (every model is one-sided).
// Channels: 3 (r, g, b), channel-major: out[c · K + i], K = order².
// References: [2] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/brdf/material.h"

namespace prt::bake {

class BrdfProjection {
 public:
  static constexpr int kThetaNodes = 16;
  static constexpr int kPhiNodes = 32;

  // Builds the projection of `material` at SH order `order` (1 .. 10). Throws BakeError
  // (bake/transfer_baker.h) when make_brdf refuses the material; `name` prefixes the message.
  BrdfProjection(const brdf::Material& material, int order, int samples, uint64_t seed,
                 const std::string& name);

  bool lambertian() const { return lambertian_; }
  int order() const { return order_; }
  // b toward the unit local direction wo: 3 · K floats, channel-major.
  void evaluate(const glm::vec3& wo, float* out) const;

 private:
  int order_ = 0, K_ = 0;
  bool lambertian_ = false;
  std::vector<float> lambert_;  // 3 · K (Lambert)
  std::vector<float> table_;    // kThetaNodes · kPhiNodes · 3 · K
};

}  // namespace prt::bake
