// bake/obscurance_falloff.h — obscurance: ambient occlusion with the visibility of a direction
// replaced by a falloff of the distance to the first surface it meets (Zhukov, Iones & Kronin
// 1998; Iones, Krupkin, Sbert & Zhukov 2003; full references in docs/SSAO.md).
//
//   W(p) = (1/π) ∫_Ω ρ(d(p, ω)) cos θ dω,
//
// d(p, ω) the distance along ω to the first hit (∞ when the ray escapes), ρ a falloff rising from
// ρ(0) = 0 to ρ(d) = 1 for every d ≥ D (the obscurance distance, scene units). Hits beyond D do
// not occlude, so a closed room is no longer black (AO = 0 everywhere) and W → AO as D → ∞.
// The baker's estimator under cosine-weighted sampling is W = (1/N) Σ_s ρ(d_s); the bent
// normal is the normalised Σ_s ρ(d_s) ω_s. docs/SSAO.md has the derivation and the choices.
//
// Falloffs, t = d / D clamped to [0, 1]:
//   linear       ρ = t
//   exponential  ρ = (1 − e^(−4t)) / (1 − e^(−4))   (Iones et al.'s 1 − e^(−τd), rescaled so that
//                                                     ρ(D) = 1; τ = 4/D)
//   smoothstep   ρ = 3t² − 2t³
//   constant     ρ = 0 for d < D, 1 otherwise       (AO with a maximum ray length D)
#pragma once

#include <optional>
#include <string>

namespace prt::bake {

enum class ObscuranceFalloff { Linear, Exponential, Smoothstep, Constant };

// Obscurance instead of plain AO when distance > 0 (BakeOptions::obscurance).
struct ObscuranceOptions {
  double distance = 0.0;  // D in scene units; 0: off (plain AO, visibility only)
  ObscuranceFalloff falloff = ObscuranceFalloff::Linear;
  bool enabled() const { return distance > 0.0; }
};

// ρ(d) for a hit at distance d ≥ 0 (d = ∞ for a ray that escapes: 1).
double obscurance_weight(ObscuranceFalloff falloff, double d, double D);

// "linear", "exponential", "smoothstep", "constant".
const char* obscurance_falloff_name(ObscuranceFalloff falloff);
// The falloff named `text`, or nothing.
std::optional<ObscuranceFalloff> parse_obscurance_falloff(const std::string& text);

}  // namespace prt::bake
