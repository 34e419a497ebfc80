// The hemicube form factors of radiosity/form_factors.h, with the item buffer sampled by rays.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "radiosity/form_factors.h"

namespace prt::radiosity {
namespace {

struct Cell {
  glm::dvec3 direction;  // in the hemicube's frame (t, b, n): z along the normal
  double weight;         // delta form factor, normalised over the hemicube
};

// The cells of a hemicube of resolution r (even), weights summing to 1.
std::vector<Cell> hemicube_cells(int r) {
  std::vector<Cell> cells;
  const double d = 2.0 / r, area = d * d;
  for (int a = 0; a < r; ++a)
    for (int b = 0; b < r; ++b) {
      const double u = -1.0 + (a + 0.5) * d, v = -1.0 + (b + 0.5) * d;
      const double q = u * u + v * v + 1.0;
      cells.push_back({{u, v, 1.0}, area / (M_PI * q * q)});
    }
  for (int side = 0; side < 4; ++side)
    for (int a = 0; a < r; ++a)
      for (int b = 0; b < r / 2; ++b) {
        const double u = -1.0 + (a + 0.5) * d, w = (b + 0.5) * d;
        const double q = u * u + w * w + 1.0;
        const double weight = w * area / (M_PI * q * q);
        const glm::dvec3 dir = side == 0   ? glm::dvec3(1.0, u, w)
                               : side == 1 ? glm::dvec3(-1.0, u, w)
                               : side == 2 ? glm::dvec3(u, 1.0, w)
                                           : glm::dvec3(u, -1.0, w);
        cells.push_back({dir, weight});
      }
  double sum = 0.0;
  for (const Cell& c : cells) sum += c.weight;
  for (Cell& c : cells) c.weight /= sum;
  return cells;
}

}  // namespace

void hemicube_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                  int resolution, std::vector<float>* row) {
  if (resolution < 2 || resolution > 4096 || resolution % 2 != 0)
    throw std::invalid_argument("form factors: the hemicube resolution must be even, 2..4096");
  row->assign(patches.size(), 0.f);
  const Patch& s = patches[i];
  if (s.area <= 0.0) return;
  const std::vector<Cell> cells = hemicube_cells(resolution);
  const glm::dvec3 n = s.normal;
  const glm::dvec3 helper = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, n)), b = glm::cross(n, t);
  const glm::vec3 origin = caster.surface_origin(i, glm::vec3(s.centroid), glm::vec3(n));
  const float inf = std::numeric_limits<float>::infinity();
  std::vector<double> sums(patches.size(), 0.0);
  for (const Cell& c : cells) {
    const glm::dvec3 d = glm::normalize(t * c.direction.x + b * c.direction.y + n * c.direction.z);
    const scene::RayCaster::Hit hit = caster.intersect(origin, glm::vec3(d), 0.f, inf);
    if (hit.hit && hit.front_face && hit.triangle != i) sums[hit.triangle] += c.weight;
  }
  for (std::size_t j = 0; j < sums.size(); ++j) (*row)[j] = static_cast<float>(sums[j]);
}

}  // namespace prt::radiosity
