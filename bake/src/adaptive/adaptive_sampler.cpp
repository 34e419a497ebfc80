// bake/src/adaptive/adaptive_sampler.cpp — adaptive sampling of the sampling pass (transfer_pass.h,
// AdaptiveSampling in bake/transfer_baker.h).
//
// Phase 1 casts min_samples rays per sampled vertex, then rounds of Neyman allocation
// (bake/adaptive/sample_allocation.h) add rays until the calibrated error model meets the budget.
// Audit vertices (every kAuditStride-th sampled vertex) draw from two independently scrambled
// sequences in alternate packets; the others from the one sequence of the fixed recipe. Hits are
// gathered into H in every round. A capped vertex (bake/adaptive/occluder_caps.h) draws inside its
// caps (bake/adaptive/cap_sampling.h). The error model is derived in calibrate() and budget()
// below.
#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/parallel_for.h>

#include "../transfer_pass.h"
#include "bake/adaptive/cap_sampling.h"
#include "bake/adaptive/sample_allocation.h"
#include "bake/sampling.h"
#include "sh/basis.h"
#include "sh/constants.h"

namespace prt::bake::detail {
namespace {

using sh::kPi;
using sh::kY00;
constexpr uint64_t kReplicaSalt = 0x5245504c49434131ull;  // seeds the second replica
constexpr std::size_t kMinAuditVertices = 64;     // fewer sampled vertices than 8 × 64: all audit
constexpr double kMinCalibration2 = 0.05 * 0.05;  // c is never taken below 0.05
constexpr std::size_t kMinClassAudits = 64;       // fewer in a class (hemisphere / caps): shared c
constexpr double kHitCost = 2.0;      // a ray that hits costs 1 + this × an escaping one
constexpr uint32_t kRoundGrowth = 4;  // a vertex's samples grow at most 4× per round
constexpr int kMaxRounds = 8;

int round_up(int n, int multiple) {
  return (n + multiple - 1) / multiple * multiple;
}

double luminance(const glm::vec3& c) {
  return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z;
}

// What one sampled vertex has accumulated so far.
struct VertexState {
  double sum_x[2] = {0.0, 0.0};  // per replica (audit) or all in [0]: Σ x_s
  // x_s = w_s·(1 − V(ω_s))·L(ω_s), w_s the cap weight (or 1). Σ over the pairs of points
  // (2i, 2i + 1) of a sequence of (x_2i − x_2i+1)²/2: the successive-difference estimate of the
  // per-sample variance, which sees the points' stratification (see spread2).
  double sum_pair2 = 0.0;
  uint32_t used = 0, visible = 0, occluded = 0, cast = 0;
  bool audit = false;
  glm::dvec3 bent{0.0};          // Σ visible ω_s (hemisphere sampling)
  double occluded_weight = 0.0;  // Σ w_s (1 − V(ω_s))   (cap sampling: AO)
  glm::dvec3 occluded_dir{0.0};  // Σ w_s (1 − V(ω_s)) ω_s (cap sampling: bent normal)
};

// Adds a hit's vertices to the row being gathered; counts back-face hits.
struct Gather {
  const scene::Scene& scene;
  int channels;  // SamplingPass::gather_channels
  std::vector<std::pair<uint32_t, float>>& gathered;
  uint64_t& back_hits;
  bool operator()(const scene::RayCaster::Hit& hit, const glm::vec3& dir, float weight) const {
    const bool front = gather_front_hit(scene, hit, dir, weight, channels, gathered);
    if (!front) ++back_hits;
    return front;
  }
};

class AdaptiveSampler {
 public:
  explicit AdaptiveSampler(SamplingPass& pass);
  void run();

 private:
  uint64_t sample_vertex(std::size_t v, const glm::vec3& n, int target, const Gather& gather);
  void sample_first_round();
  double spread2(std::size_t v) const;
  double budget();
  void calibrate();
  bool sample_round(double budget, std::vector<std::vector<BlockRows>>& round_rows);
  void finish(const std::vector<std::vector<BlockRows>>& round_rows);

  SamplingPass& p_;
  const AdaptiveSampling& ad_;
  const scene::Scene& scene_;
  std::size_t V_;
  int K_;
  int pair_, min_n_, max_n_, min_cap_n_, min_cap_audit_n_;
  int light_order_, eval_order_, eval_k_;
  double light_mean_;
  bool weighted_;
  uint64_t replica_seed_[2];
  std::vector<double> uniform_sky_;
  const std::vector<double>* lum_;
  int lum_k_;
  double lum_mean_;
  std::vector<float> hit_radiance_;
  std::vector<VertexState> state_;
  std::vector<std::size_t> slot_;
  std::size_t slots_ = 0;
  std::vector<double> occluded_sum_;  // Σ (1 − V) Y_k of each sampled vertex, at its slot
  std::vector<double> weight_bound2_;
  // The calibrated model: a_v = c_class·ρ̄_v·σ_v, c measured separately for hemisphere-sampled
  // (class 0) and cap-sampled (class 1) vertices when a class has kMinClassAudits audits.
  std::vector<double> a_, iid_a_;
  std::vector<uint32_t> lo_, hi_;
  double c2_ = 1.0, c2_class_[2] = {1.0, 1.0}, model2_ = 0.0;
};

AdaptiveSampler::AdaptiveSampler(SamplingPass& pass)
    : p_(pass),
      ad_(pass.options.adaptive),
      scene_(pass.scene),
      V_(pass.V),
      K_(pass.K),
      replica_seed_{pass.options.seed, hash_seed(pass.options.seed, kReplicaSalt)} {
  pair_ = 2 * kPacketSize;
  min_n_ = round_up(std::max(ad_.min_samples, pair_), pair_);
  max_n_ = std::max(min_n_, round_up(ad_.max_samples, pair_));
  // Capped vertices start lower: 16-sample packets, pairs of them on audit vertices.
  min_cap_n_ = std::min(min_n_, round_up(std::max(ad_.min_cap_samples, 1), kPacketSize));
  min_cap_audit_n_ = std::min(min_n_, round_up(min_cap_n_, pair_));
  // w(ω): the lighting's luminance up to the transfer's order (higher bands cannot reach the
  // exit radiance Σ_k T_k L_k).
  light_order_ = std::min(ad_.lighting_order, p_.order);
  eval_order_ = p_.order;
  eval_k_ = eval_order_ * eval_order_;
  light_mean_ = light_order_ > 0 ? ad_.lighting[0] * kY00 : 0.0;
  weighted_ = light_order_ > 0 && light_mean_ > 0.0;
  uniform_sky_ = {1.0 / kY00};
  lum_ = weighted_ ? &ad_.lighting : &uniform_sky_;
  lum_k_ = std::min(K_, weighted_ ? light_order_ * light_order_ : 1);
  lum_mean_ = weighted_ ? light_mean_ : 1.0;
  // Interreflected: a blocked sample swaps the sky's radiance for the hit surface's, so its
  // error contribution is (L_sky − L_hit), not L_sky. L_hit is approximated by the hit
  // vertices' unshadowed exit radiance ρ̄·u (in units of the mean; the audit's c calibrates
  // what the approximation misses).
  hit_radiance_.resize(p_.interreflect ? V_ : 0);
  tbb::parallel_for(std::size_t(0), hit_radiance_.size(), [&](std::size_t v) {
    std::vector<double> u(K_);
    p_.direct.unshadowed(v, u.data());
    double b = 0.0;
    for (int k = 0; k < lum_k_; ++k) b += u[k] * (*lum_)[k];
    hit_radiance_[v] = static_cast<float>(luminance(scene_.albedo[v]) * b / lum_mean_);
  });
  state_.resize(V_);
  // Sampled vertices only: a pilot bake samples a few hundred vertices of a large scene at a
  // high order.
  slot_.resize(V_);
  for (std::size_t v = 0; v < V_; ++v)
    if (p_.mode_of(v) == kSampleVertex) slot_[v] = slots_++;
  const std::size_t audit_stride = slots_ >= kMinAuditVertices * kAuditStride ? kAuditStride : 1;
  for (std::size_t v = 0; v < V_; ++v)
    if (p_.mode_of(v) == kSampleVertex) state_[v].audit = slot_[v] % audit_stride == 0;
  occluded_sum_.resize(slots_ * K_);
  a_.assign(V_, 0.0);
  iid_a_.assign(V_, 0.0);
  lo_.assign(V_, 0);
  hi_.assign(V_, 0);
}

// Casts packets for vertex v until it has `target` samples; returns the rays cast. A capped
// vertex draws inside its caps and casts only the samples above its horizon (the others have
// weight 0 but count as samples of the estimator).
uint64_t AdaptiveSampler::sample_vertex(std::size_t v, const glm::vec3& n, int target,
                                        const Gather& gather) {
  VertexState& vs = state_[v];
  const glm::vec3 origin = p_.caster.vertex_origin(static_cast<uint32_t>(v));
  const bool in_caps = p_.capped(v);
  const float tfar = std::numeric_limits<float>::infinity();
  glm::vec3 dirs[kPacketSize];
  double w[kPacketSize];
  int point[kPacketSize];  // the packet's point each cast ray came from
  bool occluded[kPacketSize];
  scene::RayCaster::Hit hits[kPacketSize];
  std::vector<float> y(eval_k_);
  double* occ = &occluded_sum_[slot_[v] * K_];
  uint64_t cast = 0;
  while (vs.used < static_cast<uint32_t>(target)) {
    const int r = vs.audit ? static_cast<int>((vs.used / kPacketSize) % 2) : 0;
    const uint32_t index = vs.audit ? vs.used / pair_ * kPacketSize : vs.used;
    int count = kPacketSize;
    if (in_caps) {
      generate_cap_directions(p_.caps.of(v), static_cast<int>(p_.caps.count(v)), n,
                              replica_seed_[r], v, index, kPacketSize, dirs, w);
      count = 0;
      for (int i = 0; i < kPacketSize; ++i)
        if (w[i] > 0.0) dirs[count] = dirs[i], w[count] = w[i], point[count++] = i;
    } else {
      generate_cosine_directions(n, replica_seed_[r], v, index, kPacketSize, dirs);
      std::fill(w, w + kPacketSize, 1.0);
      for (int i = 0; i < kPacketSize; ++i) point[i] = i;
    }
    double xs[kPacketSize] = {};  // x of each point of the packet (0: visible or no ray)
    if (count > 0)
      cast_packet(p_.caster, origin, dirs, count, tfar, p_.interreflect ? hits : nullptr, occluded);
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
      sh::evaluate(eval_order_, dirs[i].x, dirs[i].y, dirs[i].z, y.data());
      for (int k = 0; k < K_; ++k) occ[k] += w[i] * static_cast<double>(y[k]);
      double sky = 1.0;
      if (weighted_) {
        double radiance = 0.0;
        for (int k = 0; k < light_order_ * light_order_; ++k)
          radiance += ad_.lighting[k] * static_cast<double>(y[k]);
        sky = radiance / light_mean_;
      }
      double hit = 0.0;
      if (p_.interreflect && hits[i].hit && gather(hits[i], dirs[i], static_cast<float>(w[i]))) {
        const glm::uvec3 tri = scene_.triangles[hits[i].triangle];
        hit = (1.0 - hits[i].u - hits[i].v) * hit_radiance_[tri.x] +
              hits[i].u * hit_radiance_[tri.y] + hits[i].v * hit_radiance_[tri.z];
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
}

// Phase 1: min_samples (fewer in caps) at every sampled vertex; analytic and skipped vertices
// are final here. Rows of H hold unscaled sums until the rounds have added their hits.
void AdaptiveSampler::sample_first_round() {
  tbb::parallel_for(std::size_t(0), p_.blocks(), [&](std::size_t blk) {
    std::vector<std::pair<uint32_t, float>> gathered;
    const Gather gather{scene_, p_.gather_channels, gathered, p_.block_back_hits[blk]};
    const std::size_t v_end = std::min(V_, (blk + 1) * kVertexBlock);
    uint64_t rays = 0;
    for (std::size_t v = blk * kVertexBlock; v < v_end; ++v) {
      const glm::vec3 n = glm::normalize(scene_.normals[v]);
      gathered.clear();
      const uint8_t mode = p_.mode_of(v);
      if (mode != kSampleVertex) {
        if (mode == kAnalyticVertex) {
          std::vector<double> s(K_);
          p_.direct.unshadowed(v, s.data());
          p_.direct.store(v, s.data());
          p_.sums.ao[v] = 1.f;
        }
        for (int a = 0; a < 3; ++a) p_.sums.bent[3 * v + a] = n[a];
        if (p_.interreflect) append_row(gathered, 0.0, p_.rows[blk]);
        continue;
      }
      const int first_target =
          !p_.capped(v) ? min_n_ : (state_[v].audit ? min_cap_audit_n_ : min_cap_n_);
      rays += sample_vertex(v, n, first_target, gather);
      if (p_.interreflect) append_row(gathered, 1.0, p_.rows[blk]);
    }
    p_.block_rays[blk] = rays;
    if (p_.progress) p_.progress->advance(v_end - blk * kVertexBlock, rays);
  });
}

// Per-sample variance σ_v²: the successive-difference estimate over point pairs. The pairs
// (2i, 2i + 1) of a scrambled Sobol' sequence share elementary intervals, so where the occluded
// region's boundary is simple (a floor's straight horizon) the pairs agree and σ_v² is small,
// where it is ragged (contact shadows) they differ: unlike the plain sample variance, the
// estimate sees each vertex's own stratification gain. Under i.i.d. points
// E[(x_a − x_b)²/2] = σ², the usual variance. Floored at the Jeffreys p(1 − p),
// p = (occluded + ½)/(n + 1), so a vertex whose rays all escaped still owns the error of an
// occluder they may have missed; a capped vertex's weights are ≤ Ω/π, so its floor is scaled by
// (Ω/π)².
double AdaptiveSampler::spread2(std::size_t v) const {
  const VertexState& vs = state_[v];
  const double n = vs.used;
  const double var = vs.sum_pair2 / (0.5 * n);
  const double p = (vs.occluded + 0.5) / (n + 1.0);
  return std::max(var, weight_bound2_[v] * p * (1.0 - p));
}

// Budget: (rms_error)²·Σ_v B_v², B_v = ρ̄_v·b_v the direct exit radiance in units of the mean
// radiance plus, when interreflecting, the first bounce ρ̄_v·(1/n_v)·Σ_hits B(hit), read from
// the phase-1 rows of H. The later bounces only add (lighting ≥ 0), so this stays a lower bound
// of the exit radiance: the budget stays conservative.
double AdaptiveSampler::budget() {
  std::vector<double> b2_of(V_, 0.0), direct_s(V_, 0.0), direct_b(V_, 0.0);
  tbb::parallel_for(std::size_t(0), V_, [&](std::size_t v) {
    const uint8_t mode = p_.mode_of(v);
    if (mode == kSkipVertex) return;
    std::vector<double> s(K_);
    p_.direct.unshadowed(v, s.data());
    if (mode == kSampleVertex) {
      const double inv = 1.0 / state_[v].used;
      for (int k = 0; k < K_; ++k) s[k] -= occluded_sum_[slot_[v] * K_ + k] * inv;
    }
    double b = 0.0;
    for (int k = 0; k < lum_k_; ++k) b += s[k] * (*lum_)[k];
    const double rho = luminance(scene_.albedo[v]);
    direct_s[v] = b / lum_mean_;
    direct_b[v] = rho * b / lum_mean_;
    b2_of[v] = direct_b[v] * direct_b[v];
  });
  // Kept-apart albedo: the entries already hold the hit's albedo, channel c in columns c·V + j;
  // their luminance weights the hit's albedo-free radiance.
  const int channels = p_.gather_channels;
  const double weight_of[3] = {channels == 1 ? 1.0 : 0.2126, 0.7152, 0.0722};
  if (p_.interreflect)
    tbb::parallel_for(std::size_t(0), p_.blocks(), [&](std::size_t blk) {
      const BlockRows& br = p_.rows[blk];
      std::size_t offset = 0;
      for (std::size_t v = blk * kVertexBlock, i = 0; i < br.lengths.size(); ++v, ++i) {
        double gathered = 0.0;
        for (uint32_t e = 0; e < br.lengths[i]; ++e, ++offset) {
          const double w = static_cast<double>(br.weights[offset]);
          const uint32_t column = br.columns[offset];
          gathered += channels == 0 ? w * direct_b[column]
                                    : weight_of[column / V_] * w * direct_s[column % V_];
        }
        if (p_.mode_of(v) != kSampleVertex) continue;
        const double b = direct_b[v] + luminance(scene_.albedo[v]) * gathered / state_[v].used;
        b2_of[v] = b * b;
      }
    });
  double b2 = 0.0;  // fixed order: deterministic
  for (double x : b2_of) b2 += x;
  return ad_.rms_error * ad_.rms_error * b2;
}

// Allocation works in units of the sky's mean radiance. Vertex v's direct exit radiance is
// ρ̄_v·(u_v − mean x), ρ̄ the luminance albedo. Error model: e_v² = c²·ρ̄_v²σ_v²/n_v, the i.i.d.
// variance times c², measured on the audit vertices: E[(m₀ − m₁)²/4] = Var((m₀ + m₁)/2) for
// replica means m_r, so c² = Σ_audit ρ̄²(m₀ − m₁)²/4 / Σ_audit ρ̄²σ²/n — the scrambled points'
// gain over the i.i.d. rate, at the current counts. Fills a_, lo_ and model2_ = Σ a_v²/n_v.
void AdaptiveSampler::calibrate() {
  double iid_audit[2] = {0.0, 0.0}, rep_audit[2] = {0.0, 0.0};
  std::size_t audits[2] = {0, 0};
  for (std::size_t v = 0; v < V_; ++v) {
    if (p_.mode_of(v) != kSampleVertex) continue;
    const VertexState& vs = state_[v];
    const double rho = luminance(scene_.albedo[v]);
    iid_a_[v] = rho * std::sqrt(spread2(v));
    lo_[v] = vs.used;
    if (!vs.audit) continue;
    const int cls = p_.capped(v) ? 1 : 0;
    ++audits[cls];
    iid_audit[cls] += iid_a_[v] * iid_a_[v] / vs.used;
    const double half = 0.5 * vs.used, d = (vs.sum_x[0] - vs.sum_x[1]) / half;
    rep_audit[cls] += rho * rho * 0.25 * d * d;
  }
  const double iid_all = iid_audit[0] + iid_audit[1];
  c2_ = iid_all > 0.0 ? std::max((rep_audit[0] + rep_audit[1]) / iid_all, kMinCalibration2) : 1.0;
  for (int cls = 0; cls < 2; ++cls)
    c2_class_[cls] = audits[cls] >= kMinClassAudits && iid_audit[cls] > 0.0
                         ? std::max(rep_audit[cls] / iid_audit[cls], kMinCalibration2)
                         : c2_;
  model2_ = 0.0;
  for (std::size_t v = 0; v < V_; ++v) {
    if (p_.mode_of(v) != kSampleVertex) continue;
    a_[v] = std::sqrt(c2_class_[p_.capped(v) ? 1 : 0]) * iid_a_[v];
    model2_ += a_[v] * a_[v] / state_[v].used;
  }
}

// One round: allocates toward the Neyman targets with every vertex's final cap (max_n), but lets
// no vertex grow more than kRoundGrowth× (so that c and the spreads are re-measured on the way:
// a target computed from 64 rays is a rough one), then casts the extra rays; their hits form this
// round's (unscaled) rows of H. False when no vertex grows.
bool AdaptiveSampler::sample_round(double budget, std::vector<std::vector<BlockRows>>& round_rows) {
  for (std::size_t v = 0; v < V_; ++v)
    hi_[v] = p_.mode_of(v) == kSampleVertex ? std::max<uint32_t>(max_n_, state_[v].used) : 0;
  // Cost of a sample: rays that hit cost more than rays that escape (closest hit, the gather,
  // H's entries); samples below a capped vertex's horizon cast nothing.
  std::vector<double> cost(V_, 1.0);
  for (std::size_t v = 0; v < V_; ++v) {
    const VertexState& vs = state_[v];
    if (p_.mode_of(v) != kSampleVertex || vs.used == 0) continue;
    const double cast_share = static_cast<double>(vs.cast) / vs.used;
    const double hit_share = vs.cast > 0 ? static_cast<double>(vs.occluded) / vs.cast : 0.0;
    cost[v] = std::max(0.05, cast_share * (1.0 + kHitCost * hit_share));
  }
  SampleAllocation alloc = allocate_samples(a_, lo_, hi_, budget, kPacketSize, cost);
  bool grows = false;
  for (std::size_t v = 0; v < V_; ++v) {
    if (alloc.samples[v] == 0) continue;
    alloc.samples[v] = std::min<uint32_t>(alloc.samples[v], kRoundGrowth * state_[v].used);
    if (state_[v].audit)
      alloc.samples[v] = std::min<uint32_t>(round_up(alloc.samples[v], pair_), hi_[v]);
    grows = grows || alloc.samples[v] > state_[v].used;
  }
  if (!grows) return false;
  std::vector<BlockRows>& round = round_rows.emplace_back(p_.blocks());
  tbb::parallel_for(std::size_t(0), p_.blocks(), [&](std::size_t blk) {
    const std::size_t v_begin = blk * kVertexBlock;
    const std::size_t v_end = std::min(V_, v_begin + kVertexBlock);
    uint64_t rays = 0;
    std::vector<std::pair<uint32_t, float>> gathered;
    const Gather gather{scene_, p_.gather_channels, gathered, p_.block_back_hits[blk]};
    for (std::size_t v = v_begin; v < v_end; ++v) {
      gathered.clear();
      if (p_.mode_of(v) == kSampleVertex) {
        const glm::vec3 n = glm::normalize(scene_.normals[v]);
        rays += sample_vertex(v, n, static_cast<int>(alloc.samples[v]), gather);
      }
      if (p_.interreflect) append_row(gathered, 1.0, round[blk]);
    }
    p_.block_rays[blk] += rays;
    if (p_.progress) p_.progress->advance(0, rays);  // the rate counts every round's rays
  });
  return true;
}

// The final transfer, AO and bent normals, and the rows of H: every round's entries merged,
// scaled by 1/n_v.
void AdaptiveSampler::finish(const std::vector<std::vector<BlockRows>>& round_rows) {
  tbb::parallel_for(std::size_t(0), p_.blocks(), [&](std::size_t blk) {
    const std::size_t v_begin = blk * kVertexBlock, v_end = std::min(V_, v_begin + kVertexBlock);
    std::vector<double> s(K_);
    std::vector<std::pair<uint32_t, float>> gathered;
    BlockRows merged;
    std::vector<std::size_t> offsets(1 + round_rows.size(), 0);
    auto take = [&](const BlockRows& br, std::size_t row, std::size_t& offset) {
      for (uint32_t i = 0; i < br.lengths[row]; ++i, ++offset)
        gathered.emplace_back(br.columns[offset], br.weights[offset]);
    };
    for (std::size_t v = v_begin; v < v_end; ++v) {
      const bool sampled = p_.mode_of(v) == kSampleVertex;
      const double inv = sampled ? 1.0 / state_[v].used : 0.0;
      if (p_.interreflect) {
        gathered.clear();
        take(p_.rows[blk], v - v_begin, offsets[0]);
        for (std::size_t r = 0; r < round_rows.size(); ++r)
          take(round_rows[r][blk], v - v_begin, offsets[1 + r]);
        append_row(gathered, inv, merged);
      }
      if (!sampled) continue;
      const VertexState& vs = state_[v];
      const glm::vec3 n = glm::normalize(scene_.normals[v]);
      p_.direct.unshadowed(v, s.data());
      for (int k = 0; k < K_; ++k) s[k] -= occluded_sum_[slot_[v] * K_ + k] * inv;  // control
      p_.direct.store(v, s.data());                                                 // variate
      // Hemisphere: the visible fraction and mean visible direction. Caps: the same with the
      // unoccluded values (1 and (2/3)·n, E[ω] under cos/π) as control variates.
      glm::dvec3 bent = vs.bent;
      if (p_.capped(v)) {
        p_.sums.ao[v] = static_cast<float>(std::max(0.0, 1.0 - vs.occluded_weight * inv));
        bent = (2.0 / 3.0) * glm::dvec3(n) - vs.occluded_dir * inv;
      } else {
        p_.sums.ao[v] = static_cast<float>(vs.visible * inv);
      }
      const double bl = glm::length(bent);
      const glm::vec3 bn = bl > 0 ? glm::vec3(bent / bl) : n;
      for (int c = 0; c < 3; ++c) p_.sums.bent[3 * v + c] = bn[c];
      p_.st.vertex_samples[v] = vs.used;
      p_.st.vertex_standard_error[v] =
          static_cast<float>(std::sqrt(c2_class_[p_.capped(v) ? 1 : 0] * spread2(v) * inv));
    }
    if (p_.interreflect) p_.rows[blk] = std::move(merged);
  });
}

void AdaptiveSampler::run() {
  sample_first_round();
  weight_bound2_.assign(V_, 1.0);
  for (std::size_t v = 0; v < V_; ++v)
    if (p_.mode_of(v) == kSampleVertex && p_.capped(v)) {
      const double wmax =
          total_solid_angle(p_.caps.of(v), static_cast<int>(p_.caps.count(v))) / kPi;
      weight_bound2_[v] = wmax * wmax;
    }
  const double target = budget();
  calibrate();
  // Every round re-measures c after its rays; holding c while n grows within a round is
  // conservative, as the points' error falls faster than n^-½.
  std::vector<std::vector<BlockRows>> round_rows;  // per round, per block
  for (int r = 0; model2_ > target && r < kMaxRounds; ++r) {
    if (!sample_round(target, round_rows)) break;
    p_.st.allocation_rounds += 1;
    calibrate();
  }
  p_.st.allocation_budget_met = model2_ <= target;
  p_.st.qmc_calibration = std::sqrt(c2_class_[0]);
  p_.st.qmc_calibration_caps = std::sqrt(c2_class_[1]);
  finish(round_rows);
}

}  // namespace

void sample_adaptive(SamplingPass& pass) {
  AdaptiveSampler(pass).run();
}

}  // namespace prt::bake::detail
