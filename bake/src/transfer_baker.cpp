// bake/src/transfer_baker.cpp — the per-vertex sampling pass, the gather matrix and the
// assembly of TransferData (see transfer_baker.h).
//
// Interreflection estimator (Sloan, Kautz & Snyder 2002, §6), derived:
//   the exit radiance of a diffuse vertex p with albedo ρ_p is
//     B_p = (ρ_p/π) ∫_{H(n)} L_in(ω) cos θ dω,
//   and L_in(ω) = V(ω)·L_env(ω) + B_q(ω), q(ω) the point the ray p→ω hits (exit radiance of a
//   diffuse surface is the same in every direction). With N directions of pdf cos θ/π,
//     ∫ f cos θ dω ≈ (1/N) Σ_s f(ω_s) · cos θ_s / (cos θ_s/π) = (π/N) Σ_s f(ω_s),
//   so B_p ≈ (ρ_p/π)(π/N) Σ_s [V L_env + B_q] = (ρ_p/N) Σ_s V(ω_s) L_env(ω_s)
//                                             + (ρ_p/N) Σ_{s hits} B_q(ω_s).
//   Writing L_env = Σ_k L_k Y_k and B_q = Σ_k T_q,k L_k, with T_q interpolated from the hit
//   triangle's vertices with barycentrics b_i (T_{v_i} already includes ρ_{v_i}/π):
//     T_p = D_p + ρ_p Σ_j H_pj T_j,  D_p,k = (ρ_p/N) Σ_s V(ω_s) Y_k(ω_s),
//     H_pj = (1/N) Σ_{s hits} Σ_{i : v_i = j} b_i(s).
//   The ρ_p/N weight is thus the receiver's albedo × the estimator weight π/N × the BRDF's 1/π.
// Back faces occlude but reflect nothing: the transfer stored for q describes only the side
// its vertex normals point to. The side is judged with the hit triangle's flat geometric
// normal, oriented by the sum of its vertex normals (front: dot(n_g, ω) < 0). Hits and occlusion
// come from the same ray (intersect instead of occluded), so D and H are consistent: every sample
// is visible, a front hit or a back hit. H memory: ≤ 3 (column, weight) pairs of 8 bytes per hit
// ray before merging; rows merge duplicate columns, so a row costs 8 bytes × distinct vertices hit
// (typically far fewer than 3·hits at high sample counts).
#include "bake/transfer_baker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <optional>
#include <utility>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "bake/cap_sampling.h"
#include "bake/interreflection_solver.h"
#include "bake/occluder_caps.h"
#include "bake/progress.h"
#include "bake/ray_caster.h"
#include "bake/sample_allocation.h"
#include "bake/sampling.h"
#include "bake/scene_analysis.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"

#include "hit_side.h"
#include "transfer_geometry.h"

#include "scene_label.h"

namespace prt::bake {
namespace {

using sh::kPi;
using sh::kY00;
constexpr int kMaxAdaptiveBounces = 200;      // then BiCGSTAB finishes the solve
constexpr std::size_t kVertexBlock = 64;      // vertices per parallel task (fixed: determinism)
constexpr uint64_t kReplicaSalt = 0x5245504c49434131ull;  // seeds the second adaptive replica
constexpr std::size_t kAuditStride = 8;           // every 8th sampled vertex audits the error model
constexpr std::size_t kMinAuditVertices = 64;     // fewer sampled vertices than 8 × 64: all audit
constexpr double kMinCalibration2 = 0.05 * 0.05;  // c is never taken below 0.05
constexpr std::size_t kMinClassAudits = 64;       // fewer in a class (hemisphere / caps): shared c
constexpr double kHitCost = 2.0;  // a ray that hits costs 1 + this × an escaping one (allocation)
constexpr uint32_t kRoundGrowth = 4;  // a vertex's samples grow at most 4× per allocation round
constexpr int kMaxRounds = 8;

using Clock = std::chrono::steady_clock;

int round_up(int n, int multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

// Casts `count` ≤ kPacketSize rays from `origin`: closest hits into `hits` (occluded[i] = a hit)
// when `hits` is not null, occlusion only otherwise.
void cast_packet(const RayCaster& caster, const glm::vec3& origin, const glm::vec3* dirs, int count,
                 float tfar, RayCaster::Hit* hits, bool* occluded) {
  if (hits != nullptr) {
    caster.intersect_packet(origin, dirs, count, tfar, hits);
    for (int i = 0; i < count; ++i) occluded[i] = hits[i].hit;
  } else {
    caster.occluded_packet(origin, dirs, count, tfar, occluded);
  }
}

std::string primitive_of(const Scene& scene, std::size_t v) {
  for (const ScenePrimitive& p : scene.primitives)
    if (v >= p.first_vertex && v < static_cast<std::size_t>(p.first_vertex) + p.vertex_count)
      return "primitive '" + p.name + "'";
  return "vertex " + std::to_string(v);
}

bool is_grey(const glm::vec3& a) {
  return a.x == a.y && a.y == a.z;
}

// The rows of H produced by one block of vertices.
struct BlockRows {
  std::vector<uint32_t> lengths;
  std::vector<uint32_t> columns;
  std::vector<float> weights;
};

// Per-vertex results of the sampling pass.
struct VertexSums {
  std::vector<double> visibility_sh;  // V × K: (1/N) Σ V Y_k (grey; albedo applied later)
  std::vector<float> ao;              // V
  std::vector<float> bent;            // 3V
};

// Appends the hit triangle's vertices, weighted by barycentrics × the sample's weight (1 under
// cosine-weighted sampling, bake/cap_sampling.h's w in caps), to a row being gathered; false
// (nothing added) when the ray sees the back side: the flat facet's geometric normal, oriented
// by the triangle's vertex normals (hit_side.h). A back face occludes only.
bool gather_front_hit(const Scene& scene, const RayCaster::Hit& hit, const glm::vec3& dir,
                      float weight, std::vector<std::pair<uint32_t, float>>& gathered) {
  if (!detail::ray_hits_front_side(scene, hit.triangle, dir)) return false;
  const glm::uvec3 tri = scene.triangles[hit.triangle];
  const float b0 = (1.f - hit.u - hit.v) * weight, b1 = hit.u * weight, b2 = hit.v * weight;
  gathered.emplace_back(tri.x, b0);
  gathered.emplace_back(tri.y, b1);
  gathered.emplace_back(tri.z, b2);
  return true;
}

// Merges duplicate columns of the gathered entries into one row of H, scaled by row_scale.
void append_row(std::vector<std::pair<uint32_t, float>>& gathered, double row_scale,
                BlockRows& br) {
  std::sort(gathered.begin(), gathered.end(),
            [](const auto& a, const auto& b) { return a.first < b.first; });
  uint32_t len = 0;
  for (std::size_t i = 0; i < gathered.size();) {
    const uint32_t col = gathered[i].first;
    double w = 0.0;
    for (; i < gathered.size() && gathered[i].first == col; ++i) w += gathered[i].second;
    if (w <= 0.0) continue;
    br.columns.push_back(col);
    br.weights.push_back(static_cast<float>(w * row_scale));
    ++len;
  }
  br.lengths.push_back(len);
}

double max_abs(const std::vector<double>& x) {
  double m = 0.0;
  for (double e : x) m = std::max(m, std::fabs(e));
  return m;
}

// Adaptive interreflection (transfer_baker.h): T = Σ_i (ρH)^i D, stopped after the first bounce
// whose max-norm is ≤ tolerance × max|D|; BiCGSTAB (to relative residual `tolerance`) finishes
// when kMaxAdaptiveBounces were not enough (ρ → 1). Skipped when H is empty or ρ = 0: T = D.
void solve_adaptively(const SparseTransferMatrix& h, const std::vector<double>& rho,
                      const std::vector<double>& direct, int columns, double tolerance,
                      std::vector<double>& t, BakeStatistics& st, ProgressSink* progress) {
  t = direct;
  const bool any_albedo = std::any_of(rho.begin(), rho.end(), [](double r) { return r > 0.0; });
  const double d_max = max_abs(direct);
  if (h.entries() == 0 || !any_albedo || d_max == 0.0) return;
  st.interreflection_solved = true;
  std::vector<double> bounce = direct, next(direct.size());
  int bounces = 0;
  bool stopped = false;
  while (bounces < kMaxAdaptiveBounces && !stopped) {
    multiply_gather(h, rho, bounce.data(), columns, next.data());
    const double energy = max_abs(next);
    for (std::size_t j = 0; j < t.size(); ++j) t[j] += next[j];
    bounce.swap(next);
    if (st.bounce_energy.size() <= static_cast<std::size_t>(bounces))
      st.bounce_energy.push_back(0.0);
    st.bounce_energy[bounces] = std::max(st.bounce_energy[bounces], energy);
    ++bounces;
    stopped = energy <= tolerance * d_max;
  }
  st.jacobi_bounces = std::max(st.jacobi_bounces, bounces);
  if (stopped) return;
  SolveOptions so;
  so.bounces = -1;
  so.tolerance = tolerance;
  const SolveReport rep =
      solve_interreflection(h, rho, direct.data(), columns, t.data(), so, progress);
  st.solver_iterations += rep.krylov_iterations;
  st.solver_residual = std::max(st.solver_residual, rep.relative_residual);
  st.solver_converged = st.solver_converged && rep.converged;
}

}  // namespace

void validate_bake_inputs(const Scene& scene, const BakeOptions& o) {
  const std::string name = detail::scene_label(scene);
  if (o.kind != prt::TransferKind::Unshadowed && o.kind != prt::TransferKind::Shadowed &&
      o.kind != prt::TransferKind::Interreflected)
    throw BakeError(name + ": transfer kind '" + transfer_kind_name(o.kind) +
                    "' is not supported by the SH baker");
  if (o.order < 1 || o.order > kMaxBakeOrder)
    throw BakeError(name + ": SH order " + std::to_string(o.order) + " is outside [1, " +
                    std::to_string(kMaxBakeOrder) + "]");
  if (o.samples < 1 || o.samples > kMaxBakeSamples)
    throw BakeError(name + ": " + std::to_string(o.samples) +
                    " samples per vertex is outside [1, " + std::to_string(kMaxBakeSamples) + "]");
  if (o.bounces < -1) throw BakeError(name + ": bounces must be >= 0, or -1 (until converged)");
  if (!(o.bounce_tolerance > 0.0) || !std::isfinite(o.bounce_tolerance) || o.bounce_tolerance >= 1)
    throw BakeError(name + ": bounce tolerance must be in (0, 1)");
  if (o.max_solver_iterations < 1) throw BakeError(name + ": solver iteration cap must be >= 1");
  if (o.threads < 0) throw BakeError(name + ": thread count must be >= 0");
  if (o.adaptive.enabled) {
    const AdaptiveSampling& a = o.adaptive;
    if (a.min_samples < 1 || a.max_samples < a.min_samples || a.max_samples > kMaxBakeSamples)
      throw BakeError(name + ": adaptive sample range [" + std::to_string(a.min_samples) + ", " +
                      std::to_string(a.max_samples) + "] is invalid");
    if (!(a.rms_error > 0.0) || !std::isfinite(a.rms_error))
      throw BakeError(name + ": adaptive RMS error target must be > 0");
    if (!(a.bounce_tolerance > 0.0) || !(a.bounce_tolerance < 1.0))
      throw BakeError(name + ": adaptive bounce tolerance must be in (0, 1)");
    if (a.compact_output && o.kind == prt::TransferKind::Interreflected)
      throw BakeError(name + ": compact output is for shadowed and unshadowed bakes");
    if (a.cap_sampling && (a.max_caps < 1 || a.max_caps > 256 || !(a.max_cap_solid_angle > 0.0) ||
                           !std::isfinite(a.max_cap_solid_angle) || a.min_cap_samples < 1))
      throw BakeError(name + ": cap sampling needs 1..256 caps, a solid angle > 0 and >= 1 sample");
    if (!a.vertex_mode.empty() && a.vertex_mode.size() != scene.positions.size())
      throw BakeError(name + ": adaptive vertex modes do not match the vertex count");
    if (a.lighting_order < 0 ||
        a.lighting.size() < static_cast<std::size_t>(a.lighting_order) * a.lighting_order)
      throw BakeError(name + ": adaptive lighting has fewer than order² coefficients");
  }
  if (scene.positions.empty()) throw BakeError(name + ": the scene has no vertices");
  if (scene.normals.size() != scene.positions.size())
    throw BakeError(name + ": " + std::to_string(scene.normals.size()) + " normals for " +
                    std::to_string(scene.positions.size()) + " vertices");
  if (scene.albedo.size() != scene.positions.size())
    throw BakeError(name + ": " + std::to_string(scene.albedo.size()) + " albedo values for " +
                    std::to_string(scene.positions.size()) + " vertices");
  if (scene.positions.size() > 0xffffffffull) throw BakeError(name + ": too many vertices");
  for (std::size_t v = 0; v < scene.positions.size(); ++v) {
    const glm::vec3 p = scene.positions[v], n = scene.normals[v], a = scene.albedo[v];
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z))
      throw BakeError(name + ": vertex " + std::to_string(v) + " has a non-finite position");
    const float len = glm::length(n);
    if (!std::isfinite(len) || std::fabs(len - 1.f) > 1e-3f)
      throw BakeError(name + ": vertex " + std::to_string(v) + " of " + primitive_of(scene, v) +
                      " has a normal that is not unit length");
    for (int c = 0; c < 3; ++c) {
      if (!(a[c] >= 0.f && a[c] < 1.f)) {
        char buf[160];
        std::snprintf(buf, sizeof buf, "albedo (%g, %g, %g) of %s is outside [0, 1)",
                      static_cast<double>(a.x), static_cast<double>(a.y), static_cast<double>(a.z),
                      primitive_of(scene, v).c_str());
        throw BakeError(name + ": " + buf + " (energy would not be conserved)");
      }
    }
  }
  for (const glm::uvec3& t : scene.triangles)
    if (t.x >= scene.positions.size() || t.y >= scene.positions.size() ||
        t.z >= scene.positions.size())
      throw BakeError(name + ": a triangle index is out of range");
}

BakeResult bake_transfer(const Scene& scene, const BakeOptions& options, ProgressSink* progress) {
  const Clock::time_point t_start = Clock::now();
  validate_bake_inputs(scene, options);
  std::optional<tbb::global_control> thread_limit;
  if (options.threads > 0)
    thread_limit.emplace(tbb::global_control::max_allowed_parallelism,
                         static_cast<std::size_t>(options.threads));

  const std::size_t V = scene.positions.size();
  const int order = options.order;
  const int K = order * order;
  const bool grey = std::all_of(scene.albedo.begin(), scene.albedo.end(), is_grey);
  const int C = grey ? 1 : 3;
  const bool need_sh_rays = options.kind != prt::TransferKind::Unshadowed;
  const bool interreflect = options.kind == prt::TransferKind::Interreflected;
  const bool need_rays = need_sh_rays || options.ao || options.bent_normals;
  const int N = round_up_to_packet(options.samples);

  BakeResult result;
  BakeStatistics& st = result.stats;
  st.vertices = V;
  st.triangles = scene.triangles.size();
  st.samples_per_vertex = need_rays ? N : 0;
  st.skipped_triangles = scene.skipped_degenerate_triangles;

  // Shadowed/unshadowed transfer goes straight into the float output (T = ρ_c·S); only the
  // interreflected kind keeps S = (1/N) Σ V Y_k in double for the solve.
  prt::TransferData& data = result.data;
  // Compact output (AdaptiveSampling::compact_output): rows for the vertices that are not
  // kSkipVertex only, in vertex order (a pilot of 256 vertices of a large scene at order 16
  // would otherwise allocate V × 256 floats).
  const bool compact = options.adaptive.enabled && options.adaptive.compact_output;
  std::vector<std::size_t> row_of;
  std::size_t rows_out = V;
  if (compact) {
    row_of.assign(V, 0);
    rows_out = 0;
    for (std::size_t v = 0; v < V; ++v)
      if (options.adaptive.vertex_mode.empty() || options.adaptive.vertex_mode[v] != kSkipVertex)
        row_of[v] = rows_out++;
  }
  data.coefficients.assign(rows_out * C * K, 0.f);
  VertexSums sums;
  if (interreflect) sums.visibility_sh.assign(V * K, 0.0);
  auto store_direct = [&](std::size_t v, const double* s_k) {
    if (interreflect) {
      std::copy(s_k, s_k + K, &sums.visibility_sh[v * K]);
      return;
    }
    const std::size_t row = compact ? row_of[v] : v;
    for (int c = 0; c < C; ++c) {
      const double rho_c = scene.albedo[v][c];
      float* t = &data.coefficients[(row * C + c) * K];
      for (int k = 0; k < K; ++k) t[k] = static_cast<float>(rho_c * s_k[k]);
    }
  };
  if (need_rays) {
    sums.ao.assign(V, 0.f);
    sums.bent.assign(3 * V, 0.f);
  }
  SparseTransferMatrix h;
  double ray_offset = 0.0;

  // Analytic unshadowed transfer of vertex v: (1/π) · rotate_zonal(clamped cosine, n), grey.
  std::vector<double> zonal(order);
  for (int l = 0; l < order; ++l) zonal[l] = sh::clamped_cosine_zonal_coefficient(l);
  auto unshadowed = [&](std::size_t v, double* out) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[v]));
    sh::rotate_zonal(order, zonal.data(), n.x, n.y, n.z, out);
    for (int k = 0; k < K; ++k) out[k] /= kPi;
  };

  if (!need_sh_rays) {
    // Analytic; albedo applied by store_direct.
    tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
      std::vector<double> out(K);
      unshadowed(v, out.data());
      store_direct(v, out.data());
    });
  }

  const bool adaptive = options.adaptive.enabled && need_rays;
  const AdaptiveSampling& ad = options.adaptive;
  // Adaptive: the caller's vertex modes, with vertices whose occluder caps all lie below the
  // horizon made analytic (they are provably open too).
  std::vector<uint8_t> modes;
  auto mode_of = [&](std::size_t v) { return modes.empty() ? kSampleVertex : modes[v]; };
  OccluderCaps caps;
  auto capped = [&](std::size_t v) {
    return !caps.covered.empty() && caps.covered[v] && caps.count(v) > 0;
  };
  if (adaptive) {
    modes = ad.vertex_mode.empty() ? std::vector<uint8_t>(V, kSampleVertex) : ad.vertex_mode;
    if (ad.cap_sampling) {
      std::vector<uint8_t> wanted(V, 0);
      for (std::size_t v = 0; v < V; ++v) wanted[v] = modes[v] == kSampleVertex;
      caps = find_occluder_caps(scene, open_hemisphere_threshold(scene), wanted, ad.max_caps,
                                ad.max_cap_solid_angle, ad.hierarchy.get());
      st.seconds_caps = caps.seconds;
      for (std::size_t v = 0; v < V; ++v) {
        if (!wanted[v] || !caps.covered[v]) continue;
        if (caps.count(v) == 0) {
          modes[v] = kAnalyticVertex;
          ++st.cap_open_vertices;
        } else {
          ++st.cap_vertices;
        }
      }
    }
  }
  bool any_sampled = !adaptive;
  if (adaptive) {
    st.vertex_samples.assign(V, 0);
    st.vertex_standard_error.assign(V, 0.f);
    for (std::size_t v = 0; v < V; ++v) {
      any_sampled = any_sampled || mode_of(v) == kSampleVertex;
      if (mode_of(v) == kAnalyticVertex) ++st.analytic_vertices;
    }
  }
  if (adaptive && !any_sampled) {
    // Nothing to cast: no BVH is built. AO = 1 and bent normal = n are exact for an open
    // hemisphere; skipped vertices keep zeros.
    std::vector<double> out(K);
    for (std::size_t v = 0; v < V; ++v) {
      const glm::vec3 n = glm::normalize(scene.normals[v]);
      for (int a = 0; a < 3; ++a) sums.bent[3 * v + a] = n[a];
      if (mode_of(v) != kAnalyticVertex) continue;
      unshadowed(v, out.data());
      store_direct(v, out.data());
      sums.ao[v] = 1.f;
    }
    if (interreflect) h.row_offsets.assign(V + 1, 0);
  }

  if (need_rays && any_sampled) {
    const Clock::time_point t_rays = Clock::now();
    const Clock::time_point t_bvh = Clock::now();
    std::unique_ptr<RayCaster> own_caster;
    if (!(adaptive && ad.caster)) own_caster = std::make_unique<RayCaster>(scene);
    const RayCaster& caster = own_caster ? *own_caster : *ad.caster;
    st.seconds_bvh = seconds_since(t_bvh);
    ray_offset = caster.offset_scale();
    const std::size_t blocks = (V + kVertexBlock - 1) / kVertexBlock;
    std::vector<BlockRows> rows(interreflect ? blocks : 0);
    std::vector<uint64_t> block_rays(blocks, 0), block_back_hits(blocks, 0);
    if (progress) progress->start("bake", V);
    const float tfar = std::numeric_limits<float>::infinity();
    const double inv_n = 1.0 / N;

    // Adaptive sampling (see transfer_baker.h): phase 1 casts min_samples rays per sampled
    // vertex, then rounds of Neyman allocation (bake/sample_allocation.h) add rays until the
    // calibrated error model meets the budget. Audit vertices (every kAuditStride-th sampled
    // vertex) draw from two independently scrambled sequences in alternate packets; the others
    // from the one sequence of the fixed recipe. Hits are gathered into H in every round.
    const int pair = 2 * kPacketSize;
    const int min_n = round_up(std::max(ad.min_samples, pair), pair);
    const int max_n = std::max(min_n, round_up(ad.max_samples, pair));
    // Capped vertices start lower: 16-sample packets, pairs of them on audit vertices.
    const int min_cap_n = std::min(min_n, round_up(std::max(ad.min_cap_samples, 1), kPacketSize));
    const int min_cap_audit_n = std::min(min_n, round_up(min_cap_n, pair));
    // w(ω): the lighting's luminance up to the transfer's order (higher bands cannot reach the
    // exit radiance Σ_k T_k L_k).
    const int light_order = std::min(ad.lighting_order, order);
    const int eval_order = order;
    const int eval_k = eval_order * eval_order;
    const double light_mean = light_order > 0 ? ad.lighting[0] * kY00 : 0.0;
    const bool weighted = light_order > 0 && light_mean > 0.0;
    const uint64_t replica_seed[2] = {options.seed, hash_seed(options.seed, kReplicaSalt)};
    const std::vector<double> uniform_sky{1.0 / kY00};
    const std::vector<double>& lum = weighted ? ad.lighting : uniform_sky;
    const int lum_k = std::min(K, weighted ? light_order * light_order : 1);
    const double lum_mean = weighted ? light_mean : 1.0;
    auto luminance = [](const glm::vec3& c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; };
    // Interreflected: a blocked sample swaps the sky's radiance for the hit surface's, so its
    // error contribution is (L_sky − L_hit), not L_sky. L_hit is approximated by the hit
    // vertices' unshadowed exit radiance ρ̄·u (in units of the mean; the audit's c calibrates
    // what the approximation misses).
    std::vector<float> hit_radiance(adaptive && interreflect ? V : 0);
    tbb::parallel_for(std::size_t(0), hit_radiance.size(), [&](std::size_t v) {
      std::vector<double> u(K);
      unshadowed(v, u.data());
      double b = 0.0;
      for (int k = 0; k < lum_k; ++k) b += u[k] * lum[k];
      hit_radiance[v] = static_cast<float>(luminance(scene.albedo[v]) * b / lum_mean);
    });
    struct VertexState {
      double sum_x[2] = {0.0, 0.0};  // per replica (audit) or all in [0]: Σ x_s
      // x_s = w_s·(1 − V(ω_s))·L(ω_s), w_s the cap weight (or 1). Σ over the pairs of points
      // (2i, 2i + 1) of a sequence of (x_2i − x_2i+1)²/2: the successive-difference estimate of
      // the per-sample variance, which sees the points' stratification (see the allocation).
      double sum_pair2 = 0.0;
      uint32_t used = 0, visible = 0, occluded = 0, cast = 0;
      bool audit = false;
      glm::dvec3 bent{0.0};          // Σ visible ω_s (hemisphere sampling)
      double occluded_weight = 0.0;  // Σ w_s (1 − V(ω_s))   (cap sampling: AO)
      glm::dvec3 occluded_dir{0.0};  // Σ w_s (1 − V(ω_s)) ω_s (cap sampling: bent normal)
    };
    std::vector<VertexState> state(adaptive ? V : 0);
    // Σ (1 − V) Y_k of each sampled vertex, at its slot (sampled vertices only: a pilot bake
    // samples a few hundred vertices of a large scene at a high order).
    std::vector<std::size_t> slot(adaptive ? V : 0);
    std::size_t slots = 0;
    for (std::size_t v = 0; v < slot.size(); ++v)
      if (mode_of(v) == kSampleVertex) slot[v] = slots++;
    const std::size_t audit_stride = slots >= kMinAuditVertices * kAuditStride ? kAuditStride : 1;
    for (std::size_t v = 0; v < slot.size(); ++v)
      if (mode_of(v) == kSampleVertex) state[v].audit = slot[v] % audit_stride == 0;
    std::vector<double> occluded_sum(slots * K);
    // Casts packets for vertex v until it has `target` samples; returns the rays cast. A capped
    // vertex draws inside its caps (bake/cap_sampling.h) and casts only the samples above its
    // horizon (the others have weight 0 but count as samples of the estimator).
    auto sample_vertex = [&](std::size_t v, const glm::vec3& n, int target,
                             const auto& gather_hit) -> uint64_t {
      VertexState& vs = state[v];
      const glm::vec3 origin = caster.vertex_origin(static_cast<uint32_t>(v));
      const bool in_caps = capped(v);
      glm::vec3 dirs[kPacketSize];
      double w[kPacketSize];
      int point[kPacketSize];  // the packet's point each cast ray came from
      bool occluded[kPacketSize];
      RayCaster::Hit hits[kPacketSize];
      std::vector<float> y(eval_k);
      double* occ = &occluded_sum[slot[v] * K];
      uint64_t cast = 0;
      while (vs.used < static_cast<uint32_t>(target)) {
        const int r = vs.audit ? static_cast<int>((vs.used / kPacketSize) % 2) : 0;
        const uint32_t index = vs.audit ? vs.used / pair * kPacketSize : vs.used;
        int count = kPacketSize;
        if (in_caps) {
          generate_cap_directions(caps.of(v), static_cast<int>(caps.count(v)), n, replica_seed[r],
                                  v, index, kPacketSize, dirs, w);
          count = 0;
          for (int i = 0; i < kPacketSize; ++i)
            if (w[i] > 0.0) dirs[count] = dirs[i], w[count] = w[i], point[count++] = i;
        } else {
          generate_cosine_directions(n, replica_seed[r], v, index, kPacketSize, dirs);
          std::fill(w, w + kPacketSize, 1.0);
          for (int i = 0; i < kPacketSize; ++i) point[i] = i;
        }
        double xs[kPacketSize] = {};  // x of each point of the packet (0: visible or no ray)
        if (count > 0)
          cast_packet(caster, origin, dirs, count, tfar, interreflect ? hits : nullptr, occluded);
        cast += static_cast<uint64_t>(count);
        vs.cast += static_cast<uint32_t>(count);
        for (int i = 0; i < count; ++i) {
          if (!occluded[i]) {
            ++vs.visible;
            vs.bent += glm::dvec3(dirs[i]);
            continue;
          }
          ++vs.occluded;
          vs.occluded_weight += w[i];
          vs.occluded_dir += w[i] * glm::dvec3(dirs[i]);
          sh::evaluate(eval_order, dirs[i].x, dirs[i].y, dirs[i].z, y.data());
          for (int k = 0; k < K; ++k) occ[k] += w[i] * static_cast<double>(y[k]);
          double sky = 1.0;
          if (weighted) {
            double radiance = 0.0;
            for (int k = 0; k < light_order * light_order; ++k)
              radiance += ad.lighting[k] * static_cast<double>(y[k]);
            sky = radiance / light_mean;
          }
          double hit = 0.0;
          if (interreflect && hits[i].hit &&
              gather_hit(hits[i], dirs[i], static_cast<float>(w[i]))) {
            const glm::uvec3 tri = scene.triangles[hits[i].triangle];
            hit = (1.0 - hits[i].u - hits[i].v) * hit_radiance[tri.x] +
                  hits[i].u * hit_radiance[tri.y] + hits[i].v * hit_radiance[tri.z];
          }
          const double x = w[i] * (sky - hit);
          vs.sum_x[r] += x;
          xs[point[i]] = x;
        }
        for (int i = 0; i < kPacketSize; i += 2)
          vs.sum_pair2 += 0.5 * (xs[i] - xs[i + 1]) * (xs[i] - xs[i + 1]);
        vs.used += kPacketSize;
      }
      return cast;
    };
    // Phase 1 of one vertex; analytic and skipped vertices are final here. Rows of H hold
    // unscaled sums until phase 2 has added its hits.
    auto sample_adaptively = [&](std::size_t v, const glm::vec3& n,
                                 std::vector<std::pair<uint32_t, float>>& gathered,
                                 const auto& gather_hit, const auto& emit_row) -> uint64_t {
      gathered.clear();
      const uint8_t mode = mode_of(v);
      if (mode != kSampleVertex) {
        if (mode == kAnalyticVertex) {
          std::vector<double> s(K);
          unshadowed(v, s.data());
          store_direct(v, s.data());
          sums.ao[v] = 1.f;
        }
        for (int a = 0; a < 3; ++a) sums.bent[3 * v + a] = n[a];
        if (interreflect) emit_row(0.0);
        return 0;
      }
      const int first_target = !capped(v) ? min_n : (state[v].audit ? min_cap_audit_n : min_cap_n);
      const uint64_t rays = sample_vertex(v, n, first_target, gather_hit);
      if (interreflect) emit_row(1.0);
      return rays;
    };

    tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
      glm::vec3 dirs[kPacketSize];
      bool occluded[kPacketSize];
      RayCaster::Hit hits[kPacketSize];
      std::vector<float> y(K), packet_sum(K);
      std::vector<double> acc(K);
      std::vector<std::pair<uint32_t, float>> gathered;
      const std::size_t v_end = std::min(V, (blk + 1) * kVertexBlock);
      uint64_t rays = 0;
      // The hit's vertices, weighted by barycentrics, go into this vertex's row of H.
      auto gather_hit = [&](const RayCaster::Hit& hit, const glm::vec3& dir, float weight) {
        const bool front = gather_front_hit(scene, hit, dir, weight, gathered);
        if (!front) ++block_back_hits[blk];
        return front;
      };
      auto emit_row = [&](double row_scale) { append_row(gathered, row_scale, rows[blk]); };
      for (std::size_t v = blk * kVertexBlock; v < v_end; ++v) {
        const glm::vec3 n = glm::normalize(scene.normals[v]);
        if (adaptive) {
          rays += sample_adaptively(v, n, gathered, gather_hit, emit_row);
          continue;
        }
        const glm::vec3 origin = caster.vertex_origin(static_cast<uint32_t>(v));
        std::fill(acc.begin(), acc.end(), 0.0);
        gathered.clear();
        uint32_t visible = 0;
        glm::dvec3 bent(0.0);
        for (int first = 0; first < N; first += kPacketSize) {
          generate_cosine_directions(n, options.seed, v, static_cast<uint32_t>(first), kPacketSize,
                                     dirs);
          cast_packet(caster, origin, dirs, kPacketSize, tfar, interreflect ? hits : nullptr,
                      occluded);
          rays += kPacketSize;
          // SH of the visible directions: summed in float over the 16 rays of a packet (at
          // most 16 terms of magnitude ≤ ~3.5), then added to the double accumulator.
          bool any = false;
          if (need_sh_rays) std::fill(packet_sum.begin(), packet_sum.end(), 0.f);
          for (int i = 0; i < kPacketSize; ++i) {
            if (occluded[i]) continue;
            ++visible;
            bent += glm::dvec3(dirs[i]);
            if (!need_sh_rays) continue;
            any = true;
            sh::evaluate(order, dirs[i].x, dirs[i].y, dirs[i].z, y.data());
            for (int k = 0; k < K; ++k) packet_sum[k] += y[k];
          }
          if (any)
            for (int k = 0; k < K; ++k) acc[k] += static_cast<double>(packet_sum[k]);
          if (interreflect)
            for (int i = 0; i < kPacketSize; ++i)
              if (hits[i].hit) gather_hit(hits[i], dirs[i], 1.f);
        }
        if (need_sh_rays)
          for (int k = 0; k < K; ++k) acc[k] *= inv_n;
        if (need_sh_rays) store_direct(v, acc.data());
        sums.ao[v] = static_cast<float>(visible * inv_n);
        const double bl = glm::length(bent);
        const glm::vec3 bn = bl > 0 ? glm::vec3(bent / bl) : n;
        sums.bent[3 * v + 0] = bn.x;
        sums.bent[3 * v + 1] = bn.y;
        sums.bent[3 * v + 2] = bn.z;
        if (interreflect) emit_row(inv_n);
      }
      block_rays[blk] = rays;
      if (progress) progress->advance(v_end - blk * kVertexBlock, rays);
    });
    if (adaptive) {
      // Allocation in units of the sky's mean radiance. Vertex v's direct exit radiance is
      // ρ̄_v·(u_v − mean x), ρ̄ the luminance albedo. Error model: e_v² = c²·ρ̄_v²σ_v²/n_v, the
      // i.i.d. variance (σ_v² the spread of x, floored at the Jeffreys p(1 − p),
      // p = (occluded + ½)/(n + 1), so a vertex whose rays all escaped still owns the error of
      // an occluder they may have missed) times c², measured on the audit vertices:
      // E[(m₀ − m₁)²/4] = Var((m₀ + m₁)/2) for replica means m_r, so
      // c² = Σ_audit ρ̄²(m₀ − m₁)²/4 / Σ_audit ρ̄²σ²/n — the scrambled points' gain over the
      // i.i.d. rate, at the current counts. Budget: (rms_error)²·Σ_v (ρ̄_v b_v)², b_v the
      // direct exit radiance over the mean (interreflection would only add to it). Each round
      // doubles the cap (min_samples·2, ·4, … max_samples) and re-measures c; holding c while
      // n grows within a round is conservative, as the points' error falls faster than n^-½.
      // A capped vertex's weights are ≤ Ω/π: its Jeffreys floor is scaled by (Ω/π)².
      std::vector<double> weight_bound2(V, 1.0);
      for (std::size_t v = 0; v < V; ++v)
        if (mode_of(v) == kSampleVertex && capped(v)) {
          const double wmax = total_solid_angle(caps.of(v), static_cast<int>(caps.count(v))) / kPi;
          weight_bound2[v] = wmax * wmax;
        }
      // Per-sample variance σ_v²: the successive-difference estimate over point pairs. The
      // pairs (2i, 2i + 1) of a scrambled Sobol' sequence share elementary intervals, so where
      // the occluded region's boundary is simple (a floor's straight horizon) the pairs agree
      // and σ_v² is small, where it is ragged (contact shadows) they differ: unlike the plain
      // sample variance, the estimate sees each vertex's own stratification gain. Under i.i.d.
      // points E[(x_a − x_b)²/2] = σ², the usual variance. Floored at the Jeffreys p(1 − p).
      auto spread2 = [&](std::size_t v) {
        const VertexState& vs = state[v];
        const double n = vs.used;
        const double var = vs.sum_pair2 / (0.5 * n);
        const double p = (vs.occluded + 0.5) / (n + 1.0);
        return std::max(var, weight_bound2[v] * p * (1.0 - p));
      };
      // Budget denominator: Σ_v B_v², B_v = ρ̄_v·b_v (direct, in units of the mean radiance)
      // plus, when interreflecting, the first bounce ρ̄_v·(1/n_v)·Σ_hits B(hit), read from the
      // phase-1 rows of H. The later bounces only add (lighting ≥ 0), so this stays a lower
      // bound of the exit radiance: the budget stays conservative.
      std::vector<double> b2_of(V, 0.0), direct_b(V, 0.0);
      tbb::parallel_for(std::size_t(0), V, [&](std::size_t v) {
        const uint8_t mode = mode_of(v);
        if (mode == kSkipVertex) return;
        std::vector<double> s(K);
        unshadowed(v, s.data());
        if (mode == kSampleVertex) {
          const double inv = 1.0 / state[v].used;
          for (int k = 0; k < K; ++k) s[k] -= occluded_sum[slot[v] * K + k] * inv;
        }
        double b = 0.0;
        for (int k = 0; k < lum_k; ++k) b += s[k] * lum[k];
        const double rho = luminance(scene.albedo[v]);
        direct_b[v] = rho * b / lum_mean;
        b2_of[v] = direct_b[v] * direct_b[v];
      });
      if (interreflect)
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
          const BlockRows& br = rows[blk];
          std::size_t offset = 0;
          for (std::size_t v = blk * kVertexBlock, i = 0; i < br.lengths.size(); ++v, ++i) {
            double gathered = 0.0;
            for (uint32_t e = 0; e < br.lengths[i]; ++e, ++offset)
              gathered += static_cast<double>(br.weights[offset]) * direct_b[br.columns[offset]];
            if (mode_of(v) != kSampleVertex) continue;
            const double b = direct_b[v] + luminance(scene.albedo[v]) * gathered / state[v].used;
            b2_of[v] = b * b;
          }
        });
      double b2 = 0.0;  // fixed order: deterministic
      for (double x : b2_of) b2 += x;
      const double budget = ad.rms_error * ad.rms_error * b2;
      // a_v = c_class·ρ̄_v·σ_v: the calibrated standard deviation, c measured separately for
      // hemisphere-sampled (class 0) and cap-sampled (class 1) vertices when a class has
      // kMinClassAudits audit vertices, else shared.
      std::vector<double> a(V, 0.0), iid_a(V, 0.0);
      std::vector<uint32_t> lo(V, 0), hi(V, 0);
      double c2 = 1.0, c2_class[2] = {1.0, 1.0}, model2 = 0.0;
      // Measures c² and the calibrated error at the current counts; fills a, lo.
      auto measure = [&] {
        double iid_audit[2] = {0.0, 0.0}, rep_audit[2] = {0.0, 0.0};
        std::size_t audits[2] = {0, 0};
        for (std::size_t v = 0; v < V; ++v) {
          if (mode_of(v) != kSampleVertex) continue;
          const VertexState& vs = state[v];
          const double rho = luminance(scene.albedo[v]);
          iid_a[v] = rho * std::sqrt(spread2(v));
          lo[v] = vs.used;
          if (!vs.audit) continue;
          const int cls = capped(v) ? 1 : 0;
          ++audits[cls];
          iid_audit[cls] += iid_a[v] * iid_a[v] / vs.used;
          const double half = 0.5 * vs.used, d = (vs.sum_x[0] - vs.sum_x[1]) / half;
          rep_audit[cls] += rho * rho * 0.25 * d * d;
        }
        const double iid_all = iid_audit[0] + iid_audit[1];
        c2 = iid_all > 0.0 ? std::max((rep_audit[0] + rep_audit[1]) / iid_all, kMinCalibration2)
                           : 1.0;
        for (int cls = 0; cls < 2; ++cls)
          c2_class[cls] = audits[cls] >= kMinClassAudits && iid_audit[cls] > 0.0
                              ? std::max(rep_audit[cls] / iid_audit[cls], kMinCalibration2)
                              : c2;
        model2 = 0.0;
        for (std::size_t v = 0; v < V; ++v) {
          if (mode_of(v) != kSampleVertex) continue;
          a[v] = std::sqrt(c2_class[capped(v) ? 1 : 0]) * iid_a[v];
          model2 += a[v] * a[v] / state[v].used;
        }
      };
      measure();
      std::vector<std::vector<BlockRows>> round_rows;  // per round, per block
      // Each round allocates toward the Neyman targets with every vertex's final cap (max_n),
      // but lets no vertex grow more than kRoundGrowth× in one round, so that c and the spreads
      // are re-measured on the way (a target computed from 64 rays is a rough one).
      for (int r = 0; model2 > budget && r < kMaxRounds; ++r) {
        for (std::size_t v = 0; v < V; ++v)
          hi[v] = mode_of(v) == kSampleVertex ? std::max<uint32_t>(max_n, state[v].used) : 0;
        // Cost of a sample: rays that hit cost more than rays that escape (closest hit, the
        // gather, H's entries); samples below a capped vertex's horizon cast nothing.
        std::vector<double> cost(V, 1.0);
        for (std::size_t v = 0; v < V; ++v) {
          const VertexState& vs = state[v];
          if (mode_of(v) != kSampleVertex || vs.used == 0) continue;
          const double cast_share = static_cast<double>(vs.cast) / vs.used;
          const double hit_share = vs.cast > 0 ? static_cast<double>(vs.occluded) / vs.cast : 0.0;
          cost[v] = std::max(0.05, cast_share * (1.0 + kHitCost * hit_share));
        }
        SampleAllocation alloc = allocate_samples(a, lo, hi, budget, kPacketSize, cost);
        bool grows = false;
        for (std::size_t v = 0; v < V; ++v) {
          if (alloc.samples[v] == 0) continue;
          alloc.samples[v] = std::min<uint32_t>(alloc.samples[v], kRoundGrowth * state[v].used);
          if (state[v].audit)
            alloc.samples[v] = std::min<uint32_t>(round_up(alloc.samples[v], pair), hi[v]);
          grows = grows || alloc.samples[v] > state[v].used;
        }
        if (!grows) break;
        // One round: the extra rays; their hits form this round's (unscaled) rows of H.
        std::vector<BlockRows>& round = round_rows.emplace_back(blocks);
        tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
          const std::size_t v_begin = blk * kVertexBlock;
          const std::size_t v_end = std::min(V, v_begin + kVertexBlock);
          uint64_t rays = 0;
          std::vector<std::pair<uint32_t, float>> gathered;
          auto gather_hit = [&](const RayCaster::Hit& hit, const glm::vec3& dir, float weight) {
            const bool front = gather_front_hit(scene, hit, dir, weight, gathered);
            if (!front) ++block_back_hits[blk];
            return front;
          };
          for (std::size_t v = v_begin; v < v_end; ++v) {
            gathered.clear();
            if (mode_of(v) == kSampleVertex) {
              const glm::vec3 n = glm::normalize(scene.normals[v]);
              rays += sample_vertex(v, n, static_cast<int>(alloc.samples[v]), gather_hit);
            }
            if (interreflect) append_row(gathered, 1.0, round[blk]);
          }
          block_rays[blk] += rays;
          if (progress) progress->advance(0, rays);  // the rate counts every round's rays
        });
        st.allocation_rounds += 1;
        measure();
      }
      st.allocation_budget_met = model2 <= budget;
      st.qmc_calibration = std::sqrt(c2_class[0]);
      st.qmc_calibration_caps = std::sqrt(c2_class[1]);
      // The final transfer, and the rows of H: every round's entries merged, scaled by 1/n_v.
      tbb::parallel_for(std::size_t(0), blocks, [&](std::size_t blk) {
        const std::size_t v_begin = blk * kVertexBlock, v_end = std::min(V, v_begin + kVertexBlock);
        std::vector<double> s(K);
        std::vector<std::pair<uint32_t, float>> gathered;
        BlockRows merged;
        std::vector<std::size_t> offsets(1 + round_rows.size(), 0);
        auto take = [&](const BlockRows& br, std::size_t row, std::size_t& offset) {
          for (uint32_t i = 0; i < br.lengths[row]; ++i, ++offset)
            gathered.emplace_back(br.columns[offset], br.weights[offset]);
        };
        for (std::size_t v = v_begin; v < v_end; ++v) {
          const bool sampled = mode_of(v) == kSampleVertex;
          const double inv = sampled ? 1.0 / state[v].used : 0.0;
          if (interreflect) {
            gathered.clear();
            take(rows[blk], v - v_begin, offsets[0]);
            for (std::size_t r = 0; r < round_rows.size(); ++r)
              take(round_rows[r][blk], v - v_begin, offsets[1 + r]);
            append_row(gathered, inv, merged);
          }
          if (!sampled) continue;
          const VertexState& vs = state[v];
          const glm::vec3 n = glm::normalize(scene.normals[v]);
          unshadowed(v, s.data());
          for (int k = 0; k < K; ++k)
            s[k] -= occluded_sum[slot[v] * K + k] * inv;  // control variate
          store_direct(v, s.data());
          // Hemisphere: the visible fraction and mean visible direction. Caps: the same with the
          // unoccluded values (1 and (2/3)·n, E[ω] under cos/π) as control variates.
          glm::dvec3 bent = vs.bent;
          if (capped(v)) {
            sums.ao[v] = static_cast<float>(std::max(0.0, 1.0 - vs.occluded_weight * inv));
            bent = (2.0 / 3.0) * glm::dvec3(n) - vs.occluded_dir * inv;
          } else {
            sums.ao[v] = static_cast<float>(vs.visible * inv);
          }
          const double bl = glm::length(bent);
          const glm::vec3 bn = bl > 0 ? glm::vec3(bent / bl) : n;
          for (int c = 0; c < 3; ++c) sums.bent[3 * v + c] = bn[c];
          st.vertex_samples[v] = vs.used;
          st.vertex_standard_error[v] =
              static_cast<float>(std::sqrt(c2_class[capped(v) ? 1 : 0] * spread2(v) * inv));
        }
        if (interreflect) rows[blk] = std::move(merged);
      });
    }
    if (progress) progress->finish();
    for (uint64_t r : block_rays) st.rays += r;
    for (uint64_t b : block_back_hits) st.back_face_hits += b;
    st.seconds_rays = seconds_since(t_rays);
    st.bvh_bytes = caster.embree_peak_bytes();

    if (interreflect) {
      h.row_offsets.assign(1, 0);
      h.row_offsets.reserve(V + 1);
      std::size_t total = 0;
      for (const BlockRows& br : rows) total += br.columns.size();
      h.columns.reserve(total);
      h.weights.reserve(total);
      for (BlockRows& br : rows) {
        for (uint32_t len : br.lengths) h.row_offsets.push_back(h.row_offsets.back() + len);
        h.columns.insert(h.columns.end(), br.columns.begin(), br.columns.end());
        h.weights.insert(h.weights.end(), br.weights.begin(), br.weights.end());
        br = BlockRows{};
      }
      st.matrix_entries = h.entries();
      st.matrix_bytes = h.bytes();
    }
  }

  // Assemble the header arrays, then the interreflection solve per channel.
  data.order = static_cast<uint32_t>(order);
  data.channels = static_cast<uint32_t>(C);
  data.storage = options.precision;
  data.albedo_folded = true;
  detail::store_scene_geometry(scene, data);

  const Clock::time_point t_solve = Clock::now();
  std::vector<double> direct(interreflect ? V * K : 0), solved(interreflect ? V * K : 0);
  std::vector<double> rho(interreflect ? V : 0);
  if (adaptive) {
    for (std::size_t v = 0; v < V && interreflect; ++v)
      if (mode_of(v) == kSampleVertex && h.row_offsets[v + 1] == h.row_offsets[v])
        ++st.empty_gather_rows;
    st.samples_per_vertex = 0;
    for (uint32_t n_v : st.vertex_samples)
      st.samples_per_vertex = std::max(st.samples_per_vertex, static_cast<int>(n_v));
  }
  for (int c = 0; c < C && interreflect; ++c) {
    for (std::size_t v = 0; v < V; ++v) rho[v] = scene.albedo[v][c];
    for (std::size_t v = 0; v < V; ++v)
      for (int k = 0; k < K; ++k) direct[v * K + k] = rho[v] * sums.visibility_sh[v * K + k];
    if (adaptive) {
      solve_adaptively(h, rho, direct, K, ad.bounce_tolerance, solved, st, progress);
      for (std::size_t v = 0; v < V; ++v)
        for (int k = 0; k < K; ++k)
          data.coefficients[(v * C + c) * K + k] = static_cast<float>(solved[v * K + k]);
      continue;
    }
    SolveOptions so;
    so.bounces = options.bounces;
    so.tolerance = options.bounce_tolerance;
    so.max_iterations = options.max_solver_iterations;
    const SolveReport rep =
        solve_interreflection(h, rho, direct.data(), K, solved.data(), so, progress);
    st.jacobi_bounces = rep.jacobi_bounces;
    st.solver_iterations += rep.krylov_iterations;
    st.solver_residual = std::max(st.solver_residual, rep.relative_residual);
    st.solver_converged = st.solver_converged && rep.converged;
    if (st.bounce_energy.size() < rep.bounce_energy.size())
      st.bounce_energy.resize(rep.bounce_energy.size(), 0.0);
    for (std::size_t i = 0; i < rep.bounce_energy.size(); ++i)
      st.bounce_energy[i] = std::max(st.bounce_energy[i], rep.bounce_energy[i]);
    for (std::size_t v = 0; v < V; ++v)
      for (int k = 0; k < K; ++k)
        data.coefficients[(v * C + c) * K + k] = static_cast<float>(solved[v * K + k]);
  }
  st.seconds_solve = interreflect ? seconds_since(t_solve) : 0.0;
  st.stored_kind = options.kind;
  if (adaptive) {
    if (st.analytic_vertices == V)
      st.stored_kind = prt::TransferKind::Unshadowed;
    else if (!interreflect || !st.interreflection_solved)
      st.stored_kind = prt::TransferKind::Shadowed;
  }
  data.kind = st.stored_kind;
  if (options.ao) data.ao = std::move(sums.ao);
  if (options.bent_normals) data.bent_normals = std::move(sums.bent);
  st.seconds_total = seconds_since(t_start);

  nlohmann::json meta;
  meta["generator"] = "prt bake";
  meta["scene"] = scene.source_path;
  meta["sh_basis"] = sh::kBasisConvention;
  meta["transfer"] = transfer_kind_name(st.stored_kind);
  meta["order"] = order;
  meta["channels"] = C;
  meta["albedo_folded"] = true;
  meta["samples_requested"] = options.samples;
  meta["samples_per_vertex"] = st.samples_per_vertex;
  meta["sampling"] = "Owen-scrambled Sobol (0,2)-sequence, cosine-weighted (concentric)";
  meta["seed"] = options.seed;
  meta["threads"] = options.threads;
  meta["precision"] = options.precision == prt::Precision::F16 ? "f16" : "f32";
  meta["ao"] = options.ao;
  meta["bent_normals"] = options.bent_normals;
  meta["vertices"] = V;
  meta["triangles"] = st.triangles;
  meta["skipped_triangles"] = st.skipped_triangles;
  meta["rays"] = st.rays;
  meta["ray_offset"] = ray_offset;
  meta["seconds"] = st.seconds_total;
  meta["seconds_rays"] = st.seconds_rays;
  if (adaptive) {
    nlohmann::json a;
    a["transfer_requested"] = transfer_kind_name(options.kind);
    a["min_samples"] = round_up(std::max(ad.min_samples, 2 * kPacketSize), 2 * kPacketSize);
    a["max_samples"] = round_up(std::max(ad.min_samples, ad.max_samples), 2 * kPacketSize);
    a["min_cap_samples"] = round_up(std::max(ad.min_cap_samples, 1), kPacketSize);
    a["audit_stride"] = kAuditStride;
    a["allocation_rounds"] = st.allocation_rounds;
    a["qmc_calibration"] = st.qmc_calibration;
    a["qmc_calibration_caps"] = st.qmc_calibration_caps;
    a["cap_sampling"] = ad.cap_sampling;
    a["cap_vertices"] = st.cap_vertices;
    a["cap_open_vertices"] = st.cap_open_vertices;
    a["rms_sampling_error_target"] = ad.rms_error;
    a["allocation_budget_met"] = st.allocation_budget_met;
    a["lighting_weighted"] = ad.lighting_order > 0;
    a["analytic_vertices"] = st.analytic_vertices;
    uint64_t sampled = 0, sum = 0;
    for (uint32_t n_v : st.vertex_samples) sampled += n_v > 0, sum += n_v;
    a["sampled_vertices"] = sampled;
    a["mean_samples_of_sampled_vertices"] =
        sampled ? static_cast<double>(sum) / static_cast<double>(sampled) : 0.0;
    if (interreflect) {
      a["empty_gather_rows"] = st.empty_gather_rows;
      a["interreflection_solved"] = st.interreflection_solved;
      a["bounce_tolerance"] = ad.bounce_tolerance;
    }
    meta["adaptive"] = a;
  }
  if (interreflect && (!adaptive || st.interreflection_solved)) {
    nlohmann::json s;
    s["bounces_requested"] = options.bounces;
    s["tolerance"] = options.bounce_tolerance;
    s["jacobi_bounces"] = st.jacobi_bounces;
    s["krylov_iterations"] = st.solver_iterations;
    s["relative_residual"] = st.solver_residual;
    s["converged"] = st.solver_converged;
    s["bounce_energy"] = st.bounce_energy;
    s["matrix_entries"] = st.matrix_entries;
    s["back_face_hits"] = st.back_face_hits;
    s["seconds"] = st.seconds_solve;
    meta["interreflection"] = s;
  }
  data.metadata_json = meta.dump();
  return result;
}

}  // namespace prt::bake
