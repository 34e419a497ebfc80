// prt/src/glossy/hemisphere_rules.h — private: quadrature rules on the local hemisphere used by
// the BRDF projections (prt/glossy/brdf_projection.h), built from numerics/gauss_legendre.h's rule.
#pragma once

#include <vector>

#include "prt/brdf/vec3.h"

namespace prt::glossy {

// Gauss–Legendre panels on [a, b] with breakpoints at centre ± w for each w in `widths` (those
// inside (a, b)), `per_panel` nodes each.
void graded_rule(double a, double b, double centre, const std::vector<double>& widths,
                 int per_panel, std::vector<double>* nodes, std::vector<double>* weights);

struct HemisphereNode {
  brdf::Vec3 w;   // unit, z ≥ 0
  double weight;  // solid angle
};

// Product rule over the upper hemisphere in (cos θ, φ), graded towards the direction `lobe`
// (unit, z > 0 expected; a lobe at the pole is fine): panels in cos θ around lobe.z and in φ
// around the lobe's azimuth, cos θ = 0 and cos θ = 1 panel edges.
std::vector<HemisphereNode> graded_hemisphere_rule(const brdf::Vec3& lobe, int per_panel);

// Fixed product rule: `theta` Gauss–Legendre nodes in cos θ ∈ [0, 1] (in 8 equal panels when
// theta is a multiple of 8, else one panel) × `phi` uniform nodes in φ (offset by half a step).
std::vector<HemisphereNode> product_hemisphere_rule(int theta, int phi);

}  // namespace prt::glossy
