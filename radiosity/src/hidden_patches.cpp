// radiosity/src/hidden_patches.cpp — see radiosity/hidden_patches.h.
#include "radiosity/hidden_patches.h"

#include <array>
#include <cmath>

#include <tbb/parallel_for.h>

#include "form_factor_rows.h"
#include "numerics/constants.h"

namespace prt::radiosity {
namespace {

// The probe directions in a frame with +z the normal: the pole, then rings of six, each ring
// turned by half a step against the previous one.
std::array<glm::dvec3, kEnclosureProbes> local_probes() {
  std::array<glm::dvec3, kEnclosureProbes> d{};
  d[0] = {0.0, 0.0, 1.0};
  const double polar_degrees[4] = {30.0, 55.0, 75.0, 86.0};
  int k = 1;
  for (int ring = 0; ring < 4; ++ring) {
    const double theta = polar_degrees[ring] * numerics::kPi / 180.0;
    for (int s = 0; s < 6; ++s) {
      const double phi = (s + 0.5 * (ring % 2)) * numerics::kPi / 3.0;
      d[k++] = {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
    }
  }
  return d;
}

// Points of patch p where its receiving visibility is sampled (see the header).
std::vector<glm::dvec3> sample_points(const Patch& p, const FormFactorOptions& o) {
  const bool quadrature =
      o.method == FormFactorMethod::Analytic ||
      (o.method == FormFactorMethod::Rays && o.emitter_rows == EmitterRows::Reciprocal);
  if (quadrature) return detail::quadrature_points(p, o.quadrature_points);
  constexpr int m = 4;  // centroids of the m² congruent triangles
  const glm::dvec3 a = p.corners[0], e1 = p.corners[1] - a, e2 = p.corners[2] - a;
  std::vector<glm::dvec3> points;
  points.reserve(m * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; i + j < m; ++j) {
      points.push_back(a + e1 * ((i + 1.0 / 3) / m) + e2 * ((j + 1.0 / 3) / m));
      if (i + j < m - 1) points.push_back(a + e1 * ((i + 2.0 / 3) / m) + e2 * ((j + 2.0 / 3) / m));
    }
  return points;
}

// point_enclosed, with the emitting patches listed by the caller (null: scanned here).
bool enclosed(const scene::RayCaster& caster, uint32_t patch, const glm::dvec3& x,
              const glm::dvec3& n, const std::vector<Patch>& patches,
              const std::vector<uint32_t>* emitters) {
  static const std::array<glm::dvec3, kEnclosureProbes> probes = local_probes();
  // An orthonormal frame around n (Duff et al. 2017).
  const double sign = std::copysign(1.0, n.z);
  const double a = -1.0 / (sign + n.z), b = n.x * n.y * a;
  const glm::dvec3 t(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
  const glm::dvec3 u(b, sign + n.y * n.y * a, -n.y);
  const glm::vec3 origin = caster.surface_origin(patch, glm::vec3(x), glm::vec3(n));
  for (const glm::dvec3& l : probes) {
    const glm::vec3 d(glm::normalize(l.x * t + l.y * u + l.z * n));
    const scene::RayCaster::Hit hit =
        caster.intersect(origin, d, 0.f, std::numeric_limits<float>::infinity());
    if (!hit.hit || hit.front_face) return false;
  }
  // Every probe met a back face. Inside a room whose walls are wound the wrong way that is
  // also true, yet the lamps shine in: the point is enclosed only if no emitter's centroid is
  // in view of it either.
  const auto sees = [&](uint32_t e) {
    const Patch& lamp = patches[e];
    if (lamp.emission == glm::dvec3(0.0) || e == patch) return false;
    const glm::dvec3 to = lamp.centroid - x;
    const double distance = glm::length(to);
    if (!(distance > 0.0) || glm::dot(to, n) <= 0.0 || glm::dot(to, lamp.normal) >= 0.0)
      return false;
    const scene::RayCaster::Hit hit = caster.intersect(origin, glm::vec3(to / distance), 0.f,
                                                       static_cast<float>(distance * (1.0 + 1e-4)));
    return hit.hit && hit.triangle == e && hit.front_face;
  };
  if (emitters) {  // the emitting patches, listed once by the caller
    for (uint32_t e : *emitters)
      if (sees(e)) return false;
    return true;
  }
  for (uint32_t e = 0; e < patches.size(); ++e)
    if (sees(e)) return false;
  return true;
}

}  // namespace

bool point_enclosed(const scene::RayCaster& caster, uint32_t patch, const glm::dvec3& x,
                    const glm::dvec3& n, const std::vector<Patch>& patches) {
  return enclosed(caster, patch, x, n, patches, nullptr);
}

std::vector<double> visible_fractions(const std::vector<Patch>& patches,
                                      const scene::RayCaster& caster,
                                      const FormFactorOptions& options) {
  std::vector<double> fraction(patches.size(), 1.0);
  std::vector<uint32_t> emitters;  // so that an enclosed point does not scan every patch
  for (uint32_t e = 0; e < patches.size(); ++e)
    if (patches[e].emission != glm::dvec3(0.0)) emitters.push_back(e);
  tbb::parallel_for(std::size_t(0), patches.size(), [&](std::size_t i) {
    const Patch& p = patches[i];
    if (p.emission != glm::dvec3(0.0) || !(p.area > 0.0)) return;
    const std::vector<glm::dvec3> points = sample_points(p, options);
    int visible = 0;
    for (const glm::dvec3& x : points)
      visible +=
          enclosed(caster, static_cast<uint32_t>(i), x, p.normal, patches, &emitters) ? 0 : 1;
    fraction[i] = double(visible) / double(points.size());
  });
  return fraction;
}

void mark_hidden_parts(std::vector<Patch>* patches, const scene::RayCaster& caster,
                       const FormFactorOptions& options) {
  const std::vector<double> fraction = visible_fractions(*patches, caster, options);
  for (std::size_t i = 0; i < patches->size(); ++i) (*patches)[i].visible = fraction[i];
}

}  // namespace prt::radiosity
