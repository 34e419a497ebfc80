// prt/haar/approximation.h — choosing which Haar lighting coefficients to keep.
//
// Ng, Ramamoorthi & Hanrahan, "All-Frequency Shadows Using Non-linear Wavelet Lighting
// Approximation" (SIGGRAPH 2003), Sec. 4–5: a *non-linear* approximation keeps the K
// coefficients that matter most for this particular lighting, wherever they are; a *linear*
// one keeps a fixed set, the K coarsest. Ng et al. discuss weighting the lighting coefficients
// before choosing, notably by the area their basis functions cover ("area-weighted").
//
// Our area weight, precisely: the term c·ψ_q changes radiance by ±c/s over its s×s-texel
// support (see prt/haar/transform.h), so the power it moves is
//     |c| · w_q,   w_q = ∫ |ψ_q| dω = Ω_support(q) / s,
// with Ω_support the exact solid angle of the support (sum of exact texel solid angles).
// Because the support spans s² texels of solid angle ≈ Ω/s², w_q ≈ √(Ω_support · ω_texel):
// the area weighting of Ng et al., made exact for unequal cube texels. Colour: a coefficient's
// score is w_q · max over R, G, B of |c| (max, not luminance, so a saturated light of any hue
// keeps its terms). The K highest scores are kept; equal scores go to the lower wavelet index
// (deterministic). Non-finite coefficients count as 0 (score and value).
//
// Indices are wavelet indices i = face·N² + q (prt/haar/transform.h). Compiles as C++17.
// References: [4] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/haar/transform.h"

namespace prt {

// A sparse lighting vector in the Haar basis: the kept terms, by ascending wavelet index.
struct SparseLighting {
  int size = 0;                 // N of the cube map the coefficients belong to
  std::vector<uint32_t> index;  // wavelet indices i = face·N² + q, strictly ascending
  std::vector<float> rgb;       // 3 values per kept index
  size_t term_count() const { return index.size(); }
};

// Area weights w_q = Ω_support(q)/s for q ∈ [0, N²) (identical for all six faces).
std::vector<double> haar_area_weights(int size);

// Score of a coefficient: w · max_c |rgb[c]| (0 for non-finite values).
double haar_selection_score(double area_weight, const float rgb[3]) noexcept;

// Non-linear approximation: the min(k, 6N²) coefficients with the highest area-weighted
// score, over all faces and channels jointly (see above). k < 0 counts as 0.
SparseLighting select_nonlinear(const WaveletCube& lighting, int64_t k);

// Linear approximation: the min(k, 6N²) coarsest coefficients, ordered by level (the scaling
// coefficients first), then face, then q (so k = 6 keeps the six faces' scaling
// coefficients, k = 24 adds level 0, ...).
SparseLighting select_linear(const WaveletCube& lighting, int64_t k);

// Every coefficient (the exact lighting, for references and tests).
SparseLighting keep_all_terms(const WaveletCube& lighting);

}  // namespace prt
