// radiosity/form_factors.h — form factors between diffuse patches, two ways:
//
//   analytic: the point-to-polygon form factor by Lambert's contour formula, as used for
//     radiosity by Baum, Rushmeier & Winget 1989 ([43] of docs/REFERENCES.md):
//       F(x → P) = (1 / 2π) · Σ_k β_k · (n · γ_k),
//     over the edges (v_k, v_k+1) of the polygon P (first clipped to the half-space in front of
//     x), β_k the angle the edge subtends at x and γ_k the unit normal of the plane through x
//     and the edge; exact for an unoccluded polygon. F_ij averages F(x_k → P_j) · V_k over
//     quadrature points x_k of patch i (`quadrature_points`: 1 = the centroid; 3 = the
//     degree-2 rule at barycentrics (2/3, 1/6, 1/6) and permutations), V_k ∈ {0, 1} the
//     visibility of the segment from x_k to the matching point y_k of patch j (an Embree
//     occlusion ray; origins by scene::RayCaster::surface_origin). Sampled visibility can count
//     an occluder and the polygon behind it both in full; a row that then sums above 1 is
//     scaled to sum to 1.
//   rays: Monte Carlo — `rays_per_patch` cosine-distributed rays (`emitter_rays_per_patch` from
//     a patch whose emission is not zero, when given) leave uniformly distributed points of
//     patch i; F_ij is the fraction whose closest hit is the front face of patch j
//     (the estimator is unbiased; with independent samples its standard error is
//     √(F(1 − F)/N), with the stratified Sobol' samples it is lower; see RaySampling).
//     Emitters' rows may instead come from the receivers by reciprocity (EmitterRows).
//   hemicube: Cohen & Greenberg 1985 ([24]): the scene's patches rasterised with a z-buffer onto
//     a hemicube of `hemicube_resolution` cells across its top face (R × R/2 on each side face)
//     at the centroid of patch i; each cell credits the patch whose front face it shows with its
//     exact delta form factor (radiosity/hemicube.h), so the cells sum to 1. The ray caster is
//     not used (radiosity/hemicube.h has the ray-cast item buffer as a second method).
//     compute_form_factors combines the two hemicubes of every pair, weighted by the other
//     patch's area (combine_hemicube_estimates, radiosity/hemicube.h), so that receivers
//     smaller than a cell are not aliased; form_factor_row and hemicube_row give the raw row
//     of the hemicube at i (progressive refinement shoots those).
//
// F_ij is the fraction of the power leaving patch i that arrives at the front of patch j; patch
// i's row is computed at i (the sender), so every row sums to at most 1 (analytic: up to float
// rounding and the clipped-polygon approximation; rays: exactly the fraction that hit a front
// face). 1 − Σ_j F_ij leaves the scene or lands on a back face. Random numbers come from a
// generator seeded by (seed, i), so a row does not depend on the thread count or on which other
// rows are computed. Frame and units: the Scene's.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

// Lambert's formula for the differential area at x with unit normal n and the polygon `polygon`
// (any winding; the part behind x's tangent plane is clipped off; both sides of the polygon
// receive). Returns a value in [0, 1].
double point_polygon_form_factor(const glm::dvec3& x, const glm::dvec3& n,
                                 const std::vector<glm::dvec3>& polygon);

// Patch-to-patch form factor between two planar convex polygons with no occluder,
// F_AB = (1 / A_A) ∫_A F(x → B) dx: each fan triangle of A is split into m² congruent triangles
// and the point-to-polygon value is taken at their centroids (m = quadrature_steps).
// Normal of A: from its winding (counter-clockwise = front).
double polygon_polygon_form_factor(const std::vector<glm::dvec3>& a,
                                   const std::vector<glm::dvec3>& b, int quadrature_steps);

enum class FormFactorMethod { Analytic, Rays, Hemicube };

// rays: how a row's 4-D samples (two uniforms for the point on the patch, two for the
// direction) are drawn. Both are unbiased and depend only on (seed, row).
enum class RaySampling {
  Independent,  // every sample from the row's pseudo-random stream
  Sobol,        // the first N points of the 4-D Sobol' sequence, scrambled (nested) per row
                // (numerics/low_discrepancy.h; [90], [91] of docs/REFERENCES.md): stratified in
                // every projection
};

// rays: how the rows of emitting patches (emission ≠ 0) are made.
enum class EmitterRows {
  Rays,        // like every other row, with emitter_rays_per_patch rays when that is > 0
  Reciprocal,  // F_ej = A_j · F_je / A_e, F_je the analytic value (quadrature_points points of
               // receiver j, one visibility ray each; as the analytic method): no ray noise in
               // the direct light. The row is then scaled to sum to at most 1. It is checked
               // against the emitter's own ray row (rays_of: emitter_rays_per_patch or
               // rays_per_patch rays), which replaces it when the sums differ by more than
               // max(10%, 4 standard errors of the ray sum): a few points per receiver miss
               // most of an emitter's light when receivers are much larger than their distance
               // to it (coarse patches next to a lamp; docs/RADIOSITY.md, "Coarse patches").
};

struct FormFactorOptions {
  FormFactorMethod method = FormFactorMethod::Analytic;
  int quadrature_points = 3;  // analytic: 1 (centroid) or 3 (degree-2 rule)
  int rays_per_patch = 4096;  // rays
  // rays: rays from each emitting patch (emission ≠ 0); 0 = rays_per_patch. Direct light is
  // estimated from the emitters' rows, so their noise dominates unless they shoot more.
  int emitter_rays_per_patch = 0;
  uint64_t seed = 1;                             // rays
  RaySampling sampling = RaySampling::Sobol;     // rays
  EmitterRows emitter_rows = EmitterRows::Rays;  // rays
  int hemicube_resolution = 64;  // hemicube: cells across the top face (even, 2..4096)
};

// Row i of F (sender i), `patches.size()` floats.
void form_factor_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                     const FormFactorOptions& options, std::vector<float>* row);

// The hemicube row of patch i (see above).
void hemicube_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                  int resolution, std::vector<float>* row);

// The whole matrix, row-major (row i = sender i), rows computed in parallel (TBB).
struct FormFactorMatrix {
  std::size_t size = 0;
  std::vector<float> f;  // size²
  float at(std::size_t i, std::size_t j) const { return f[i * size + j]; }
  double row_sum(std::size_t i) const;
};

FormFactorMatrix compute_form_factors(const std::vector<Patch>& patches,
                                      const scene::RayCaster& caster,
                                      const FormFactorOptions& options);

// Area-weighted fraction of cosine-distributed rays (rays_per_patch per patch, points uniform on
// each patch) that leave the scene without hitting anything: 0 for a closed scene.
double escape_fraction(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                       int rays_per_patch, uint64_t seed);

}  // namespace prt::radiosity
