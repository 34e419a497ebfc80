// bake/src/glossy_emitter_gather.cpp — see bake/glossy_emitter_gather.h.
#include "bake/glossy_emitter_gather.h"

#include <atomic>
#include <chrono>
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

// G of one vertex into g (E · 3 · K doubles, overwritten).
void gather_vertex(const scene::Scene& scene, const scene::RayCaster& caster,
                   const prt::EmitterResponses& responses, const double frame[9], int order,
                   int samples, uint64_t seed, std::size_t v, std::vector<double>& g,
                   std::vector<float>& y, uint64_t& hits) {
  const std::size_t K = std::size_t(order) * order, E = responses.emitter_count();
  const std::size_t V = responses.vertex_count();
  std::fill(g.begin(), g.end(), 0.0);
  const uint64_t vertex_seed = hash_seed(seed, v);
  const glm::vec3 origin = caster.vertex_origin(static_cast<uint32_t>(v));
  const glm::vec3 t(frame[0], frame[1], frame[2]), b(frame[3], frame[4], frame[5]),
      n(frame[6], frame[7], frame[8]);
  glm::vec3 local[kPacketSize], dirs[kPacketSize];
  scene::RayCaster::Hit hit[kPacketSize];
  for (int first = 0; first < samples; first += kPacketSize) {
    for (int i = 0; i < kPacketSize; ++i) {
      local[i] = to_glm(numerics::sample_uniform_hemisphere(
          to_numerics(sample_sobol_2d(static_cast<uint32_t>(first + i), vertex_seed))));
      dirs[i] = glm::normalize(local[i].x * t + local[i].y * b + local[i].z * n);
    }
    caster.intersect_packet(origin, dirs, kPacketSize, std::numeric_limits<float>::infinity(), hit);
    for (int i = 0; i < kPacketSize; ++i) {
      if (!hit[i].hit || !detail::ray_hits_front_side(scene, hit[i].triangle, dirs[i])) continue;
      ++hits;
      const glm::uvec3 tri = scene.triangles[hit[i].triangle];
      const double beta[3] = {1.0 - hit[i].u - hit[i].v, hit[i].u, hit[i].v};
      sh::evaluate(order, local[i].x, local[i].y, local[i].z, y.data());
      for (std::size_t e = 0; e < E; ++e)
        for (int c = 0; c < 3; ++c) {
          double radiance = 0;
          for (int a = 0; a < 3; ++a)
            radiance += beta[a] * responses.responses[3 * (e * V + tri[a]) + c];
          if (radiance == 0.0) continue;
          double* row = &g[(e * 3 + c) * K];
          for (std::size_t k = 0; k < K; ++k) row[k] += radiance * y[k];
        }
    }
  }
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
  std::vector<double> frames(9 * V);
  for (std::size_t v = 0; v < V; ++v)
    if (const prt::Status s = prt::glossy_vertex_frame(glossy, v, &frames[9 * v]); !s.ok())
      throw BakeError(s.message());
  const scene::RayCaster caster(scene);
  std::atomic<uint64_t> hits{0};
  const double w = 2.0 * sh::kPi / N;
  tbb::parallel_for(std::size_t{0}, (V + kBlock - 1) / kBlock, [&](std::size_t block) {
    std::vector<double> g(E * 3 * K);
    std::vector<float> y(K);
    uint64_t block_hits = 0;
    for (std::size_t v = block * kBlock; v < std::min(V, (block + 1) * kBlock); ++v) {
      gather_vertex(scene, caster, responses, &frames[9 * v], order, N, o.seed, v, g, y,
                    block_hits);
      float* dst = &out.coefficients[v * E * 3 * K];
      for (std::size_t k = 0; k < g.size(); ++k) dst[k] = static_cast<float>(g[k] * w);
    }
    hits += block_hits;
  });
  if (stats) {
    stats->rays = uint64_t(V) * N;
    stats->front_hits = hits.load();
    stats->seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  return out;
}

}  // namespace prt::bake
