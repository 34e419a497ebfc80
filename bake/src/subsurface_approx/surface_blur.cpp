// A normalised Gaussian blur over a mesh by straight-line distance (see
// bake/subsurface_approx/surface_blur.h).
#include "bake/subsurface_approx/surface_blur.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include <tbb/parallel_for.h>

namespace prt::bake {
namespace {

struct CellKey {
  int64_t x, y, z;
  bool operator==(const CellKey& o) const { return x == o.x && y == o.y && z == o.z; }
};
struct CellHash {
  std::size_t operator()(const CellKey& k) const {
    uint64_t h = uint64_t(k.x) * 0x9E3779B97F4A7C15ull;
    h ^= uint64_t(k.y) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= uint64_t(k.z) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return static_cast<std::size_t>(h);
  }
};

CellKey cell_of(const glm::vec3& p, double cell) {
  return {static_cast<int64_t>(std::floor(p.x / cell)),
          static_cast<int64_t>(std::floor(p.y / cell)),
          static_cast<int64_t>(std::floor(p.z / cell))};
}

}  // namespace

std::vector<double> blur_over_surface(const scene::Scene& scene, const std::vector<double>& areas,
                                      const std::vector<int32_t>& group,
                                      const std::vector<double>& values, int width, double sigma) {
  const std::size_t n = scene.positions.size();
  const double radius = kBlurCutoff * sigma, inv_two_var = 1.0 / (2 * sigma * sigma);
  // Vertices of each cell, in vertex order (so every sum runs in a fixed order).
  std::unordered_map<CellKey, std::vector<uint32_t>, CellHash> cells;
  for (uint32_t v = 0; v < n; ++v)
    if (group[v] >= 0) cells[cell_of(scene.positions[v], radius)].push_back(v);
  std::vector<double> out(values);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    if (group[v] < 0) return;
    const glm::dvec3 p(scene.positions[v]);
    const CellKey c = cell_of(scene.positions[v], radius);
    std::vector<double> sum(width, 0.0);
    double weight = 0;
    for (int64_t dz = -1; dz <= 1; ++dz)
      for (int64_t dy = -1; dy <= 1; ++dy)
        for (int64_t dx = -1; dx <= 1; ++dx) {
          const auto it = cells.find({c.x + dx, c.y + dy, c.z + dz});
          if (it == cells.end()) continue;
          for (uint32_t j : it->second) {
            if (group[j] != group[v]) continue;
            const glm::dvec3 d = glm::dvec3(scene.positions[j]) - p;
            const double r2 = glm::dot(d, d);
            if (r2 > radius * radius) continue;
            const double w = areas[j] * std::exp(-r2 * inv_two_var);
            weight += w;
            const double* f = &values[std::size_t(j) * width];
            for (int k = 0; k < width; ++k) sum[k] += w * f[k];
          }
        }
    if (weight <= 0) return;  // an isolated vertex keeps its value
    for (int k = 0; k < width; ++k) out[v * width + k] = sum[k] / weight;
  });
  return out;
}

}  // namespace prt::bake
