// bake/src/glossy_emitter_gather.cpp — see bake/glossy_emitter_gather.h.
#include "bake/glossy_emitter_gather.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "hit_side.h"
#include "scene/ray_caster.h"
#include "sh/basis.h"
#include "sh/constants.h"

namespace prt::bake {
namespace {

constexpr std::size_t kBlock = 64;  // vertices per parallel task

void check_inputs(const scene::Scene& scene, const prt::GlossyTransferData& glossy,
                  const prt::EmitterResponses& responses, const GlossyEmitterGatherOptions& o) {
  if (o.samples < 1 || o.samples > (1 << 24))
    throw BakeError("glossy emitter gather: samples " + std::to_string(o.samples) +
                    " outside 1..16777216");
  if (o.emitter_samples < 0 || o.emitter_samples > (1 << 24))
    throw BakeError("glossy emitter gather: emitter samples " + std::to_string(o.emitter_samples) +
                    " outside 0..16777216");
  if (o.threads < 0) throw BakeError("glossy emitter gather: threads must be ≥ 0");
  const std::size_t V = scene.vertex_count();
  if (glossy.vertex_count != V || responses.vertex_count() != V)
    throw BakeError("glossy emitter gather: the scene has " + std::to_string(V) +
                    " vertices, the glossy file " + std::to_string(glossy.vertex_count) +
                    ", the emitter responses " + std::to_string(responses.vertex_count()));
  bool same = responses.triangles.size() == 3 * scene.triangles.size();
  for (std::size_t t = 0; same && t < scene.triangles.size(); ++t)
    for (int a = 0; a < 3; ++a)
      same = same && responses.triangles[3 * t + a] == scene.triangles[t][a];
  if (!same)
    throw BakeError(
        "glossy emitter gather: the emitter responses' triangles differ from the "
        "scene's");
  if (responses.responses.size() != 3 * V * responses.emitter_count())
    throw BakeError("glossy emitter gather: the responses do not match their counts");
  if (glossy.order < 1 || glossy.order > uint32_t(prt::kMaxBrdfProjectionOrder))
    throw BakeError("glossy emitter gather: order " + std::to_string(glossy.order));
}

// The emitter each vertex lies on: its primitive's material name among the responses' emitters
// (radiosity/emitter_solve.h groups emitting primitives by material, "<none>" without a name).
std::vector<uint32_t> emitters_of_vertices(const scene::Scene& scene,
                                           const prt::EmitterResponses& responses) {
  std::vector<uint32_t> out(scene.vertex_count(), prt::kNotAnEmitter);
  for (const scene::ScenePrimitive& p : scene.primitives) {
    const bool unnamed = p.material.empty();
    if (unnamed && p.emission == glm::vec3(0.f)) continue;
    const std::string name = unnamed ? "<none>" : p.material;
    uint32_t e = 0;
    while (e < responses.emitter_count() && responses.emitters[e].name != name) ++e;
    if (e == responses.emitter_count()) continue;
    for (uint32_t k = 0; k < p.vertex_count && p.first_vertex + k < out.size(); ++k)
      out[p.first_vertex + k] = e;
  }
  return out;
}

// The front-facing surface of each emitter for area sampling: its triangles (all three vertices
// on it), their cumulative areas and unit front normals (counter-clockwise, as hit_side.h).
struct EmitterSurface {
  std::vector<uint32_t> triangles;
  std::vector<double> cumulative;  // cumulative area, last = the emitter's area
  std::vector<glm::vec3> normals;
  double area() const { return cumulative.empty() ? 0.0 : cumulative.back(); }
};

std::vector<EmitterSurface> emitter_surfaces(const scene::Scene& scene,
                                             const std::vector<uint32_t>& emitter_of_vertex,
                                             std::size_t emitters) {
  std::vector<EmitterSurface> out(emitters);
  for (uint32_t t = 0; t < scene.triangles.size(); ++t) {
    const glm::uvec3 tri = scene.triangles[t];
    const uint32_t e = emitter_of_vertex[tri.x];
    if (e == prt::kNotAnEmitter || emitter_of_vertex[tri.y] != e || emitter_of_vertex[tri.z] != e)
      continue;
    const glm::vec3 p0 = scene.positions[tri.x];
    glm::vec3 ng = glm::cross(scene.positions[tri.y] - p0, scene.positions[tri.z] - p0);
    const double area = 0.5 * glm::length(ng);
    if (!(area > 0.0)) continue;
    // Oriented like the vertex normals (the side radiosity emits from, hit_side.h's rule).
    if (glm::dot(ng, scene.normals[tri.x] + scene.normals[tri.y] + scene.normals[tri.z]) < 0.f)
      ng = -ng;
    EmitterSurface& s = out[e];
    s.triangles.push_back(t);
    s.cumulative.push_back(s.area() + area);
    s.normals.push_back(glm::normalize(ng));
  }
  return out;
}

// The density in solid angle, at a vertex, of area sampling emitter surface s toward a point at
// distance r whose front normal makes cosine cos_l with the direction back to the vertex.
double area_pdf(const EmitterSurface& s, double r, double cos_l) {
  return cos_l > 0.0 ? r * r / (cos_l * s.area()) : 0.0;
}

// What one vertex's gather reads.
struct GatherContext {
  const scene::Scene& scene;
  const scene::RayCaster& caster;
  const prt::EmitterResponses& responses;
  const std::vector<uint32_t>& emitter_of_vertex;
  const std::vector<EmitterSurface>& surfaces;
  int order;
  int hemisphere_samples;  // N_h, a multiple of kPacketSize
  int area_samples;        // N_a per emitter, a multiple of kPacketSize; 0: none
  uint64_t seed;
};

// The emitter whose sampled surface triangle t belongs to, or kNotAnEmitter.
uint32_t surface_emitter(const GatherContext& c, uint32_t t) {
  const glm::uvec3 tri = c.scene.triangles[t];
  const uint32_t e = c.emitter_of_vertex[tri.x];
  if (c.area_samples == 0 || e == prt::kNotAnEmitter || c.emitter_of_vertex[tri.y] != e ||
      c.emitter_of_vertex[tri.z] != e || !(c.surfaces[e].area() > 0.0))
    return prt::kNotAnEmitter;
  return e;
}

// Adds weight · y to rows (e, c) of g for every emitter e and channel c with radiance[e·3 + c].
void add_rows(std::size_t K, std::size_t E, const double* radiance, const float* y, double* g) {
  for (std::size_t ec = 0; ec < E * 3; ++ec) {
    if (radiance[ec] == 0.0) continue;
    double* row = g + ec * K;
    for (std::size_t k = 0; k < K; ++k) row[k] += radiance[ec] * y[k];
  }
}

// The hemisphere directions: every front hit brings the responses interpolated there; on an
// emitter's own surface its unit emission only with the balance-heuristic weight
// N_h p_h / (N_h p_h + N_a p_a) (the area samples bring the rest of it).
void gather_hemisphere(const GatherContext& c, const double frame[9], std::size_t v,
                       std::vector<double>& g, std::vector<float>& y, uint64_t& hits) {
  const std::size_t K = std::size_t(c.order) * c.order, E = c.responses.emitter_count();
  const std::size_t V = c.responses.vertex_count();
  const double ph_n = c.hemisphere_samples / (2.0 * sh::kPi);  // N_h p_h
  const uint64_t vertex_seed = hash_seed(c.seed, v);
  const glm::vec3 origin = c.caster.vertex_origin(static_cast<uint32_t>(v));
  const glm::vec3 t(frame[0], frame[1], frame[2]), b(frame[3], frame[4], frame[5]),
      n(frame[6], frame[7], frame[8]);
  glm::vec3 local[kPacketSize], dirs[kPacketSize];
  scene::RayCaster::Hit hit[kPacketSize];
  std::vector<double> radiance(E * 3);
  for (int first = 0; first < c.hemisphere_samples; first += kPacketSize) {
    for (int i = 0; i < kPacketSize; ++i) {
      local[i] = to_glm(numerics::sample_uniform_hemisphere(
          to_numerics(sample_sobol_2d(static_cast<uint32_t>(first + i), vertex_seed))));
      dirs[i] = glm::normalize(local[i].x * t + local[i].y * b + local[i].z * n);
    }
    c.caster.intersect_packet(origin, dirs, kPacketSize, std::numeric_limits<float>::infinity(),
                              hit);
    for (int i = 0; i < kPacketSize; ++i) {
      if (!hit[i].hit || !detail::ray_hits_front_side(c.scene, hit[i].triangle, dirs[i])) continue;
      ++hits;
      const glm::uvec3 tri = c.scene.triangles[hit[i].triangle];
      const double beta[3] = {1.0 - hit[i].u - hit[i].v, hit[i].u, hit[i].v};
      for (std::size_t e = 0; e < E; ++e)
        for (int ch = 0; ch < 3; ++ch) {
          double r = 0;
          for (int a = 0; a < 3; ++a)
            r += beta[a] * c.responses.responses[3 * (e * V + tri[a]) + ch];
          radiance[e * 3 + ch] = r / ph_n;
        }
      if (const uint32_t e = surface_emitter(c, hit[i].triangle); e != prt::kNotAnEmitter) {
        const glm::vec3 p0 = c.scene.positions[tri.x];
        glm::vec3 ng = glm::cross(c.scene.positions[tri.y] - p0, c.scene.positions[tri.z] - p0);
        const double cos_l = std::abs(glm::dot(glm::normalize(ng), dirs[i]));
        const double pa_n = c.area_samples * area_pdf(c.surfaces[e], hit[i].t, cos_l);
        for (int ch = 0; ch < 3; ++ch)  // the emission 1 under MIS, the reflected rest as it is
          radiance[e * 3 + ch] += 1.0 / (ph_n + pa_n) - 1.0 / ph_n;
      }
      sh::evaluate(c.order, local[i].x, local[i].y, local[i].z, y.data());
      add_rows(K, E, radiance.data(), y.data(), g.data());
    }
  }
}

// N_a points uniform by area on emitter e's surface: its unit emission toward the vertex, where
// visible and in the vertex's upper hemisphere, weighted 1 / (N_h p_h + N_a p_a).
void gather_emitter_area(const GatherContext& c, const double frame[9], std::size_t v,
                         std::size_t e, std::vector<double>& g, std::vector<float>& y) {
  const EmitterSurface& s = c.surfaces[e];
  if (c.area_samples == 0 || !(s.area() > 0.0)) return;
  const std::size_t K = std::size_t(c.order) * c.order;
  const double ph_n = c.hemisphere_samples / (2.0 * sh::kPi);
  const uint64_t seed = hash_seed(hash_seed(c.seed, v), e + 1);
  const glm::vec3 origin = c.caster.vertex_origin(static_cast<uint32_t>(v));
  glm::vec3 d[kPacketSize], local[kPacketSize];
  double weight[kPacketSize];
  bool occluded[kPacketSize];
  for (int first = 0; first < c.area_samples; first += kPacketSize) {
    for (int i = 0; i < kPacketSize; ++i) {
      const uint32_t index = static_cast<uint32_t>(first + i);
      const double pick = numerics::sobol_owen_float(index, 2, seed) * s.area();
      const std::size_t k = std::min<std::size_t>(
          std::upper_bound(s.cumulative.begin(), s.cumulative.end(), pick) - s.cumulative.begin(),
          s.triangles.size() - 1);
      const glm::uvec3 tri = c.scene.triangles[s.triangles[k]];
      const auto w = numerics::sample_uniform_triangle(to_numerics(sample_sobol_2d(index, seed)));
      const glm::vec3 x = w.x * c.scene.positions[tri.x] + w.y * c.scene.positions[tri.y] +
                          w.z * c.scene.positions[tri.z];
      d[i] = x - origin;  // unnormalised: occlusion on t < 1 − 1e-4 stops short of x
      const double r = glm::length(d[i]);
      const glm::vec3 dir = d[i] / float(r);
      local[i] = {float(frame[0] * dir.x + frame[1] * dir.y + frame[2] * dir.z),
                  float(frame[3] * dir.x + frame[4] * dir.y + frame[5] * dir.z),
                  float(frame[6] * dir.x + frame[7] * dir.y + frame[8] * dir.z)};
      const double cos_l = -glm::dot(s.normals[k], dir);
      weight[i] = local[i].z > 0.f && cos_l > 0.0 && r > 0.0
                      ? 1.0 / (ph_n + c.area_samples * area_pdf(s, r, cos_l))
                      : 0.0;
    }
    c.caster.occluded_packet(origin, d, kPacketSize, 1.f - 1e-4f, occluded);
    for (int i = 0; i < kPacketSize; ++i) {
      if (weight[i] == 0.0 || occluded[i]) continue;
      sh::evaluate(c.order, local[i].x, local[i].y, local[i].z, y.data());
      double radiance[3] = {weight[i], weight[i], weight[i]};
      add_rows(K, 1, radiance, y.data(), &g[e * 3 * K]);
    }
  }
}

}  // namespace

prt::GlossyEmitterRadiance gather_glossy_emitters(const scene::Scene& scene,
                                                  const prt::GlossyTransferData& glossy,
                                                  const prt::EmitterResponses& responses,
                                                  const GlossyEmitterGatherOptions& o,
                                                  GlossyEmitterGatherStatistics* stats) {
  const auto start = std::chrono::steady_clock::now();
  check_inputs(scene, glossy, responses, o);
  std::optional<tbb::global_control> thread_limit;
  if (o.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(o.threads));
  const std::size_t V = scene.vertex_count(), E = responses.emitter_count();
  const int order = static_cast<int>(glossy.order), N = round_up_to_packet(o.samples);
  const std::size_t K = std::size_t(order) * order;
  prt::GlossyEmitterRadiance out;
  out.order = glossy.order;
  out.vertex_count = V;
  out.emitters = responses.emitters;
  out.coefficients.assign(V * E * 3 * K, 0.f);
  out.emitter_of_vertex = emitters_of_vertices(scene, responses);
  const std::vector<EmitterSurface> surfaces = emitter_surfaces(scene, out.emitter_of_vertex, E);
  std::vector<double> frames(9 * V);
  for (std::size_t v = 0; v < V; ++v)
    if (const prt::Status s = prt::glossy_vertex_frame(glossy, v, &frames[9 * v]); !s.ok())
      throw BakeError(s.message());
  const scene::RayCaster caster(scene);
  std::atomic<uint64_t> hits{0};
  const GatherContext context{
      scene,     caster,
      responses, out.emitter_of_vertex,
      surfaces,  order,
      N,         o.emitter_samples > 0 ? round_up_to_packet(o.emitter_samples) : 0,
      o.seed};
  tbb::parallel_for(std::size_t{0}, (V + kBlock - 1) / kBlock, [&](std::size_t block) {
    std::vector<double> g(E * 3 * K);
    std::vector<float> y(K);
    uint64_t block_hits = 0;
    for (std::size_t v = block * kBlock; v < std::min(V, (block + 1) * kBlock); ++v) {
      std::fill(g.begin(), g.end(), 0.0);
      gather_hemisphere(context, &frames[9 * v], v, g, y, block_hits);
      for (std::size_t e = 0; e < E; ++e) gather_emitter_area(context, &frames[9 * v], v, e, g, y);
      float* dst = &out.coefficients[v * E * 3 * K];
      for (std::size_t k = 0; k < g.size(); ++k) dst[k] = static_cast<float>(g[k]);
    }
    hits += block_hits;
  });
  if (stats) {
    stats->rays = uint64_t(V) * (N + uint64_t(context.area_samples) * E);
    stats->front_hits = hits.load();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

}  // namespace prt::bake
