// radiosity/hemicube.h — the hemicube of Cohen & Greenberg 1985 ([24] of docs/REFERENCES.md):
// the patches seen from the centroid of patch i are rasterised with a z-buffer onto the five
// faces of a unit hemicube standing on the patch, and each cell hands its delta form factor to
// the patch it shows.
//
// Frame: the hemicube's local frame (t, b, n) at the centroid c of patch i, n its front normal,
// t = normalize(helper × n), b = n × t (helper = +y when |n.x| > 0.9, else +x). The faces sit at
// distance 1 from c: the top (face 0) spans [−1, 1]² at n = 1; the side faces (1: +t, 2: −t,
// 3: +b, 4: −b) span [−1, 1] across and [0, 1] up (the half above the patch's plane). A face
// maps local points p = (x, y, z) to face coordinates (s, h, d), d the depth along the face's
// axis: top (x, y, z); +t (y, z, x); −t (y, z, −x); +b (x, z, y); −b (x, z, −y).
// Cells: R × R on top, R across × R/2 up on each side (R even), row-major, index y·R + x; cell
// (x, y) covers s ∈ −1 + [x, x + 1]·2/R and h ∈ −1 + [y, y + 1]·2/R (top) or h ∈ [y, y + 1]·2/R
// (sides, y = 0 at the base). A cell shows what lies along the ray from c through its centre.
//
// Delta form factors: the exact form factor from the differential area at c to the cell
// (Lambert's formula, radiosity/form_factors.h), so the 3R² cells tile the hemisphere and sum to
// 1 up to rounding; ≈ ΔA / (π (s² + h² + 1)²) on top and h·ΔA / (π (s² + h² + 1)²) on the
// sides. Stored once per resolution with the symmetries of the faces: the top face's eight
// (x ↔ R−1−x, y ↔ R−1−y, x ↔ y), (R/2)(R/2 + 1)/2 values; the sides' mirror across s = 0
// (all four alike), (R/2)² values.
//
// Rasterisation (our own; no graphics API): each patch j ≠ i is transformed to the local frame
// once, then per face clipped (Sutherland–Hodgman) to the face's view frustum — the near plane
// d ≥ 1e-6·√A_i, the four planes |s| ≤ d and |h| ≤ d, and for the side faces the hemicube's base
// plane h ≥ 0 — whose projection bounds the cells to visit; each cell centre is tested with the
// triangle's homogeneous edge functions in double (Olano & Greer 1997, [81] of
// docs/REFERENCES.md) and a top-left fill rule (a cell centre exactly on an edge shared by two
// patches belongs to exactly one). Depth: 1/d from the patch's plane (exact, affine on the face),
// the nearest wins. Every patch occludes; a cell credits j only when it shows j's front face (c in
// front of j's plane, the one-sided convention of radiosity/patches.h); back faces and empty
// cells credit nothing (their share escapes). Cost per patch i: O(N) transforms plus the
// clipped patches' bounding boxes, plus the 3R² cells. Memory: 12 bytes per cell and thread
// (item and depth buffers, kept per thread): 3 MB at R = 512, 600 MB at R = 4096.
//
// Combined estimate (what compute_form_factors returns for the hemicube method). A hemicube at
// patch i resolves patch j only as finely as its cells: a receiver j that covers less than a
// cell's solid angle gets 0 or 1 cell, so F_ij is 0 or several times too large. In the gather
// L_j = E_j + ρ_j Σ_i (A_i F_ij / A_j) L_i that error is divided by the small A_j, and on a
// regular grid of small receivers (refined patches, radiosity/patch_refinement.h) the 0s and 1s
// form a checkerboard. Every pair has a second estimate of the same quantity G_ij = A_i F_ij =
// A_j F_ji: the hemicube at j, in which i is seen with A_i/A_j times as many cells. With the
// aliasing error of a patch covering n cells taken as ∝ √n cells (edge cells), the two
// estimates' standard errors are ∝ √(A_i G δ) and √(A_j G δ) (δ a cell's delta form factor), so
// the inverse-variance combination is
//     G_ij = A_i A_j / (A_i + A_j) · (F^(i)_ij + F^(j)_ji),
// which weights each hemicube by the other patch's area: a small receiver's light comes from
// its own hemicube (Cohen & Greenberg's gathering), equal patches average the two. G is
// symmetric. Rows F_ij = G_ij / A_i that sum above 1 are scaled to 1, and so are the rows of
// patches whose own hemicube saw nothing escape (raw sum ≥ 1 − 1e-6, exact there): rows sum to
// 1 in a closed scene, as they must (the combination alone loses what both centroids
// under-estimate of near neighbours: down to 0.93 on a box of 48 patches). Other rows keep
// their combined sum: scaling them to their raw sums was tried and is worse, since a large
// sender's raw sum carries the error of standing at its centroid only (+3.9% for the lamp of
// test_radiosity's floor).
// A row then depends on every other row: progressive refinement (rows on demand) and the
// partial update after a move (radiosity/form_factor_update.h) recompute from raw rows.
//
// The second, independent item buffer `ray_cast_hemicube` shoots one Embree ray per cell centre
// (from scene::RayCaster::surface_origin at c); the two agree cell for cell except where a
// cell's centre lies within float rounding of a patch's edge.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

constexpr uint32_t kHemicubeEmpty = 0xFFFFFFFFu;     // nothing along the cell's ray
constexpr uint32_t kHemicubeBackFace = 0xFFFFFFFEu;  // the back face of some patch

// Resolution R: even, 2..4096; anything else throws std::invalid_argument.
void check_hemicube_resolution(int resolution);

class DeltaFormFactors {
 public:
  explicit DeltaFormFactors(int resolution);
  int resolution() const { return r_; }
  double top(int x, int y) const;   // x, y in [0, R)
  double side(int x, int y) const;  // x in [0, R), y in [0, R/2)
  double cell(int face, int x, int y) const { return face == 0 ? top(x, y) : side(x, y); }
  std::size_t stored_values() const { return top_.size() + side_.size(); }

 private:
  int fold(int x) const { return x >= r_ / 2 ? x - r_ / 2 : r_ / 2 - 1 - x; }
  int r_ = 0;
  std::vector<double> top_, side_;
};

// The table of resolution R, computed on first use and kept (thread-safe).
const DeltaFormFactors& delta_form_factors(int resolution);

// The hemicube's frame at patch p (see above).
void hemicube_frame(const Patch& p, glm::dvec3* t, glm::dvec3* b);

struct HemicubeBuffer {
  int resolution = 0;
  std::array<std::vector<uint32_t>, 5> faces;  // patch ids, kHemicubeEmpty, kHemicubeBackFace
};

// The z-buffered item buffer of patch i.
void rasterize_hemicube(const std::vector<Patch>& patches, uint32_t i, int resolution,
                        HemicubeBuffer* buffer);

// The same item buffer with one ray per cell centre (a second, independent method).
void ray_cast_hemicube(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                       uint32_t i, int resolution, HemicubeBuffer* buffer);

// F_ij = Σ of the delta form factors of the cells showing j's front face; `patch_count` floats.
void hemicube_form_factors(const HemicubeBuffer& buffer, std::size_t patch_count,
                           std::vector<float>* row);

// Replaces raw hemicube rows F^(i) (row i from the hemicube at i; `f` holds all of them) by the
// combined estimate above, in place; entries of zero-area patches become 0.
void combine_hemicube_estimates(const std::vector<Patch>& patches, std::vector<float>* f);

}  // namespace prt::radiosity
