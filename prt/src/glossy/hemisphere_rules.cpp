// prt/src/glossy/hemisphere_rules.cpp — Gauss–Legendre panels and hemisphere product rules.
#include "glossy/hemisphere_rules.h"

#include <algorithm>
#include <cmath>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"

namespace prt::glossy {

using numerics::append_gauss_legendre;
using numerics::kPi;

void graded_rule(double a, double b, double centre, const std::vector<double>& widths,
                 int per_panel, std::vector<double>* nodes, std::vector<double>* weights) {
  std::vector<double> edges{a, b};
  if (centre > a && centre < b) edges.push_back(centre);
  for (double w : widths) {
    if (centre - w > a && centre - w < b) edges.push_back(centre - w);
    if (centre + w > a && centre + w < b) edges.push_back(centre + w);
  }
  std::sort(edges.begin(), edges.end());
  for (std::size_t k = 0; k + 1 < edges.size(); ++k)
    if (edges[k + 1] - edges[k] > 1e-12)
      append_gauss_legendre(per_panel, edges[k], edges[k + 1], nodes, weights);
}

std::vector<HemisphereNode> graded_hemisphere_rule(const brdf::Vec3& lobe, int per_panel) {
  static const std::vector<double> kCosWidths{0.002, 0.01, 0.04, 0.12, 0.3, 0.6};
  static const std::vector<double> kPhiWidths{0.01, 0.04, 0.12, 0.35, 1.0, 2.0};
  const double phi_lobe = (lobe.x == 0.0 && lobe.y == 0.0) ? 0.0 : std::atan2(lobe.y, lobe.x);
  std::vector<double> c, wc, p, wp;
  graded_rule(0.0, 1.0, std::clamp(lobe.z, 0.0, 1.0), kCosWidths, per_panel, &c, &wc);
  graded_rule(phi_lobe - kPi, phi_lobe + kPi, phi_lobe, kPhiWidths, per_panel, &p, &wp);
  std::vector<HemisphereNode> rule;
  rule.reserve(c.size() * p.size());
  for (std::size_t i = 0; i < c.size(); ++i)
    for (std::size_t j = 0; j < p.size(); ++j)
      rule.push_back({brdf::spherical_direction(c[i], p[j]), wc[i] * wp[j]});
  return rule;
}

std::vector<HemisphereNode> product_hemisphere_rule(int theta, int phi) {
  std::vector<double> c, wc;
  const int panels = theta % 8 == 0 ? 8 : 1;
  for (int k = 0; k < panels; ++k)
    append_gauss_legendre(theta / panels, double(k) / panels, double(k + 1) / panels, &c, &wc);
  std::vector<HemisphereNode> rule;
  rule.reserve(c.size() * std::size_t(phi));
  const double step = 2.0 * kPi / phi;
  for (std::size_t i = 0; i < c.size(); ++i)
    for (int j = 0; j < phi; ++j)
      rule.push_back({brdf::spherical_direction(c[i], (j + 0.5) * step), wc[i] * step});
  return rule;
}

}  // namespace prt::glossy
