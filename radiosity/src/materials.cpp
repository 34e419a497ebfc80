#include "radiosity/materials.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace prt::radiosity {

std::string describe_colour(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%g, %g, %g)", double(v.x), double(v.y), double(v.z));
  return buf;
}

void check_materials(const scene::Scene& scene) {
  for (const scene::ScenePrimitive& p : scene.primitives) {
    const std::string where = scene.source_path + ": material " +
                              (p.material.empty() ? "<none>" : p.material) + " of " + p.name + ": ";
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(p.emission[c]) || p.emission[c] < 0.f)
        throw std::invalid_argument(where + "emission " + describe_colour(p.emission) +
                                    " must be finite and non-negative");
      if (!std::isfinite(p.albedo[c]) || p.albedo[c] < 0.f || p.albedo[c] > 1.f)
        throw std::invalid_argument(where + "albedo " + describe_colour(p.albedo) +
                                    " must be in [0, 1]");
    }
    for (uint32_t v = 0; v < p.vertex_count && p.first_vertex + v < scene.albedo.size(); ++v) {
      const glm::vec3 a = scene.albedo[p.first_vertex + v];
      for (int c = 0; c < 3; ++c)
        if (!std::isfinite(a[c]) || a[c] < 0.f || a[c] > 1.f)
          throw std::invalid_argument(where + "vertex albedo " + describe_colour(a) +
                                      " must be in [0, 1]");
    }
  }
}

bool has_unit_albedo(const scene::Scene& scene) {
  for (const glm::vec3& a : scene.albedo)
    if (a.x >= 1.f || a.y >= 1.f || a.z >= 1.f) return true;
  return false;
}

}  // namespace prt::radiosity
