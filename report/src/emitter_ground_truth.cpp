// report/src/emitter_ground_truth.cpp — the path tracer of report/emitter_ground_truth.h.
#include "report/emitter_ground_truth.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bake/sampling.h"
#include "numerics/hash.h"
#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "scene/ray_caster.h"
#include "scene/scene_label.h"
#include "sh/constants.h"

namespace prt::report {
namespace {

using sh::kPi;
constexpr int kRouletteFromDepth = 2;  // path vertices 0 and 1 never roulette
constexpr float kFar = 1e30f;
constexpr double kShadowShorten = 1.0 - 1e-4;  // shadow rays stop short of the emitter's point

using Rng = numerics::SplitMix64;

double luminance(const glm::dvec3& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// Uniform point on triangle (a, b, c) from two uniforms (square-root parametrisation).
glm::dvec3 uniform_triangle_point(const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c,
                                  double u1, double u2) {
  const numerics::Vec3<double> w = numerics::sample_uniform_triangle<double>({u1, u2});
  return w.x * a + w.y * b + w.z * c;
}

// The flat triangles of the scene with their materials, and the emitter distribution.
struct Triangles {
  std::vector<glm::dvec3> a, b, c, normal, albedo, emission;
  std::vector<double> area;
  std::vector<uint32_t> emitters;    // triangle indices that emit
  std::vector<double> emitter_cdf;   // inclusive, normalised to 1
  std::vector<double> emitter_prob;  // per triangle (0 for non-emitters)

  explicit Triangles(const scene::Scene& s) {
    const std::size_t T = s.triangles.size();
    a.resize(T), b.resize(T), c.resize(T), normal.assign(T, glm::dvec3(0.0));
    albedo.resize(T), emission.assign(T, glm::dvec3(0.0)), area.resize(T);
    emitter_prob.assign(T, 0.0);
    for (std::size_t t = 0; t < T; ++t) {
      const glm::uvec3 tri = s.triangles[t];
      a[t] = glm::dvec3(s.positions[tri.x]), b[t] = glm::dvec3(s.positions[tri.y]);
      c[t] = glm::dvec3(s.positions[tri.z]);
      const glm::dvec3 cr = glm::cross(b[t] - a[t], c[t] - a[t]);
      const double len = glm::length(cr);
      area[t] = 0.5 * len;
      if (len > 0.0) normal[t] = cr / len;
      albedo[t] = (glm::dvec3(s.albedo[tri.x]) + glm::dvec3(s.albedo[tri.y]) +
                   glm::dvec3(s.albedo[tri.z])) /
                  3.0;
    }
    for (const scene::ScenePrimitive& p : s.primitives)
      for (uint32_t k = 0; k < p.triangle_count && p.first_triangle + k < T; ++k)
        emission[p.first_triangle + k] = glm::dvec3(p.emission);
    double sum = 0.0;
    std::vector<double> weight;
    for (std::size_t t = 0; t < T; ++t) {
      const glm::dvec3& e = emission[t];
      if (!(e.x + e.y + e.z > 0.0) || !(area[t] > 0.0)) continue;
      const double w = area[t] * std::max(luminance(e), 1e-3 * (e.x + e.y + e.z));
      emitters.push_back(static_cast<uint32_t>(t));
      weight.push_back(w);
      sum += w;
    }
    double acc = 0.0;
    for (std::size_t k = 0; k < emitters.size(); ++k) {
      acc += weight[k];
      emitter_cdf.push_back(acc / sum);
      emitter_prob[emitters[k]] = weight[k] / sum;
    }
  }

  uint32_t pick_emitter(double u) const {
    const auto it = std::upper_bound(emitter_cdf.begin(), emitter_cdf.end(), u);
    const std::size_t k = std::min<std::size_t>(it - emitter_cdf.begin(), emitters.size() - 1);
    return emitters[k];
  }
};

glm::vec3 to_float(const glm::dvec3& v) {
  return glm::vec3(v);
}

// The power heuristic's weight of a technique with pdf p against one with pdf q.
double power_weight(double p, double q) {
  const double p2 = p * p, q2 = q * q;
  return p2 + q2 > 0.0 ? p2 / (p2 + q2) : 0.0;
}

struct Tracer {
  const scene::Scene& scene;
  const Triangles& tris;
  const scene::RayCaster& caster;
  int max_bounces;

  // Next-event estimate of emitted radiance reaching x (normal n, not on triangle `self`),
  // weighted against cosine sampling; adds throughput-weighted light to *out.
  uint32_t next_event(const glm::dvec3& x, const glm::vec3& origin, const glm::dvec3& n,
                      const glm::dvec3& beta, Rng& rng, glm::dvec3* out) const {
    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (tris.emitters.empty()) return 0;
    const uint32_t e = tris.pick_emitter(u0);
    const glm::dvec3 y = uniform_triangle_point(tris.a[e], tris.b[e], tris.c[e], u1, u2);
    const glm::dvec3 w = y - x;
    const double d2 = glm::dot(w, w);
    if (!(d2 > 0.0)) return 0;
    const double dist = std::sqrt(d2);
    const glm::dvec3 dir = w / dist;
    const double cos_x = glm::dot(n, dir), cos_y = -glm::dot(tris.normal[e], dir);
    if (!(cos_x > 0.0) || !(cos_y > 0.0)) return 0;
    const glm::vec3 dir_f = to_float(dir);
    const float tfar = static_cast<float>(
        glm::length(glm::dvec3(to_float(y)) - glm::dvec3(origin)) * kShadowShorten);
    if (caster.occluded(origin, glm::normalize(dir_f), 0.f, tfar)) return 1;
    const double p_light = tris.emitter_prob[e] / tris.area[e] * d2 / cos_y;
    const double p_cos = cos_x / kPi;
    *out += beta * tris.emission[e] * (cos_x / (kPi * p_light) * power_weight(p_light, p_cos));
    return 1;
  }

  // One path from x (normal n, throughput beta = the receiver's albedo): the reflected radiance
  // into *out; returns the rays cast.
  uint32_t trace(glm::dvec3 x, glm::vec3 origin, glm::dvec3 n, glm::dvec3 beta, Rng& rng,
                 glm::dvec3* out) const {
    uint32_t cast = 0;
    for (int depth = 0;; ++depth) {
      cast += next_event(x, origin, n, beta, rng, out);
      glm::vec3 t, b;
      const glm::vec3 nf = to_float(n);
      bake::build_orthonormal_basis(nf, t, b);
      // (glm::vec2's constructor: the two draws in the compiler's argument order, as before.)
      const glm::vec2 u(static_cast<float>(rng.uniform()), static_cast<float>(rng.uniform()));
      const glm::vec3 local =
          bake::to_glm(numerics::sample_cosine_hemisphere(bake::to_numerics(u)));
      const glm::vec3 d = glm::normalize(local.x * t + local.y * b + local.z * nf);
      const double cos_x = glm::dot(n, glm::dvec3(d));
      if (!(cos_x > 0.0)) break;
      ++cast;
      const scene::RayCaster::Hit hit = caster.intersect(origin, d, 0.f, kFar);
      if (!hit.hit || !hit.front_face) break;  // escaped, or a back face: absorbed
      const uint32_t h = hit.triangle;
      const glm::dvec3 p =
          (1.0 - hit.u - hit.v) * tris.a[h] + double(hit.u) * tris.b[h] + double(hit.v) * tris.c[h];
      const glm::dvec3& e = tris.emission[h];
      if (e.x + e.y + e.z > 0.0) {
        const double d2 = glm::dot(p - x, p - x);
        const double cos_h = -glm::dot(tris.normal[h], glm::dvec3(d));
        const double p_light = cos_h > 0.0 ? tris.emitter_prob[h] / tris.area[h] * d2 / cos_h : 0;
        *out += beta * e * power_weight(cos_x / kPi, p_light);
      }
      if (depth >= max_bounces) break;
      const glm::dvec3& rho = tris.albedo[h];
      beta *= rho;
      if (depth + 1 >= kRouletteFromDepth) {
        const double survive = std::clamp(std::max({rho.x, rho.y, rho.z}), 0.05, 0.99);
        if (rng.uniform() >= survive) break;
        beta /= survive;
      }
      x = p;
      n = tris.normal[h];
      origin = caster.surface_origin(h, to_float(p), to_float(n));
    }
    return cast;
  }
};

void check_inputs(const scene::Scene& s, const EmitterGroundTruthOptions& o) {
  const std::string name = scene::scene_label(s);
  if (s.vertex_count() == 0 || s.triangles.empty())
    throw std::invalid_argument(name + ": the scene has no vertices or no triangles");
  if (s.albedo.size() != s.vertex_count())
    throw std::invalid_argument(name + ": albedo does not match the vertex count");
  for (const glm::vec3& a : s.albedo)
    for (int c = 0; c < 3; ++c)
      if (!(a[c] >= 0.f && a[c] <= 1.f))
        throw std::invalid_argument(name + ": albedo " + std::to_string(a[c]) +
                                    " is outside [0, 1]");
  for (const scene::ScenePrimitive& p : s.primitives)
    for (int c = 0; c < 3; ++c)
      if (!(p.emission[c] >= 0.f) || !std::isfinite(p.emission[c]))
        throw std::invalid_argument(name + ": primitive " + p.name +
                                    ": emission must be finite and non-negative");
  if (o.samples < 1 || o.max_bounces < 0)
    throw std::invalid_argument(name + ": ground truth needs samples >= 1 and max_bounces >= 0");
  for (uint32_t t : o.patches)
    if (t >= s.triangles.size())
      throw std::invalid_argument(name + ": patch " + std::to_string(t) + " is out of range");
}

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

}  // namespace

EmitterGroundTruthResult compute_emitter_ground_truth(const scene::Scene& scene,
                                                      const EmitterGroundTruthOptions& o) {
  check_inputs(scene, o);
  const auto t0 = std::chrono::steady_clock::now();
  const Triangles tris(scene);
  const scene::RayCaster caster(scene);
  const Tracer tracer{scene, tris, caster, o.max_bounces};
  std::optional<tbb::global_control> limit;
  if (o.threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, o.threads);

  EmitterGroundTruthResult r;
  const std::size_t T = scene.triangles.size();
  r.patches = o.patches;
  if (r.patches.empty())
    for (std::size_t t = 0; t < T; ++t) r.patches.push_back(static_cast<uint32_t>(t));
  std::sort(r.patches.begin(), r.patches.end());
  r.patches.erase(std::unique(r.patches.begin(), r.patches.end()), r.patches.end());
  r.radiance.assign(T, glm::dvec3(0.0));
  r.standard_error.assign(T, glm::dvec3(0.0));
  r.samples = o.samples;
  std::atomic<uint64_t> rays{0};
  tbb::parallel_for(std::size_t(0), r.patches.size(), [&](std::size_t k) {
    const uint32_t t = r.patches[k];
    glm::dvec3 sum(0.0), sum2(0.0);
    uint64_t cast = 0;
    for (int s = 0; s < o.samples; ++s) {
      Rng rng{numerics::hash_seed(numerics::hash_seed(o.seed, t), static_cast<uint64_t>(s))};
      const double u1 = rng.uniform(), u2 = rng.uniform();
      const glm::dvec3 x = uniform_triangle_point(tris.a[t], tris.b[t], tris.c[t], u1, u2);
      const glm::vec3 origin = caster.surface_origin(t, to_float(x), to_float(tris.normal[t]));
      glm::dvec3 l(0.0);
      cast += tracer.trace(x, origin, tris.normal[t], tris.albedo[t], rng, &l);
      sum += l, sum2 += l * l;
    }
    const double N = o.samples;
    const glm::dvec3 mean = sum / N;
    const glm::dvec3 var = o.samples > 1
                               ? glm::max(glm::dvec3(0.0), (sum2 - N * mean * mean) / (N - 1.0))
                               : glm::dvec3(0.0);
    r.radiance[t] = tris.emission[t] + mean;
    r.standard_error[t] = glm::sqrt(var / N);
    rays += cast;
  });
  double se2 = 0.0, l2 = 0.0;
  for (uint32_t t : r.patches) {
    if (tris.emitter_prob[t] > 0.0) continue;
    se2 += tris.area[t] * glm::dot(r.standard_error[t], r.standard_error[t]);
    l2 += tris.area[t] * glm::dot(r.radiance[t], r.radiance[t]);
  }
  r.relative_rms_se = l2 > 0.0 ? std::sqrt(se2 / l2) : 0.0;
  r.rays = rays.load();
  r.seconds = seconds_since(t0);
  return r;
}

glm::dvec3 point_reflected_radiance(const scene::Scene& scene, const glm::dvec3& x,
                                    const glm::dvec3& n, const glm::dvec3& rho,
                                    const EmitterGroundTruthOptions& o,
                                    glm::dvec3* standard_error) {
  check_inputs(scene, o);
  const Triangles tris(scene);
  const scene::RayCaster caster(scene);
  const Tracer tracer{scene, tris, caster, o.max_bounces};
  const glm::dvec3 unit_n = glm::normalize(n);
  glm::dvec3 sum(0.0), sum2(0.0);
  for (int s = 0; s < o.samples; ++s) {
    Rng rng{numerics::hash_seed(numerics::hash_seed(o.seed, ~0ull), static_cast<uint64_t>(s))};
    rng.uniform(), rng.uniform();  // the point's two uniforms in the patch estimator
    glm::dvec3 l(0.0);
    tracer.trace(x, to_float(x), unit_n, rho, rng, &l);
    sum += l, sum2 += l * l;
  }
  const double N = o.samples;
  const glm::dvec3 mean = sum / N;
  if (standard_error)
    *standard_error =
        o.samples > 1
            ? glm::sqrt(glm::max(glm::dvec3(0.0), (sum2 - N * mean * mean) / (N - 1.0)) / N)
            : glm::dvec3(0.0);
  return mean;
}

}  // namespace prt::report
