// Normal blurring and depth-map translucency: the approximations that cast rays (see
// bake/subsurface_approx/subsurface_approximations.h).
#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

#include "approximation_common.h"
#include "bake/subsurface/subsurface_baker.h"
#include "bake/subsurface_approx/surface_blur.h"
#include "numerics/constants.h"
#include "numerics/hash.h"
#include "numerics/low_discrepancy.h"
#include "numerics/sampling.h"
#include "scene/ray_caster.h"
#include "sh/basis.h"
#include "sh/zonal.h"

namespace prt::bake {
namespace {

using numerics::kPi;

// The vertex normals blurred with σ = ℓ_c per channel, renormalised (the geometric normal where
// the blur cancels); σ is capped at the scene's extent (σ_a = 0 has ℓ = ∞).
std::vector<std::array<glm::dvec3, 3>> blurred_normals(const SubsurfaceApproximationInputs& in) {
  const scene::Scene& scene = *in.scene;
  const std::size_t n = scene.positions.size();
  const std::vector<double> areas = vertex_areas(scene);
  std::vector<double> normals(n * 3);
  for (std::size_t v = 0; v < n; ++v)
    for (int a = 0; a < 3; ++a) normals[v * 3 + a] = scene.normals[v][a];
  std::vector<std::array<glm::dvec3, 3>> out(n);
  const double extent = std::max(double(scene.extent()), 1e-30);
  for (int c = 0; c < 3; ++c) {
    const double sigma_tr = in.material.channels[c].sigma_tr();
    const double sigma = sigma_tr > 1.0 / extent ? 1.0 / sigma_tr : extent;
    const std::vector<double> b = blur_over_surface(scene, areas, in.group, normals, 3, sigma);
    for (std::size_t v = 0; v < n; ++v) {
      const glm::dvec3 m(b[v * 3], b[v * 3 + 1], b[v * 3 + 2]);
      const double len = glm::length(m);
      out[v][c] = len > 1e-9 ? m / len : glm::dvec3(scene.normals[v]);
    }
  }
  return out;
}

}  // namespace

std::vector<glm::dvec3> fibonacci_directions(int count) {
  std::vector<glm::dvec3> dirs(count);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < count; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / count, r = std::sqrt(std::max(0.0, 1 - z * z));
    dirs[i] = {r * std::cos(golden * i), r * std::sin(golden * i), z};
  }
  return dirs;
}

Thickness shadow_map_thickness(const scene::RayCaster& caster, const scene::Scene& scene,
                               const std::vector<int32_t>& group, uint32_t v,
                               const glm::vec3& toward_light, float far) {
  Thickness out;
  const float eps = 4.f * caster.vertex_ray_starts().offset[v];
  const glm::vec3 origin = scene.positions[v] + far * toward_light;
  const scene::RayCaster::Hit hit = caster.intersect(origin, -toward_light, 0.f, far - eps);
  if (!hit.hit) return out;  // nothing before v: no entry surface, no light through
  const glm::uvec3 tri = scene.triangles[hit.triangle];
  if (group[tri.x] != group[v]) {
    out.blocked = true;
    return out;
  }
  out.thickness = std::max(0.0, double(far) - double(hit.t));
  const float w = 1.f - hit.u - hit.v;
  const glm::vec3 ne = glm::normalize(w * scene.normals[tri.x] + hit.u * scene.normals[tri.y] +
                                      hit.v * scene.normals[tri.z]);
  out.entry_cos = hit.front_face ? std::max(0.0, double(glm::dot(ne, toward_light))) : 0.0;
  return out;
}

namespace detail {

prt::TransferData normal_blur_transfer(const SubsurfaceApproximationInputs& in) {
  prt::TransferData out = lambert_transfer(in);
  const scene::Scene& scene = *in.scene;
  const int order = static_cast<int>(out.order), kc = order * order;
  const std::size_t n = scene.positions.size();
  const auto normals = blurred_normals(in);
  std::vector<double> zonal(order);
  for (int l = 0; l < order; ++l) zonal[l] = sh::clamped_cosine_zonal_coefficient(l);
  const int samples = std::max(16, in.normal_blur_samples);
  std::vector<double> rows(n * 3 * kc, 0.0);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    if (in.group[v] < 0) return;
    const glm::dvec3 ng(scene.normals[v]);
    numerics::Vec3<double> t, b;
    numerics::build_orthonormal_basis(numerics::Vec3<double>{ng.x, ng.y, ng.z}, &t, &b);
    const uint64_t seed = numerics::hash_seed(in.seed, v);
    const glm::vec3 origin = in.caster->vertex_origin(static_cast<uint32_t>(v));
    std::vector<double> y(kc), f(kc), blocked(3 * kc, 0.0);
    for (int s = 0; s < samples; ++s) {
      const numerics::Vec2<double> u{numerics::sobol_owen_double(s, 0, seed),
                                     numerics::sobol_owen_double(s, 1, seed)};
      const numerics::Vec3<double> l = numerics::sample_uniform_hemisphere(u);
      const glm::dvec3 d =
          l.x * glm::dvec3(t.x, t.y, t.z) + l.y * glm::dvec3(b.x, b.y, b.z) + l.z * ng;
      if (!in.caster->occluded(origin, glm::vec3(d), 0.f, std::numeric_limits<float>::infinity()))
        continue;
      sh::evaluate(order, d.x, d.y, d.z, y.data());
      for (int c = 0; c < 3; ++c) {
        const double cosine = std::max(0.0, glm::dot(normals[v][c], d));
        for (int k = 0; k < kc; ++k) blocked[c * kc + k] += cosine * y[k];
      }
    }
    for (int c = 0; c < 3; ++c) {
      const glm::dvec3 nc = normals[v][c];
      sh::rotate_zonal(order, zonal.data(), nc.x, nc.y, nc.z, f.data());
      const double scale = in.material.channels[c].total() / kPi;
      for (int k = 0; k < kc; ++k)
        rows[(v * 3 + c) * kc + k] =
            scale * (f[k] - numerics::kTwoPi / samples * blocked[c * kc + k]);
    }
  });
  set_translucent_rows(in, rows, out);
  return out;
}

prt::TransferData depth_map_transfer(const SubsurfaceApproximationInputs& in) {
  prt::TransferData out = lambert_transfer(in);
  const scene::Scene& scene = *in.scene;
  const int order = static_cast<int>(out.order), kc = order * order;
  const std::size_t n = scene.positions.size();
  const std::vector<glm::dvec3> dirs = fibonacci_directions(std::max(16, in.depth_map_directions));
  const double weight = 4.0 * kPi / double(dirs.size());
  std::vector<std::vector<double>> basis(dirs.size(), std::vector<double>(kc));
  for (std::size_t d = 0; d < dirs.size(); ++d)
    sh::evaluate(order, dirs[d].x, dirs[d].y, dirs[d].z, basis[d].data());
  const float far = 2.f * std::max(scene.extent(), 1e-20f);
  std::vector<double> rows(n * 3 * kc, 0.0);
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t v) {
    if (in.group[v] < 0) return;
    double* row = &rows[v * 3 * kc];
    for (int c = 0; c < 3; ++c)  // the lit side: Lambert with R_total
      for (int k = 0; k < kc; ++k) row[c * kc + k] = double(out.coefficients[(v * 3 + c) * kc + k]);
    const glm::dvec3 nv(scene.normals[v]);
    for (std::size_t d = 0; d < dirs.size(); ++d) {
      if (glm::dot(nv, dirs[d]) >= 0) continue;
      const Thickness th = shadow_map_thickness(*in.caster, scene, in.group,
                                                static_cast<uint32_t>(v), glm::vec3(dirs[d]), far);
      if (th.blocked || th.entry_cos <= 0) continue;
      for (int c = 0; c < 3; ++c) {
        const subsurface::DipoleProfile& p = in.material.channels[c];
        const double a =
            weight * p.total() / kPi * std::exp(-p.sigma_tr() * th.thickness) * th.entry_cos;
        for (int k = 0; k < kc; ++k) row[c * kc + k] += a * basis[d][k];
      }
    }
  });
  set_translucent_rows(in, rows, out);
  return out;
}

}  // namespace detail
}  // namespace prt::bake
