// bake/subsurface_approx/surface_blur.h — a normalised Gaussian blur of per-vertex values over a
// mesh, by straight-line distance between vertices.
//
// blurred_v = Σ_j a_j g(|x_v − x_j|) f_j / Σ_j a_j g(|x_v − x_j|),  g(r) = e^{−r²/2σ²},
// over the vertices j of v's own group (a translucent object: values never cross between
// groups; group −1 is left out, its vertices keep their own values), with a_j the vertex's area
// (a third of its triangles' areas: vertex_areas() of bake/subsurface/subsurface_baker.h) and the
// sum cut at r ≤ kBlurCutoff·σ (the 2D Gaussian's mass beyond 3.5σ is e^{−6.125} = 0.2%).
// Normalised, so the blur of a constant field is that constant, at an object's edges too, as a
// texture-space blur of a filled atlas is. Straight-line distance is the dipole bake's metric
// (Jensen et al. 2001): light crosses a thin part through its thickness, as it does in the dipole,
// where a geodesic blur (repeated mesh smoothing) would carry it only around the rim. Cost: O(Σ_v
// neighbours of v within the cutoff) with a hash grid of cell kBlurCutoff·σ; vertices run in
// parallel, each summed in a fixed order (bit-identical for any thread count).
#pragma once

#include <cstdint>
#include <vector>

#include "scene/scene.h"

namespace prt::bake {

inline constexpr double kBlurCutoff = 3.5;

// Blurs `values` (`width` floats per vertex, vertex-major) with standard deviation sigma (scene
// units, > 0). `group` has one entry per vertex (−1: not blurred). Returns the blurred values.
std::vector<double> blur_over_surface(const scene::Scene& scene, const std::vector<double>& areas,
                                      const std::vector<int32_t>& group,
                                      const std::vector<double>& values, int width, double sigma);

}  // namespace prt::bake
