// tests/support/mixed_scale_scenes.h — scenes that mix scales (unit objects on grounds 1e3 and
// 1e5 across, at the origin and 1e4 away from it) and the ray counts that check them, shared by
// the tests of the ray origins (tests/scene/test_ray_offset.cpp) and of the bakers at contact
// (tests/bake/test_bake_mixed_scale.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "numerics/sampling.h"
#include "scene/orthonormal_basis.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace prt::test {

// The budget of every closed form at contact: stratified sampling and tessellation stay well
// below it (see each case), a wrong ray origin does not (an offset proportional to the scene's
// size missed by 0.12).
constexpr double kClosedFormTolerance = 0.01;

// Sorted, unique coordinates: `required` values, a fine step over [-fine, fine], then a
// geometric progression (×1.6) out to ±half.
inline std::vector<float> graded(std::vector<float> required, float fine, float step, float half) {
  for (float x = -fine; x <= fine + 1e-6f; x += step) required.push_back(x);
  for (float x = fine * 1.6f; x < half; x *= 1.6f) {
    required.push_back(x);
    required.push_back(-x);
  }
  required.push_back(half);
  required.push_back(-half);
  std::sort(required.begin(), required.end());
  required.erase(std::unique(required.begin(), required.end(),
                             [](float a, float b) { return std::fabs(a - b) < 1e-4f; }),
                 required.end());
  return required;
}

// A grid through origin + us[i]·u + vs[j]·v, facing cross(u, v), vertex (i, j) at j·|us| + i.
inline scene::Scene graded_grid(glm::vec3 origin, glm::vec3 u, const std::vector<float>& us,
                                glm::vec3 v, const std::vector<float>& vs, glm::vec3 albedo,
                                const std::string& name) {
  scene::Scene s;
  const glm::vec3 n = glm::normalize(glm::cross(u, v));
  const uint32_t nu = static_cast<uint32_t>(us.size());
  for (float b : vs)
    for (float a : us) {
      s.positions.push_back(origin + a * u + b * v);
      s.normals.push_back(n);
      s.albedo.push_back(albedo);
    }
  for (uint32_t j = 0; j + 1 < vs.size(); ++j)
    for (uint32_t i = 0; i + 1 < nu; ++i) {
      const uint32_t a = j * nu + i, b = a + 1, c = a + nu + 1, d = a + nu;
      s.triangles.push_back({a, b, c});
      s.triangles.push_back({a, c, d});
    }
  scene::ScenePrimitive p;
  p.name = name;
  p.vertex_count = static_cast<uint32_t>(s.positions.size());
  p.triangle_count = static_cast<uint32_t>(s.triangles.size());
  p.albedo = albedo;
  s.primitives.push_back(p);
  return s;
}

// Ground y = 0 facing +Y, ±half in x and z, with grid lines at `xs_near` and `zs_near`.
inline scene::Scene ground(float half, std::vector<float> xs_near, std::vector<float> zs_near) {
  return graded_grid({0, 0, 0}, {0, 0, 1}, graded(std::move(zs_near), 3.f, 0.25f, half), {1, 0, 0},
                     graded(std::move(xs_near), 3.f, 0.25f, half), glm::vec3(0.5f), "ground");
}

// Index of the vertex at (x, 0, z) of the first primitive (the ground).
inline uint32_t ground_vertex(const scene::Scene& s, float x, float z) {
  for (uint32_t v = 0; v < s.primitives[0].vertex_count; ++v)
    if (std::fabs(s.positions[v].x - x) < 1e-5f && std::fabs(s.positions[v].z - z) < 1e-5f &&
        s.positions[v].y == 0.f)
      return v;
  FAIL("no ground vertex at " << x << ", " << z);
  return 0;
}

// The scale mixes every closed form is checked at.
struct MixedScaleVariant {
  float ground_half;  // the ground spans ±ground_half: the scale mix is 2·ground_half : 1
  glm::vec3 shift;    // the whole scene is moved by this
  std::string label() const {
    return "ground " + std::to_string(2 * ground_half) + " across, shifted by " +
           std::to_string(shift.x);
  }
};

inline const MixedScaleVariant kMixedScaleVariants[] = {{500.f, glm::vec3(0.f)},
                                                        {5e4f, glm::vec3(0.f)},
                                                        {500.f, glm::vec3(1e4f, 3e3f, -1e4f)},
                                                        {5e4f, glm::vec3(1e4f, 3e3f, -1e4f)}};

// Casts N cosine-distributed rays (a spiral over the disc, Malley's method) from vertex v's ray
// origin (RayCaster::vertex_origin, the bakers' origin); returns the fraction that hit.
inline double occluded_fraction(const scene::RayCaster& caster, const scene::Scene& scene,
                                uint32_t v, int N) {
  const glm::vec3 n = glm::normalize(scene.normals[v]);
  glm::vec3 t, b;
  scene::build_orthonormal_basis(n, t, b);
  int hits = 0;
  for (int i = 0; i < N; ++i) {
    const float fi = static_cast<float>(i);
    const prt::numerics::Vec2<float> u{(fi + 0.5f) / static_cast<float>(N),
                                       std::fmod(fi * 0.618034f, 1.f)};
    const prt::numerics::Vec3<float> l = prt::numerics::sample_cosine_hemisphere(u);
    const glm::vec3 d = glm::normalize(l.x * t + l.y * b + l.z * n);
    hits += caster.occluded(caster.vertex_origin(v), d, 0.f, INFINITY) ? 1 : 0;
  }
  return hits / double(N);
}

}  // namespace prt::test
