// report/ssao_comparison.h — screen-space AO measured against ray-traced AO, pixel by pixel, for
// `prt report --ssao` (docs/SSAO.md).
//
// Input: what a renderer read back for one camera (the viewer's page, web/ssao_page.js): per
// pixel, the world-space position and normal of the surface seen (a G-buffer; coverage in the
// position's 4th value) and AO estimates in [0, 1] (1 = open): classic SSAO, GTAO, and the
// file's per-vertex AO interpolated over the triangles ("baked"). Rows bottom to top, 4 floats
// per pixel, the estimate in the first.
// The truth is traced here at the G-buffer's own points (Embree, the scene's triangles): N
// cosine-weighted Owen-scrambled Sobol' rays per pixel (bake/sampling.h) from the point, offset
// 2·10⁻⁴ × the scene's diagonal along the normal; AO = the mean visibility and, when an
// obscurance distance D > 0 is given, obscurance = the mean ρ(d) of bake/obscurance_falloff.h.
// Per pixel it also records the nearest hit among those rays and the thickness of the surface
// (the distance to the first surface along −n from just below the point; ∞ when none).
// Errors, per estimate and truth: relative RMS = √(Σ(e − t)²/Σt²), RMS, and the mean signed error
// (bias), over every pixel showing the front side of a surface and over the regions where
// screen-space AO is known to fail:
//   contact   pixels with a surface closer than contact_fraction × R (R the screen-space radius):
//             object/ground contact and creases;
//   thin      pixels on a surface thinner than thin_fraction × R (the depth buffer shows it as
//             infinitely thick);
//   edge      pixels within edge_fraction × the image height of the border (their samples fall
//             off screen) — and "interior", the rest;
//   distance  the distance from the eye, in equal bins between the nearest and farthest pixel.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake/obscurance_falloff.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace prt::report {

struct AoCapture {
  std::string name;  // the camera's name
  int width = 0, height = 0;
  glm::vec3 eye{0.f};
  std::vector<float> position, normal;        // 4 per pixel (see above)
  std::vector<std::vector<float>> estimates;  // 4 per pixel each, AO in the first
  std::vector<std::string> estimate_names;    // e.g. "ssao", "gtao", "baked"
  // A surface covers the pixel (position w = 1: its front side, 2: its back side).
  bool covered(std::size_t pixel) const { return position[4 * pixel + 3] > 0.5f; }
  // Measured: the front side of a surface (its back side has no baked AO to compare with).
  bool front(std::size_t pixel) const {
    const float w = position[4 * pixel + 3];
    return w > 0.5f && w < 1.5f;
  }
};

struct PixelTruthOptions {
  int rays = 256;  // per pixel, rounded up to a multiple of 16
  uint64_t seed = 1;
  bake::ObscuranceOptions obscurance;  // distance > 0: obscurance too
};

// Per pixel (uncovered pixels: ao = obscurance = −1).
struct PixelTruth {
  std::vector<float> ao, obscurance;  // obscurance empty when no distance was given
  std::vector<float> nearest;         // nearest hit distance (∞ when every ray escaped)
  std::vector<float> thickness;       // along −n (∞ when nothing is below)
  int rays = 0;
};

// Traces the truth at the capture's pixels (threads: TBB).
PixelTruth trace_pixel_truth(const scene::Scene& scene, const scene::RayCaster& caster,
                             const AoCapture& capture, const PixelTruthOptions& options);

struct ErrorStats {
  uint64_t pixels = 0;
  double relative_rms = 0, rms = 0, bias = 0, truth_mean = 0;
};

struct RegionRule {
  double radius = 1;              // R, the screen-space radius in scene units
  double contact_fraction = 0.1;  // contact: nearest hit < this × R
  double thin_fraction = 0.25;    // thin: thickness < this × R
  double edge_fraction = 0.1;     // edge band: this × height pixels from the border
};

// Accumulates squared errors; several cameras may add to one.
struct ErrorAccumulator {
  double sum_e2 = 0, sum_t2 = 0, sum_e = 0, sum_t = 0;
  uint64_t n = 0;
  void add(double estimate, double truth);
  void merge(const ErrorAccumulator& other);
  ErrorStats stats() const;
};

// One estimate against one truth: every region's accumulator, and the distance bins.
struct RegionErrors {
  ErrorAccumulator all, contact, thin, edge, interior;
  std::vector<ErrorAccumulator> distance;  // one per bin
  void merge(const RegionErrors& other);
};

// Adds the covered pixels of `capture`'s estimate `estimate` against `truth` (one value per
// pixel, −1 where uncovered) to `out`, binning the eye distance in [d_lo, d_hi) into
// out.distance.size() bins (clamped to the ends).
void accumulate_errors(const AoCapture& capture, int estimate, const std::vector<float>& truth,
                       const PixelTruth& traced, const RegionRule& rule, double d_lo, double d_hi,
                       RegionErrors& out);

// The smallest and largest eye distance of the covered pixels.
void eye_distance_range(const AoCapture& capture, double& lo, double& hi);

}  // namespace prt::report
