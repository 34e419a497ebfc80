// relight/shown_window.h — the automatic window of `prt relight` (--window auto), chosen on what
// the run shows: the exit radiance of the file's own vertices in every view it renders.
//
// Why not the lighting alone: sh::choose_window_auto keeps the *unshadowed irradiance*
// non-negative, but shadowed transfer (a vertex that sees only part of the sky) and glossy
// transfer (a sharp BRDF lobe against a ringing lighting) can still shade below zero with that
// window. Exit radiance is linear in the lighting and a window scales band l by h_l, so for one
// view (a lighting rotation and, for glossy files, an eye point)
//   B_v,c(h) = Σ_l h_l s_v,c,l,   s_v,c,l = the shading of band l of the lighting alone,
// computed once per view by `order` calls of the file's own kernel (O(V·n²) per call for
// diffuse files). Each candidate window then costs O(V·n) per view, and vertices with
// s_0 − Σ_{l≥1}|s_l| above the margin pass every candidate and are skipped.
//
// Candidates, weakest first: None, then Sloan's Laplacian h_l = 1/(1 + λ l²(l+1)²) with
// λ_j = λ_1·2^((j−1)/4), λ_1 = 1/(100·(n−1)²n²) (the last band keeps 99 %), up to λ ≥ 1e6
// (band 1 keeps 2.5e-7: the lighting's mean alone). The choice is the first candidate under
// which no vertex of any view has a channel below kShownWindowMargin·Σ_l h_l|s_v,c,l| (a margin
// over the float rounding of the kernels, so that the render's own count agrees), leaving out
// the vertices that fail even under the strongest candidate: those the transfer itself shades
// below zero under the lighting's mean (glossy transfer of a sharp lobe next to an occluder),
// which no lighting window removes; they are counted apart. The strongest candidate thus always
// qualifies (for order 1 there is only None).
// Counts of negative vertices (a channel < 0, as the render counts them) are the most in any
// one view. References: Sloan, "Stupid SH tricks", GDC 2008 ([6] of docs/REFERENCES.md).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "prt/lighting/sh_lighting.h"
#include "sh/window.h"

namespace prt::relight {

// Relative margin of the choice (see above): about 100× float rounding of an order-10 sum.
constexpr double kShownWindowMargin = 1e-5;

// Exit radiance of every vertex under one lighting, 3 floats per vertex (a file's shading for
// one view).
using ShadeVertices = std::function<std::vector<float>(const prt::ShLighting&)>;

struct ShownWindowChoice {
  sh::Window window = sh::Window::None;  // None or Laplacian
  double strength = 0.0;                 // λ for Laplacian, 0 for None
  std::size_t vertices = 0;              // per view
  int views = 0;
  std::size_t negative_before = 0;  // most vertices with a negative channel in a view, no window
  std::size_t negative_after = 0;   // the same under the chosen window
  // Most vertices in a view that fail the margin test even under the strongest candidate (the
  // lighting's mean alone): the transfer itself shades them below zero, which no window of the
  // lighting removes. They are left out of the choice.
  std::size_t unremovable = 0;
};

class ShownWindowSearch {
 public:
  explicit ShownWindowSearch(int order);

  // The candidates' λ, weakest first; [0] = 0 stands for None.
  const std::vector<double>& strengths() const { return lambdas_; }

  // Adds a view from its band sums: bands[(v·3 + c)·order + l] = s_v,c,l, v < vertex_count.
  // Throws std::invalid_argument when the size does not match or the vertex count changes.
  void add_view_bands(const std::vector<float>& bands, std::size_t vertex_count);

  // Shades each band of `lighting` alone (`order` calls of shade) and adds the view.
  void add_view(const prt::ShLighting& lighting, const ShadeVertices& shade);

  ShownWindowChoice choose() const;

 private:
  struct RangeCounts {
    std::vector<std::size_t> failing, negative;  // per candidate
    std::size_t intrinsic = 0;                   // vertices no candidate lifts
  };
  // The counts of add_view_bands over vertices first .. end − 1.
  RangeCounts count_range(const std::vector<float>& bands, std::size_t first,
                          std::size_t end) const;

  int order_;
  std::vector<double> lambdas_;
  std::vector<double> factors_;        // h of candidate j at band l: [j·order + l]
  std::vector<std::size_t> failing_;   // per candidate: most vertices below the margin, a view
  std::vector<std::size_t> negative_;  // per candidate: most vertices below 0, a view
  std::size_t unremovable_ = 0;        // most unremovable vertices in a view
  std::size_t vertices_ = 0;
  int views_ = 0;
};

// "window auto: laplacian, strength 2.1e-05, the weakest that leaves none of the 507 vertices
// negative in the 1 view rendered (28 are without a window)", or what remains when no
// candidate removes the ringing.
std::string describe_shown_window(const ShownWindowChoice& choice);

// Windows `lighting` as chosen and returns describe_shown_window(choice). Throws on failure.
std::string apply_shown_window(const ShownWindowChoice& choice, prt::ShLighting* lighting);

}  // namespace prt::relight
