// report/src/glossy_ground_truth.cpp — the glossy Monte Carlo reference of
// report/glossy_ground_truth.h.
#include "report/glossy_ground_truth.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "numerics/hash.h"
#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "prt/brdf/material.h"
#include "scene/ray_caster.h"
#include "scene/scene_label.h"
#include "scene/tangent_frames.h"
#include "sh/constants.h"

namespace prt::report {
namespace {

using bake::BakeError;
using brdf::Rgb;
using brdf::Vec3;
using numerics::hash_seed;
using sh::kPi;
constexpr int kRouletteFromDepth = 2;  // path vertices 0 and 1 never roulette
constexpr std::size_t kVertexBlock = 16;
constexpr uint32_t kNoPrimitive = ~0u;

using SampleRng = numerics::SplitMix64;

// An orthonormal shading frame (t, b, n) in world space.
struct Frame {
  glm::dvec3 t, b, n;
  Vec3 to_local(const glm::dvec3& d) const {
    return {glm::dot(t, d), glm::dot(b, d), glm::dot(n, d)};
  }
  glm::dvec3 to_world(const Vec3& d) const { return d.x * t + d.y * b + d.z * n; }
};

// The frame of unit normal n from tangent t (any length, not parallel to n) and handedness w.
// False when t is (nearly) parallel to n.
bool make_frame(const glm::dvec3& n, const glm::dvec3& t, double w, Frame* f) {
  const glm::dvec3 tp = t - glm::dot(t, n) * n;
  const double len = glm::length(tp);
  if (!(len > 1e-6)) return false;
  f->n = n;
  f->t = tp / len;
  f->b = (w < 0 ? -1.0 : 1.0) * glm::cross(n, f->t);
  return true;
}

// The surface at a path vertex: a BRDF, or Lambert with an albedo (brdf == nullptr).
struct Surface {
  const brdf::Brdf* brdf = nullptr;
  Rgb albedo;

  Rgb eval(const Vec3& wi, const Vec3& wo) const {
    if (brdf) return brdf->eval(wi, wo);
    if (wi.z <= 0 || wo.z <= 0) return {};
    return (1.0 / kPi) * albedo;
  }
  double pdf(const Vec3& wo, const Vec3& wi) const {
    if (brdf) return brdf->pdf(wo, wi);
    return wi.z > 0 && wo.z > 0 ? wi.z / kPi : 0.0;
  }
  brdf::BrdfSample sample(const Vec3& wo, double u1, double u2) const {
    if (brdf) return brdf->sample(wo, u1, u2);
    brdf::BrdfSample s;
    if (wo.z <= 0) return s;
    const numerics::Vec3<float> l = numerics::sample_cosine_hemisphere(
        numerics::Vec2<float>{static_cast<float>(u1), static_cast<float>(u2)});
    s.wi = brdf::normalize({l.x, l.y, l.z});
    if (!(s.wi.z > 0)) return s;
    s.pdf = s.wi.z / kPi;
    s.f = (1.0 / kPi) * albedo;
    return s;
  }
};

double channel(const Rgb& c, int i) {
  return i == 0 ? c.r : i == 1 ? c.g : c.b;
}

bool positive(const Rgb& c) {
  return c.r > 0 || c.g > 0 || c.b > 0;
}

// A triangle's geometric normal, oriented to the side its vertex normals point to.
glm::dvec3 oriented_face_normal(const scene::Scene& s, uint32_t tri) {
  const glm::uvec3 t = s.triangles[tri];
  glm::dvec3 ng = glm::cross(glm::dvec3(s.positions[t.y] - s.positions[t.x]),
                             glm::dvec3(s.positions[t.z] - s.positions[t.x]));
  const double len = glm::length(ng);
  if (!(len > 0)) return glm::dvec3(0);
  ng /= len;
  if (glm::dot(ng, glm::dvec3(s.normals[t.x] + s.normals[t.y] + s.normals[t.z])) < 0) ng = -ng;
  return ng;
}

// The paths of the header's estimator: what one sample of L_o needs.
struct GlossyPaths {
  const scene::Scene& scene;
  GlossyGroundTruthOptions options;
  EnvironmentSampler light;
  scene::RayCaster caster;
  std::vector<glm::vec4> tangents;                       // scene::tangent_frames
  std::vector<std::shared_ptr<const brdf::Brdf>> brdfs;  // per primitive (null: Lambert)
  std::vector<uint32_t> primitive_of_vertex, primitive_of_triangle;

  GlossyPaths(const scene::Scene& s, const sh::EnvMap& env, const GlossyGroundTruthOptions& o)
      : scene(s), options(o), light(env), caster(s), tangents(scene::tangent_frames(s)) {
    primitive_of_vertex.assign(s.vertex_count(), kNoPrimitive);
    primitive_of_triangle.assign(s.triangles.size(), kNoPrimitive);
    for (std::size_t p = 0; p < s.primitives.size(); ++p) {
      const scene::ScenePrimitive& prim = s.primitives[p];
      std::shared_ptr<const brdf::Brdf> made;
      if (prim.brdf) {
        Result<std::shared_ptr<const brdf::Brdf>> r = brdf::make_brdf(*prim.brdf);
        if (!r.ok())
          throw BakeError(scene::scene_label(s) + ": material of primitive '" + prim.name +
                          "': " + r.status().message());
        made = r.value();
      }
      brdfs.push_back(made);
      const std::size_t v_end = std::min<std::size_t>(
          s.vertex_count(), std::size_t(prim.first_vertex) + prim.vertex_count);
      for (std::size_t v = prim.first_vertex; v < v_end; ++v)
        primitive_of_vertex[v] = static_cast<uint32_t>(p);
      const std::size_t t_end = std::min<std::size_t>(
          s.triangles.size(), std::size_t(prim.first_triangle) + prim.triangle_count);
      for (std::size_t t = prim.first_triangle; t < t_end; ++t)
        primitive_of_triangle[t] = static_cast<uint32_t>(p);
    }
  }

  Surface surface(uint32_t primitive, const glm::vec3& albedo) const {
    Surface s;
    if (primitive != kNoPrimitive) s.brdf = brdfs[primitive].get();
    s.albedo = {albedo.x, albedo.y, albedo.z};
    return s;
  }

  // The receiving vertex's frame (false for a degenerate normal).
  bool vertex_frame(uint32_t v, Frame* f) const {
    const glm::dvec3 n(scene.normals[v]);
    const double len = glm::length(n);
    if (!(len > 0)) return false;
    const glm::vec4 t = tangents[v];
    return make_frame(n / len, glm::dvec3(t), t.w, f) ||
           make_frame(n / len, glm::dvec3(scene::normal_only_tangent(glm::vec3(n / len))), 1.0, f);
  }

  // The frame at a hit (see header); false when nothing usable.
  bool hit_frame(uint32_t tri, float u, float v, const glm::dvec3& ng, Frame* f) const {
    const glm::uvec3 ix = scene.triangles[tri];
    const double w[3] = {1.0 - u - v, u, v};
    const uint32_t id[3] = {ix.x, ix.y, ix.z};
    glm::dvec3 ns(0), t(0);
    int major = 0;
    for (int a = 0; a < 3; ++a) {
      ns += w[a] * glm::dvec3(scene.normals[id[a]]);
      t += w[a] * glm::dvec3(tangents[id[a]]);
      if (w[a] > w[major]) major = a;
    }
    const double len = glm::length(ns);
    ns = len > 0 ? ns / len : ng;
    if (glm::dot(ns, ng) <= 0) ns = ng;
    const double handed = tangents[id[major]].w;
    const glm::dvec3 tp = t - glm::dot(t, ns) * ns;
    if (glm::length(tp) >= 0.5 && make_frame(ns, tp, handed, f)) return true;
    if (make_frame(ns, glm::dvec3(tangents[id[major]]), handed, f)) return true;
    return make_frame(ns, glm::dvec3(scene::normal_only_tangent(glm::vec3(ns))), 1.0, f);
  }

  uint32_t sample_vertex(uint32_t v, uint64_t sample_index, double out[3]) const;
};

uint32_t GlossyPaths::sample_vertex(uint32_t v, uint64_t sample_index, double out[3]) const {
  out[0] = out[1] = out[2] = 0;
  Frame frame;
  if (!vertex_frame(v, &frame)) return 0;
  const glm::dvec3 p(scene.positions[v]);
  const glm::dvec3 eye(options.eye[0], options.eye[1], options.eye[2]);
  const glm::dvec3 to_eye = eye - p;
  const double eye_distance = glm::length(to_eye);
  if (!(eye_distance > 0) || !std::isfinite(eye_distance)) return 0;
  Vec3 wo = frame.to_local(to_eye / eye_distance);
  if (!(wo.z > 0)) return 0;

  SampleRng rng{hash_seed(hash_seed(options.seed, v), sample_index)};
  uint32_t cast = 0;
  Surface surf = surface(primitive_of_vertex[v], scene.albedo[v]);
  glm::vec3 origin = caster.vertex_origin(v);
  double beta[3] = {1, 1, 1};
  const float far = 1e30f;
  for (int depth = 0;; ++depth) {
    // Light sample, balance heuristic against the BRDF sample.
    double ld[3], lrgb[3], lpdf;
    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (light.sample(u0, u1, u2, ld, lrgb, &lpdf) && lpdf > 0) {
      const Vec3 wi = frame.to_local(glm::dvec3(ld[0], ld[1], ld[2]));
      if (wi.z > 0) {
        const Rgb f = surf.eval(wi, wo);
        if (positive(f)) {
          ++cast;
          const glm::vec3 d(static_cast<float>(ld[0]), static_cast<float>(ld[1]),
                            static_cast<float>(ld[2]));
          if (!caster.occluded(origin, d, 0.f, far)) {
            const double weight = wi.z / (lpdf + surf.pdf(wo, wi));
            for (int c = 0; c < 3; ++c) out[c] += beta[c] * channel(f, c) * weight * lrgb[c];
          }
        }
      }
    }
    // BRDF sample: escape → weighted map radiance; front hit → continue the path.
    const double s1 = rng.uniform(), s2 = rng.uniform();
    const brdf::BrdfSample s = surf.sample(wo, s1, s2);
    if (!(s.pdf > 0) || !(s.wi.z > 0)) break;
    double gain[3];
    for (int c = 0; c < 3; ++c) gain[c] = channel(s.f, c) * s.wi.z / s.pdf;
    const glm::dvec3 dw = glm::normalize(frame.to_world(s.wi));
    const glm::vec3 d(dw);
    ++cast;
    const scene::RayCaster::Hit hit = caster.intersect(origin, d, 0.f, far);
    if (!hit.hit) {
      const double dd[3] = {dw.x, dw.y, dw.z};
      double rgb[3], lpdf_at;
      light.evaluate(dd, rgb, &lpdf_at);
      const double w = s.pdf / (s.pdf + lpdf_at);
      for (int c = 0; c < 3; ++c) out[c] += beta[c] * gain[c] * w * rgb[c];
      break;
    }
    if (depth >= options.max_bounces) break;
    const glm::dvec3 ng = oriented_face_normal(scene, hit.triangle);
    if (!(glm::dot(ng, dw) < 0)) break;  // back face (or degenerate): occludes only
    Frame next;
    if (!hit_frame(hit.triangle, hit.u, hit.v, ng, &next)) break;
    const Vec3 wo_next = next.to_local(-dw);
    if (!(wo_next.z > 0)) break;  // below the shading horizon: one-sided BRDF reflects nothing
    for (int c = 0; c < 3; ++c) beta[c] *= gain[c];
    if (depth + 1 >= kRouletteFromDepth) {
      const double survive = std::clamp(std::max({gain[0], gain[1], gain[2]}), 0.05, 0.99);
      if (rng.uniform() >= survive) break;
      for (double& x : beta) x /= survive;
    }
    const glm::uvec3 tri = scene.triangles[hit.triangle];
    const float w0 = 1.f - hit.u - hit.v;
    const glm::vec3 hp = w0 * scene.positions[tri.x] + hit.u * scene.positions[tri.y] +
                         hit.v * scene.positions[tri.z];
    origin = caster.surface_origin(hit.triangle, hp, glm::vec3(ng));
    surf =
        surface(primitive_of_triangle[hit.triangle], scene.albedo_at(hit.triangle, hit.u, hit.v));
    frame = next;
    wo = wo_next;
  }
  return cast;
}

// Checks the inputs (before the ray caster is built), then the sampler over GlossyPaths.
VertexSampler glossy_sampler(const scene::Scene& scene, const sh::EnvMap& env,
                             const GlossyGroundTruthOptions& o) {
  check_ground_truth_inputs(scene, o, o.max_bounces, "glossy ground truth");
  for (double e : o.eye)
    if (!std::isfinite(e))
      throw BakeError(scene::scene_label(scene) + ": the eye point is not finite");
  auto paths = std::make_shared<const GlossyPaths>(scene, env, o);
  return make_vertex_sampler(paths, "glossy ground truth", kVertexBlock,
                             paths->light.skipped_texels());
}

}  // namespace

GlossyGroundTruthIntegrator::GlossyGroundTruthIntegrator(const scene::Scene& scene,
                                                         const sh::EnvMap& env,
                                                         const GlossyGroundTruthOptions& o)
    : VertexEstimator(scene.vertex_count(), o, glossy_sampler(scene, env, o),
                      scene::scene_label(scene) + ": glossy ground truth") {}

GroundTruthResult compute_glossy_ground_truth(const scene::Scene& scene, const sh::EnvMap& env,
                                              const GlossyGroundTruthOptions& options,
                                              ProgressSink* progress) {
  GlossyGroundTruthIntegrator integrator(scene, env, options);
  integrator.refine(options.target_relative_se, progress);
  return integrator.result();
}

}  // namespace prt::report
