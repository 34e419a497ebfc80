#include "radiosity/patches.h"

#include <stdexcept>

namespace prt::radiosity {

std::vector<Patch> make_patches(const scene::Scene& scene) {
  std::vector<Patch> patches(scene.triangles.size());
  for (std::size_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    Patch& p = patches[t];
    for (int k = 0; k < 3; ++k) p.corners[k] = glm::dvec3(scene.positions[tri[k]]);
    p.centroid = (p.corners[0] + p.corners[1] + p.corners[2]) / 3.0;
    const glm::dvec3 cross = glm::cross(p.corners[1] - p.corners[0], p.corners[2] - p.corners[0]);
    const double length = glm::length(cross);
    p.area = 0.5 * length;
    if (length > 0.0) p.normal = cross / length;
    p.albedo = (glm::dvec3(scene.albedo[tri.x]) + glm::dvec3(scene.albedo[tri.y]) +
                glm::dvec3(scene.albedo[tri.z])) /
               3.0;
  }
  for (const scene::ScenePrimitive& primitive : scene.primitives)
    for (uint32_t k = 0; k < primitive.triangle_count; ++k)
      if (primitive.first_triangle + k < patches.size())
        patches[primitive.first_triangle + k].emission = glm::dvec3(primitive.emission);
  return patches;
}

std::vector<float> vertex_radiance(const scene::Scene& scene, const std::vector<Patch>& patches,
                                   const std::vector<glm::dvec3>& patch_radiance) {
  if (patches.size() != scene.triangles.size() || patch_radiance.size() != patches.size())
    throw std::invalid_argument("vertex_radiance: one patch and one radiance per triangle needed");
  std::vector<glm::dvec3> sum(scene.vertex_count(), glm::dvec3(0.0));
  std::vector<double> weight(scene.vertex_count(), 0.0);
  for (std::size_t t = 0; t < patches.size(); ++t) {
    if (!(patches[t].visible > 0.0)) continue;  // wholly hidden: seen from nowhere
    for (int k = 0; k < 3; ++k) {
      const uint32_t v = scene.triangles[t][k];
      sum[v] += patches[t].area * patch_radiance[t];
      weight[v] += patches[t].area * patches[t].visible;
    }
  }
  std::vector<float> out(3 * scene.vertex_count(), 0.f);
  for (std::size_t v = 0; v < sum.size(); ++v)
    if (weight[v] > 0.0)
      for (int c = 0; c < 3; ++c) out[3 * v + c] = static_cast<float>(sum[v][c] / weight[v]);
  return out;
}

}  // namespace prt::radiosity
