// bake/src/haar_baker.cpp — the Haar-wavelet bake (see bake/haar_baker.h).
#include "bake/haar_baker.h"
#include "bake/haar_part.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "bake/compact_gather.h"
#include "bake/interreflection_solver.h"
#include "bake/progress.h"
#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "prt/core/memory_budget.h"
#include "prt/formats/part_file.h"
#include "prt/haar/cube_map.h"
#include "prt/haar/transform.h"
#include "scene/ray_caster.h"
#include "scene/scene_label.h"
#include "sh/constants.h"

#include "hit_side.h"
#include "transfer_geometry.h"

namespace prt::bake {
namespace {

using Clock = std::chrono::steady_clock;
using sh::kInvPi;
constexpr std::size_t kVerticesPerTask = 32;     // fixed: determinism does not depend on it
constexpr std::size_t kVerticesPerChunk = 4096;  // sparse vectors held before the builder
constexpr int kSolveColumns = 64;                // interreflection: columns per Krylov solve

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Every (sub-)texel direction of the cube with its quadrature weight (exact solid angle).
struct TexelSamples {
  int per_texel = 1;                 // S²
  std::vector<glm::vec3> direction;  // texel-major: [t·S² + s]
  std::vector<float> solid_angle;
};

TexelSamples make_texel_samples(int size, int supersample, uint64_t seed) {
  TexelSamples ts;
  const int s2 = supersample * supersample;
  ts.per_texel = s2;
  const std::size_t texels = std::size_t{6} * size * size;
  ts.direction.resize(texels * s2);
  ts.solid_angle.resize(texels * s2);
  const double texel_width = 2.0 / size, sub_width = texel_width / supersample;
  for (int face = 0; face < 6; ++face) {
    for (int row = 0; row < size; ++row) {
      for (int col = 0; col < size; ++col) {
        const std::size_t t = (std::size_t(face) * size + row) * size + col;
        for (int sy = 0; sy < supersample; ++sy) {
          for (int sx = 0; sx < supersample; ++sx) {
            const std::size_t i = t * s2 + sy * supersample + sx;
            const double a0 = -1.0 + col * texel_width + sx * sub_width;
            const double b0 = -1.0 + row * texel_width + sy * sub_width;
            double ja = 0.5, jb = 0.5;  // centre for S = 1
            if (supersample > 1) {
              const uint64_t h = hash_seed(seed, i);
              ja = static_cast<double>(h >> 40) * 0x1p-24;
              jb = static_cast<double>(h & 0xffffffu) * 0x1p-24;
            }
            double d[3];
            cube_face_point_direction(face, a0 + ja * sub_width, b0 + jb * sub_width, d);
            ts.direction[i] = glm::vec3(float(d[0]), float(d[1]), float(d[2]));
            ts.solid_angle[i] =
                static_cast<float>(supersample == 1 ? cube_texel_solid_angle(size, col, row)
                                                    : cube_face_rect_solid_angle(
                                                          a0, a0 + sub_width, b0, b0 + sub_width));
          }
        }
      }
    }
  }
  return ts;
}

// One H row under construction: (vertex, weight) pairs, merged when emitted.
using GatherRow = std::vector<std::pair<uint32_t, float>>;

// Traces vertex v's texel rays; writes the grey quadrature transfer Σ V·cos·Ω into
// `dense` (6N² floats, albedo not applied) and, when `row` is given, its gather row: with
// gather_channels = C > 0 (albedo kept apart), C blocks of V columns whose weights hold the hit
// point's albedo (as the SH baker, transfer_pass.h). Returns the rays cast.
uint64_t trace_vertex(const scene::Scene& scene, const scene::RayCaster& caster,
                      const TexelSamples& ts, uint32_t v, bool shadows, int gather_channels,
                      GatherRow* row, float* dense) {
  const glm::vec3 n = glm::normalize(scene.normals[v]);
  const glm::vec3 origin = caster.vertex_origin(v);
  const std::size_t samples = ts.direction.size();
  const int s2 = ts.per_texel;
  glm::vec3 dirs[kPacketSize];
  uint32_t texel[kPacketSize];
  float weight[kPacketSize];
  bool occluded[kPacketSize];
  scene::RayCaster::Hit hits[kPacketSize];
  int count = 0;
  uint64_t rays = 0;
  const float tfar = std::numeric_limits<float>::infinity();
  auto flush = [&] {
    if (count == 0) return;
    if (row != nullptr) {
      caster.intersect_packet(origin, dirs, count, tfar, hits);
      for (int i = 0; i < count; ++i) {
        occluded[i] = hits[i].hit;
        if (!hits[i].hit) continue;
        // Back faces occlude but reflect nothing (hit_side.h, as the SH baker).
        if (!detail::ray_hits_front_side(scene, hits[i].triangle, dirs[i])) continue;
        const glm::uvec3 tri = scene.triangles[hits[i].triangle];
        const float w = static_cast<float>(weight[i] * kInvPi);
        if (gather_channels == 0) {
          row->emplace_back(tri.x, w * (1.f - hits[i].u - hits[i].v));
          row->emplace_back(tri.y, w * hits[i].u);
          row->emplace_back(tri.z, w * hits[i].v);
          continue;
        }
        const glm::vec3 rho = scene.albedo_at(hits[i].triangle, hits[i].u, hits[i].v);
        const auto V = static_cast<uint32_t>(scene.positions.size());
        for (int c = 0; c < gather_channels; ++c) {
          const uint32_t block = static_cast<uint32_t>(c) * V;
          row->emplace_back(block + tri.x, w * rho[c] * (1.f - hits[i].u - hits[i].v));
          row->emplace_back(block + tri.y, w * rho[c] * hits[i].u);
          row->emplace_back(block + tri.z, w * rho[c] * hits[i].v);
        }
      }
    } else {
      caster.occluded_packet(origin, dirs, count, tfar, occluded);
    }
    rays += static_cast<uint64_t>(count);
    for (int i = 0; i < count; ++i)
      if (!occluded[i]) dense[texel[i]] += weight[i];
    count = 0;
  };
  for (std::size_t i = 0; i < samples; ++i) {
    const float c = glm::dot(n, ts.direction[i]);
    if (!(c > 0.f)) continue;  // below the horizon: contributes nothing, no ray
    const float w = c * ts.solid_angle[i];
    const uint32_t t = static_cast<uint32_t>(i / s2);
    if (!shadows) {
      dense[t] += w;
      continue;
    }
    dirs[count] = ts.direction[i];
    texel[count] = t;
    weight[count] = w;
    if (++count == kPacketSize) flush();
  }
  flush();
  return rays;
}

std::string metadata_json(const scene::Scene& scene, const HaarBakeOptions& o, int channels,
                          bool apart) {
  nlohmann::json j;
  j["generator"] = "prt bake --basis haar";
  j["basis"] = "haar";
  j["haar"] = {{"cube_size", o.cube_size},
               {"faces", "+X,-X,+Y,-Y,+Z,-Z; wavelet index face*N^2+q, non-standard 2D Haar"},
               {"supersample", o.supersample},
               {"relative_threshold", o.compression.relative_threshold},
               {"max_terms_per_vertex", o.compression.max_terms_per_vertex},
               {"quantization_bits", static_cast<int>(o.compression.quantization)}};
  j["transport"] = transfer_kind_name(o.transport);
  j["albedo_folded"] = !apart;
  if (apart) j["albedo_kept_apart"] = "textured scene: multiply by the surface's (texture) albedo";
  j["channels"] = channels;
  j["frame"] = "glTF, +Y up";
  j["scene"] = scene.source_path;
  j["seed"] = o.seed;
  return j.dump();
}

void validate_haar_options(const scene::Scene& scene, const HaarBakeOptions& o) {
  const std::string name = scene.source_path.empty() ? "scene" : scene.source_path;
  if (o.transport != prt::TransferKind::Unshadowed && o.transport != prt::TransferKind::Shadowed &&
      o.transport != prt::TransferKind::Interreflected)
    throw BakeError(name + ": Haar transport must be unshadowed, shadowed or interreflected");
  if (!prt::is_valid_cube_size(o.cube_size))
    throw BakeError(name + ": cube size " + std::to_string(o.cube_size) +
                    " is not a power of two in [8, 128]");
  if (o.supersample < 1 || o.supersample > kMaxHaarSupersample)
    throw BakeError(name + ": supersampling " + std::to_string(o.supersample) + " is outside [1, " +
                    std::to_string(kMaxHaarSupersample) + "]");
  if (!(o.compression.relative_threshold >= 0.0 && o.compression.relative_threshold < 1.0))
    throw BakeError(name + ": relative threshold must be in [0, 1)");
  if (o.compression.max_terms_per_vertex < 0)
    throw BakeError(name + ": terms per vertex must be >= 0 (0 = no limit)");
  // The shared scene and albedo checks of the SH baker.
  BakeOptions sh;
  sh.kind = o.transport;
  sh.order = 1;
  sh.bounces = o.bounces;
  sh.bounce_tolerance = o.bounce_tolerance;
  sh.max_solver_iterations = o.max_solver_iterations;
  sh.threads = o.threads;
  validate_bake_inputs(scene, sh);
  if (o.transport == prt::TransferKind::Interreflected && scene.textured() &&
      3 * uint64_t(scene.vertex_count()) > 0xffffffffull)
    throw BakeError(name + ": too many vertices for interreflection with the albedo kept apart");
  if (o.transport == prt::TransferKind::Interreflected) {
    const uint64_t channels = 3;  // upper bound
    const uint64_t bytes =
        uint64_t(scene.vertex_count()) * 6 * uint64_t(o.cube_size) * o.cube_size * channels * 4;
    if (bytes > kMaxHaarInterreflectionBytes)
      throw BakeError(name + ": interreflected Haar transfer at cube size " +
                      std::to_string(o.cube_size) + " needs " + std::to_string(bytes >> 20) +
                      " MiB of dense wavelet coefficients; use a smaller --cube");
  }
}

// What every phase of one Haar bake shares: the scene, the options and the sizes derived from
// them, the directions traced and the BVH, the progress sink and the rays cast per task.
struct HaarBakeContext {
  const scene::Scene& scene;
  const HaarBakeOptions& options;
  const std::size_t V;  // vertices
  const int N;          // cube size
  const std::size_t W;  // texels = wavelet coefficients
  const int C;          // channels: 1 when the albedo is grey (or kept apart without bounces)
  const bool shadows;
  const bool apart;  // the albedo is kept apart (textured scene, bake/transfer_baker.h)
  const TexelSamples& ts;
  const scene::RayCaster* caster;  // null when merging parts (no rays)
  ProgressSink* progress;
  std::vector<uint64_t> task_rays;  // rays cast per task of kVerticesPerTask vertices

  // Dense per-vertex transfer (texel domain, albedo/π applied, or 1/π when it is kept apart), C
  // channels interleaved.
  uint64_t dense_transfer(uint32_t v, GatherRow* row, std::vector<float>& grey_dense,
                          std::vector<float>& dense) const {
    std::fill(grey_dense.begin(), grey_dense.end(), 0.f);
    const uint64_t rays =
        trace_vertex(scene, *caster, ts, v, shadows, apart ? C : 0, row, grey_dense.data());
    for (int c = 0; c < C; ++c) {
      const float k = static_cast<float>((apart ? 1.0 : scene.albedo[v][c]) * kInvPi);
      for (std::size_t t = 0; t < W; ++t) dense[t * C + c] = grey_dense[t] * k;
    }
    return rays;
  }
};

// Unshadowed or shadowed transfer: each vertex traced, compressed and added to the builder, a
// chunk of vertices at a time.
void bake_direct_haar(HaarBakeContext& ctx, prt::HaarTransferBuilder& builder) {
  const std::size_t V = ctx.V, W = ctx.W;
  const int N = ctx.N, C = ctx.C;
  std::vector<prt::SparseVertexTransfer> sparse;
  for (std::size_t first = 0; first < V; first += kVerticesPerChunk) {
    const std::size_t end = std::min(V, first + kVerticesPerChunk);
    sparse.assign(end - first, {});
    tbb::parallel_for(first, end, kVerticesPerTask, [&](std::size_t task_first) {
      std::vector<float> grey_dense(W), dense(W * C);
      const std::size_t task_end = std::min(end, task_first + kVerticesPerTask);
      uint64_t rays = 0;
      for (std::size_t v = task_first; v < task_end; ++v) {
        rays += ctx.dense_transfer(static_cast<uint32_t>(v), nullptr, grey_dense, dense);
        prt::Result<prt::SparseVertexTransfer> s =
            prt::compress_vertex_transfer(dense.data(), N, C, ctx.options.compression);
        sparse[v - first] = std::move(s.value());  // size and channels were validated
      }
      ctx.task_rays[task_first / kVerticesPerTask] = rays;
      if (ctx.progress) ctx.progress->advance(task_end - task_first, rays);
    });
    for (const prt::SparseVertexTransfer& s : sparse) {
      const prt::Status added = builder.add_vertex(s);
      if (!added.ok()) throw BakeError(ctx.scene.source_path + ": " + added.message());
    }
  }
}

// Merges a gather row's entries by column (sorted), dropping columns of zero weight.
void merge_gather_row(GatherRow& row) {
  std::sort(row.begin(), row.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::size_t kept = 0;
  for (std::size_t i = 0; i < row.size();) {
    const uint32_t col = row[i].first;
    double w = 0.0;
    for (; i < row.size() && row[i].first == col; ++i) w += row[i].second;
    if (w > 0.0) row[kept++] = {col, static_cast<float>(w)};
  }
  row.resize(kept);
}

// Interreflection, pass 1: every vertex's direct transfer D̂ (wavelet domain, dense, into
// coeffs: V × W × C) and its gather row of H (into rows).
void trace_direct_wavelets(HaarBakeContext& ctx, std::vector<float>& coeffs,
                           std::vector<GatherRow>& rows) {
  const std::size_t V = ctx.V, W = ctx.W;
  const int N = ctx.N, C = ctx.C;
  tbb::parallel_for(std::size_t(0), V, kVerticesPerTask, [&](std::size_t task_first) {
    std::vector<float> grey_dense(W);
    const std::size_t task_end = std::min(V, task_first + kVerticesPerTask);
    uint64_t rays = 0;
    for (std::size_t v = task_first; v < task_end; ++v) {
      std::vector<float> dense(W * C);
      rays += ctx.dense_transfer(static_cast<uint32_t>(v), &rows[v], grey_dense, dense);
      float* out = coeffs.data() + v * W * C;
      std::copy(dense.begin(), dense.end(), out);
      for (int face = 0; face < 6; ++face)
        for (int c = 0; c < C; ++c)
          prt::forward_haar_2d(out + std::size_t(face) * N * N * C + c, N, C);
      merge_gather_row(rows[v]);
    }
    ctx.task_rays[task_first / kVerticesPerTask] = rays;
    if (ctx.progress) ctx.progress->advance(task_end - task_first, rays);
  });
}

// The gather rows as one sparse matrix H (rows are emptied).
SparseTransferMatrix gather_matrix(std::vector<GatherRow>& rows) {
  SparseTransferMatrix h;
  h.row_offsets.reserve(rows.size() + 1);
  for (const GatherRow& row : rows) {
    for (const auto& [col, w] : row) {
      h.columns.push_back(col);
      h.weights.push_back(w);
    }
    h.row_offsets.push_back(h.columns.size());
  }
  rows = {};
  return h;
}

// Interreflection, pass 2: T̂ = D̂ + diag(ρ) H T̂, per channel, in chunks of wavelet columns
// (coeffs: D̂ in, T̂ out).
void solve_wavelet_interreflection(const HaarBakeContext& ctx, const SparseTransferMatrix& h,
                                   std::vector<float>& coeffs, HaarBakeStatistics& st) {
  const std::size_t V = ctx.V, W = ctx.W;
  const int C = ctx.C;
  const Clock::time_point t_solve = Clock::now();
  SolveOptions so;
  so.bounces = ctx.options.bounces;
  so.tolerance = ctx.options.bounce_tolerance;
  so.max_iterations = ctx.options.max_solver_iterations;
  std::vector<double> d(V * kSolveColumns), t(V * kSolveColumns);
  for (int c = 0; c < C; ++c) {
    // Kept apart: G = D + H_c G with channel c's block of H and no receiver albedo.
    std::vector<double> rho(V, 1.0);
    const SparseTransferMatrix block =
        ctx.apart ? column_block(h, static_cast<uint64_t>(c) * V, V) : SparseTransferMatrix{};
    if (!ctx.apart)
      for (std::size_t v = 0; v < V; ++v) rho[v] = ctx.scene.albedo[v][c];
    const SparseTransferMatrix& hc = ctx.apart ? block : h;
    for (std::size_t first = 0; first < W; first += kSolveColumns) {
      const int cols = static_cast<int>(std::min<std::size_t>(kSolveColumns, W - first));
      for (std::size_t v = 0; v < V; ++v)
        for (int k = 0; k < cols; ++k) d[v * cols + k] = coeffs[(v * W + first + k) * C + c];
      const SolveReport r = solve_interreflection(hc, rho, d.data(), cols, t.data(), so);
      st.solver_iterations += r.krylov_iterations;
      st.solver_residual = std::max(st.solver_residual, r.relative_residual);
      st.solver_converged = st.solver_converged && r.converged;
      for (std::size_t v = 0; v < V; ++v)
        for (int k = 0; k < cols; ++k)
          coeffs[(v * W + first + k) * C + c] = static_cast<float>(t[v * cols + k]);
    }
  }
  st.seconds_solve = seconds_since(t_solve);
}

// Interreflection after the rays: H from the gather rows, the solve of D̂ in coeffs, then every
// vertex's T̂ truncated and added to the builder.
void finish_interreflected_haar(HaarBakeContext& ctx, prt::HaarTransferBuilder& builder,
                                HaarBakeStatistics& st, std::vector<float>& coeffs,
                                std::vector<GatherRow>& rows) {
  const std::size_t V = ctx.V, W = ctx.W;
  const int N = ctx.N, C = ctx.C;
  const SparseTransferMatrix h = gather_matrix(rows);
  solve_wavelet_interreflection(ctx, h, coeffs, st);
  for (std::size_t v = 0; v < V; ++v) {
    const prt::SparseVertexTransfer s =
        prt::truncate_vertex_coefficients(coeffs.data() + v * W * C, N, C, ctx.options.compression);
    const prt::Status added = builder.add_vertex(s);
    if (!added.ok()) throw BakeError(ctx.scene.source_path + ": " + added.message());
  }
}

// Interreflected transfer: pass 1 traces (the rays' statistics are recorded when it ends),
// pass 2 solves and truncates.
void bake_interreflected_haar(HaarBakeContext& ctx, prt::HaarTransferBuilder& builder,
                              HaarBakeStatistics& st, Clock::time_point t_rays) {
  std::vector<float> coeffs(ctx.V * ctx.W * ctx.C);
  std::vector<GatherRow> rows(ctx.V);
  trace_direct_wavelets(ctx, coeffs, rows);
  if (ctx.progress) ctx.progress->finish();
  for (uint64_t r : ctx.task_rays) st.rays += r;
  st.seconds_rays = seconds_since(t_rays);
  finish_interreflected_haar(ctx, builder, st, coeffs, rows);
}

// The parts of a sharded bake (haar_part.h) in place of the rays: each vertex's truncated vector
// added in vertex order, or D̂ and the gather rows assembled for the single bake's solve.
void fill_haar_from_parts(HaarBakeContext& ctx, prt::HaarTransferBuilder& builder,
                          HaarBakeStatistics& st, const std::vector<const HaarPart*>& parts) {
  const std::size_t V = ctx.V, WC = ctx.W * static_cast<std::size_t>(ctx.C);
  const std::vector<uint32_t> order = make_morton_order(ctx.scene.positions);
  for (const HaarPart* p : parts) st.rays += p->rays;
  if (ctx.options.transport != prt::TransferKind::Interreflected) {
    // Each vertex's part, row in it and first index of its vector there.
    struct Where {
      const HaarPart* part;
      std::size_t row;
      uint64_t first;
    };
    std::vector<Where> at(V);
    for (const HaarPart* p : parts) {
      uint64_t first = 0;
      for (std::size_t i = 0; i < p->rows.size(); ++i) {
        at[order[p->rows.first + i]] = {p, i, first};
        first += p->sparse_lengths[i];
      }
    }
    // Vertex order takes rows from every part in turn (Morton rows): the parts' pages go at the
    // end, when every vector is in the builder.
    for (std::size_t v = 0; v < V; ++v) {
      const HaarPart& p = *at[v].part;
      const uint64_t first = at[v].first, n = p.sparse_lengths[at[v].row];
      const uint32_t* index = p.index_data() + first;
      const float* values = p.values_data() + first * ctx.C;
      prt::SparseVertexTransfer s;
      s.index.assign(index, index + n);
      s.values.assign(values, values + n * ctx.C);
      const prt::Status added = builder.add_vertex(s);
      if (!added.ok()) throw BakeError(ctx.scene.source_path + ": " + added.message());
    }
    for (const HaarPart* p : parts) release_haar_part_pages(*p);
    return;
  }
  std::vector<float> coeffs(V * WC);
  std::vector<GatherRow> rows(V);
  for (const HaarPart* p : parts) {
    const float* wavelets = p->wavelet_data();
    const uint32_t* columns = p->column_data();
    const float* weights = p->weight_data();
    uint64_t entry = 0;
    for (std::size_t i = 0; i < p->rows.size(); ++i) {
      const std::size_t v = order[p->rows.first + i];
      std::copy(wavelets + i * WC, wavelets + (i + 1) * WC, coeffs.begin() + v * WC);
      for (uint32_t k = 0; k < p->gather_lengths[i]; ++k, ++entry)
        rows[v].emplace_back(columns[entry], weights[entry]);
    }
    release_haar_part_pages(*p);  // its rows copied: one part's pages at a time
  }
  finish_interreflected_haar(ctx, builder, st, coeffs, rows);
}

}  // namespace

namespace {

// Channels: 1 when the albedo is grey (or kept apart without bounces), else 3.
int haar_channels(const scene::Scene& scene, const HaarBakeOptions& options) {
  const bool interreflect = options.transport == prt::TransferKind::Interreflected;
  const bool apart = scene.textured();
  bool grey = true;
  for (const glm::vec3& a : scene.albedo) grey = grey && a.x == a.y && a.y == a.z;
  for (const scene::ScenePrimitive& p : scene.primitives)
    if (p.base_color_texture) {
      const glm::vec3 f = p.base_color_texture->factor;
      grey = grey && f.x == f.y && f.y == f.z && p.base_color_texture->image->grey();
    }
  return grey || (apart && !interreflect) ? 1 : 3;
}

// bake_haar_transfer, or (with `parts`) the merge of a sharded bake's parts (no BVH, no rays).
HaarBakeResult bake_haar_with(const scene::Scene& scene, const HaarBakeOptions& options,
                              ProgressSink* progress, const std::vector<const HaarPart*>* parts) {
  const Clock::time_point t_start = Clock::now();
  validate_haar_options(scene, options);
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  options.threads);
  const std::size_t V = scene.vertex_count();
  const int N = options.cube_size;
  const bool interreflect = options.transport == prt::TransferKind::Interreflected;
  const bool apart = scene.textured();
  const int C = haar_channels(scene, options);

  HaarBakeResult result;
  HaarBakeStatistics& st = result.stats;
  st.vertices = V;
  st.triangles = scene.triangles.size();
  const TexelSamples ts = make_texel_samples(N, options.supersample, options.seed);
  std::optional<scene::RayCaster> caster;
  if (!parts) caster.emplace(scene);
  prt::HaarTransferBuilder builder(N, C, options.compression.quantization);
  HaarBakeContext ctx{scene,
                      options,
                      V,
                      N,
                      std::size_t{6} * N * N,
                      C,
                      options.transport != prt::TransferKind::Unshadowed,
                      apart,
                      ts,
                      caster ? &*caster : nullptr,
                      progress,
                      {}};
  // The memory known before the rays: interreflection holds every vertex's dense wavelet
  // vector (6N² × channels floats) and the Krylov solve's blocks (d, t and BiCGSTAB's seven, of
  // kSolveColumns doubles per vertex). The gather rows and the truncated output grow with what
  // the rays see and are not charged.
  MemoryBudget budget(options.memory_limit, scene.source_path);
  if (interreflect) {
    budget.charge(uint64_t(V) * ctx.W * uint64_t(C) * sizeof(float),
                  "the dense wavelet coefficients of the interreflection");
    budget.charge(uint64_t(V) * 9 * kSolveColumns * sizeof(double),
                  "the interreflection solve's blocks");
  }
  const Clock::time_point t_rays = Clock::now();
  ctx.task_rays.assign((V + kVerticesPerTask - 1) / kVerticesPerTask, 0);
  if (parts) {
    fill_haar_from_parts(ctx, builder, st, *parts);
  } else if (!interreflect) {
    if (progress) progress->start("bake haar", V);
    bake_direct_haar(ctx, builder);
    if (progress) progress->finish();
    for (uint64_t r : ctx.task_rays) st.rays += r;
    st.seconds_rays = seconds_since(t_rays);
  } else {
    if (progress) progress->start("bake haar", V);
    bake_interreflected_haar(ctx, builder, st, t_rays);
  }

  prt::Result<prt::HaarTransfer> transfer = builder.finish();
  if (!transfer.ok()) throw BakeError(scene.source_path + ": " + transfer.status().message());
  prt::HaarTransferFile& file = result.file;
  file.transfer = std::move(transfer.value());
  prt::TransferData& info = file.info;
  info.kind = prt::TransferKind::Haar;
  info.order = static_cast<uint32_t>(N);
  info.channels = static_cast<uint32_t>(C);
  info.albedo_folded = !apart;
  detail::store_scene_geometry(scene, info);
  info.metadata_json = metadata_json(scene, options, C, apart);
  st.stored_bytes = file.transfer.stored_bytes();
  st.dense_bytes = file.transfer.dense_bytes();
  st.entries = file.transfer.entry_count();
  st.seconds_total = seconds_since(t_start);
  return result;
}

}  // namespace

HaarBakeResult bake_haar_transfer(const scene::Scene& scene, const HaarBakeOptions& options,
                                  ProgressSink* progress) {
  return bake_haar_with(scene, options, progress, nullptr);
}

void check_haar_shardable(const scene::Scene& scene, const HaarBakeOptions&) {
  if (scene.textured())
    throw BakeError(scene::scene_label(scene) +
                    ": a sharded bake needs the albedo folded into the transfer (the scene is "
                    "textured)");
}

HaarPart bake_haar_part(const scene::Scene& scene, const HaarBakeOptions& options, ShardSpec shard,
                        ProgressSink* progress) {
  const Clock::time_point t_start = Clock::now();
  validate_haar_options(scene, options);
  check_haar_shardable(scene, options);
  if (shard.count == 0 || shard.index >= shard.count)
    throw BakeError(scene::scene_label(scene) + ": not a shard");
  std::unique_ptr<tbb::global_control> limit;
  if (options.threads > 0)
    limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                  options.threads);
  HaarPart part;
  part.shard = shard;
  part.vertices = scene.vertex_count();
  part.rows = shard_rows(part.vertices, shard);
  part.channels = haar_channels(scene, options);
  const int N = options.cube_size, C = part.channels;
  const std::size_t W = std::size_t{6} * N * N, n = part.rows.size();
  const bool interreflect = options.transport == prt::TransferKind::Interreflected;
  const TexelSamples ts = make_texel_samples(N, options.supersample, options.seed);
  const scene::RayCaster caster(scene);
  HaarBakeContext ctx{scene,
                      options,
                      part.vertices,
                      N,
                      W,
                      C,
                      options.transport != prt::TransferKind::Unshadowed,
                      false,
                      ts,
                      &caster,
                      progress,
                      {}};
  const std::vector<uint32_t> order = make_morton_order(scene.positions);
  std::vector<prt::SparseVertexTransfer> sparse(interreflect ? 0 : n);
  std::vector<GatherRow> rows(interreflect ? n : 0);
  if (interreflect) {
    MemoryBudget budget(options.memory_limit, scene.source_path);
    budget.charge(uint64_t(n) * W * uint64_t(C) * sizeof(float),
                  "the dense wavelet coefficients of the interreflection");
    part.wavelets.assign(n * W * C, 0.f);
  }
  const Clock::time_point t_rays = Clock::now();
  ctx.task_rays.assign((n + kVerticesPerTask - 1) / kVerticesPerTask, 0);
  if (progress) progress->start("bake haar", n);
  tbb::parallel_for(std::size_t(0), n, kVerticesPerTask, [&](std::size_t task_first) {
    std::vector<float> grey_dense(W), dense(W * C);
    const std::size_t task_end = std::min(n, task_first + kVerticesPerTask);
    uint64_t rays = 0;
    for (std::size_t i = task_first; i < task_end; ++i) {
      const uint32_t v = order[part.rows.first + i];
      rays += ctx.dense_transfer(v, interreflect ? &rows[i] : nullptr, grey_dense, dense);
      if (!interreflect) {
        sparse[i] = std::move(
            prt::compress_vertex_transfer(dense.data(), N, C, options.compression).value());
        continue;
      }
      float* out = part.wavelets.data() + i * W * C;
      std::copy(dense.begin(), dense.end(), out);
      for (int face = 0; face < 6; ++face)
        for (int c = 0; c < C; ++c)
          prt::forward_haar_2d(out + std::size_t(face) * N * N * C + c, N, C);
      merge_gather_row(rows[i]);
    }
    ctx.task_rays[task_first / kVerticesPerTask] = rays;
    if (progress) progress->advance(task_end - task_first, rays);
  });
  if (progress) progress->finish();
  for (uint64_t r : ctx.task_rays) part.rays += r;
  for (const prt::SparseVertexTransfer& sv : sparse) {
    part.sparse_lengths.push_back(static_cast<uint32_t>(sv.index.size()));
    part.sparse_index.insert(part.sparse_index.end(), sv.index.begin(), sv.index.end());
    part.sparse_values.insert(part.sparse_values.end(), sv.values.begin(), sv.values.end());
  }
  for (const GatherRow& row : rows) {
    part.gather_lengths.push_back(static_cast<uint32_t>(row.size()));
    for (const auto& [col, w] : row) {
      part.gather_columns.push_back(col);
      part.gather_weights.push_back(w);
    }
  }
  part.stats.vertices = n;
  part.stats.rays = part.rays;
  part.stats.seconds_rays = seconds_since(t_rays);
  part.stats.seconds_total = seconds_since(t_start);
  return part;
}

void release_haar_part_pages(const HaarPart& p) {
  if (!p.mapped) return;
  const HaarPart::Mapped& m = p.view;
  prt::release_part_pages(m.sparse_index, m.entries * sizeof(uint32_t));
  prt::release_part_pages(m.sparse_values, m.entries * p.channels * sizeof(float));
  prt::release_part_pages(m.wavelets, m.texels * sizeof(float));
  prt::release_part_pages(m.gather_columns, m.gathered * sizeof(uint32_t));
  prt::release_part_pages(m.gather_weights, m.gathered * sizeof(float));
}

HaarBakeResult merge_haar_parts(const scene::Scene& scene, const HaarBakeOptions& options,
                                const std::vector<const HaarPart*>& parts, ProgressSink* progress) {
  check_haar_shardable(scene, options);
  const std::string name = scene::scene_label(scene);
  const uint64_t V = scene.vertex_count();
  const int C = haar_channels(scene, options);
  const uint64_t WC = uint64_t{6} * options.cube_size * options.cube_size * C;
  const bool interreflect = options.transport == prt::TransferKind::Interreflected;
  uint64_t next = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const HaarPart& p = *parts[i];
    const uint64_t n = p.rows.size();
    const RowRange want =
        shard_rows(V, {static_cast<uint32_t>(i), static_cast<uint32_t>(parts.size())});
    uint64_t entries = 0, gathered = 0;
    for (uint32_t len : p.sparse_lengths) entries += len;
    for (uint32_t len : p.gather_lengths) gathered += len;
    bool ok = p.vertices == V && p.channels == C && p.rows.first == want.first &&
              p.rows.end == want.end && p.rows.first == next &&
              p.sparse_lengths.size() == (interreflect ? 0 : n) && p.index_size() == entries &&
              p.values_size() == entries * C && p.wavelet_size() == (interreflect ? n * WC : 0) &&
              p.gather_lengths.size() == (interreflect ? n : 0) && p.column_size() == gathered &&
              p.weight_size() == gathered;
    const uint32_t* columns = p.column_data();
    for (uint64_t k = 0; ok && k < gathered; ++k) ok = columns[k] < V;
    if (!ok)
      throw BakeError(name + ": part " + std::to_string(i) + " of " + std::to_string(parts.size()) +
                      " does not fit the scene or the split");
    release_haar_part_pages(p);  // checked: read again, one part at a time, when copied
    next = p.rows.end;
  }
  if (next != V) throw BakeError(name + ": the parts do not cover every vertex");
  return bake_haar_with(scene, options, progress, &parts);
}

}  // namespace prt::bake
