// Errors of hemicube form factors against closed forms and Lambert's formula, for the hemicube
// tests and the hemicube_resolution_error bench.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/hemicube.h"
#include "radiosity/patches.h"
#include "scene/material_assignment.h"
#include "scene/scene.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace prt::test {

// Square B of two_squares (radiosity_fixtures.h) as a polygon seen from square A: parallel
// (opposite) or perpendicular.
inline const std::vector<glm::dvec3> kOppositeUnitSquare = {
    {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1}};
inline const std::vector<glm::dvec3> kPerpendicularUnitSquare = {
    {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1}};

// F from the first `half` patches (square A) to the rest (square B) by hemicubes, area-weighted.
inline double hemicube_square_to_square(const std::vector<radiosity::Patch>& patches,
                                        std::size_t half, int r) {
  double weighted = 0.0, area = 0.0;
  std::vector<float> row;
  radiosity::HemicubeBuffer buffer;
  for (uint32_t i = 0; i < half; ++i) {
    radiosity::rasterize_hemicube(patches, i, r, &buffer);
    radiosity::hemicube_form_factors(buffer, patches.size(), &row);
    area += patches[i].area;
    for (std::size_t j = half; j < patches.size(); ++j) weighted += patches[i].area * row[j];
  }
  return weighted / area;
}

// The largest |hemicube − Lambert at the centroid| over A's patches (point value: the
// hemicube's own error, without the collocation error of standing at one point).
inline double worst_point_error(const std::vector<radiosity::Patch>& patches, std::size_t half,
                                const std::vector<glm::dvec3>& b, int r) {
  double worst = 0.0;
  std::vector<float> row;
  radiosity::HemicubeBuffer buffer;
  for (uint32_t i = 0; i < half; ++i) {
    radiosity::rasterize_hemicube(patches, i, r, &buffer);
    radiosity::hemicube_form_factors(buffer, patches.size(), &row);
    double f = 0.0;
    for (std::size_t j = half; j < patches.size(); ++j) f += row[j];
    worst = std::max(worst, std::abs(f - radiosity::point_polygon_form_factor(
                                             patches[i].centroid, patches[i].normal, b)));
  }
  return worst;
}

// The Cornell box OBJ at `path`, its white walls at albedo 0.73, subdivided to `max_edge`.
inline scene::Scene cornell_box(const std::string& path, double max_edge) {
  scene::Scene scene = scene::load_scene(path);
  scene::apply_albedo(scene, {scene::parse_material_colour("--albedo", "white=0.73")});
  return scene::subdivide_to_edge_length(scene, max_edge);
}

// Area-weighted mean over rows of Σ_j |F_ij − G_ij| (the share of row i's power sent to a
// different patch), and the largest such row difference.
inline std::pair<double, double> row_difference(const std::vector<radiosity::Patch>& patches,
                                                const radiosity::FormFactorMatrix& f,
                                                const radiosity::FormFactorMatrix& g) {
  double weighted = 0.0, area = 0.0, worst = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    double d = 0.0;
    for (std::size_t j = 0; j < patches.size(); ++j) d += std::abs(double(f.at(i, j)) - g.at(i, j));
    weighted += patches[i].area * d;
    area += patches[i].area;
    worst = std::max(worst, d);
  }
  return {weighted / area, worst};
}

}  // namespace prt::test
