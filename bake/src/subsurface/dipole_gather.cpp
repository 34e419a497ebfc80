// The subsurface sum, direct and hierarchical (bake/subsurface/dipole_gather.h).
#include "bake/subsurface/dipole_gather.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <numeric>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <glm/geometric.hpp>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"

namespace prt::bake {
namespace {

constexpr int kLeafSamples = 8;
// A source closer than kNearFactor × its own disc radius is integrated over that disc.
constexpr double kNearFactor = 8.0;
constexpr int kDiscNodes = 12;
constexpr int kMaxDepth = 40;

struct Node {
  glm::dvec3 lo{0.0}, hi{0.0}, centroid{0.0};
  double area = 0;
  uint32_t first = 0, count = 0;  // samples order[first, first + count)
  std::array<int32_t, 8> child{{-1, -1, -1, -1, -1, -1, -1, -1}};
  bool leaf = true;
};

// One material's octree: nodes, their Σ A_i S_i (nodes × K) and the sample order.
struct Octree {
  std::vector<Node> nodes;
  std::vector<double> sum_as;
  std::vector<uint32_t> order;
};

class OctreeBuilder {
 public:
  OctreeBuilder(const SubsurfaceSamples& s, Octree& t) : s_(s), t_(t) {}

  int build(uint32_t first, uint32_t count, int depth) {
    const int index = static_cast<int>(t_.nodes.size());
    t_.nodes.emplace_back();
    Node node;
    node.first = first;
    node.count = count;
    node.lo = node.hi = s_.positions[t_.order[first]];
    for (uint32_t j = first; j < first + count; ++j) {
      node.lo = glm::min(node.lo, s_.positions[t_.order[j]]);
      node.hi = glm::max(node.hi, s_.positions[t_.order[j]]);
    }
    const glm::dvec3 mid = 0.5 * (node.lo + node.hi);
    if (count > kLeafSamples && depth < kMaxDepth && node.hi != node.lo) {
      // Stable bucketing into octants keeps the order, and so the sums, deterministic.
      std::array<std::vector<uint32_t>, 8> bucket;
      for (uint32_t j = first; j < first + count; ++j) {
        const glm::dvec3& p = s_.positions[t_.order[j]];
        const int oct = (p.x > mid.x ? 1 : 0) | (p.y > mid.y ? 2 : 0) | (p.z > mid.z ? 4 : 0);
        bucket[oct].push_back(t_.order[j]);
      }
      uint32_t at = first;
      std::array<std::pair<uint32_t, uint32_t>, 8> ranges{};
      for (int o = 0; o < 8; ++o) {
        ranges[o] = {at, static_cast<uint32_t>(bucket[o].size())};
        std::copy(bucket[o].begin(), bucket[o].end(), t_.order.begin() + at);
        at += static_cast<uint32_t>(bucket[o].size());
      }
      node.leaf = false;
      for (int o = 0; o < 8; ++o)
        if (ranges[o].second > 0)
          node.child[o] = build(ranges[o].first, ranges[o].second, depth + 1);
    }
    t_.nodes[index] = node;
    return index;
  }

  // Areas, centroids and Σ A S, bottom-up from the samples (children have larger indices).
  void aggregate(int K) {
    t_.sum_as.assign(t_.nodes.size() * static_cast<std::size_t>(K), 0.0);
    for (std::size_t n = t_.nodes.size(); n-- > 0;) {
      Node& node = t_.nodes[n];
      double* sum = &t_.sum_as[n * K];
      glm::dvec3 weighted(0.0);
      double area = 0;
      for (uint32_t j = node.first; j < node.first + node.count; ++j) {
        const uint32_t i = t_.order[j];
        area += s_.areas[i];
        weighted += s_.areas[i] * s_.positions[i];
        const double* si = &s_.transfer[static_cast<std::size_t>(i) * K];
        for (int k = 0; k < K; ++k) sum[k] += s_.areas[i] * si[k];
      }
      node.area = area;
      node.centroid = area > 0 ? weighted / area : 0.5 * (node.lo + node.hi);
    }
  }

 private:
  const SubsurfaceSamples& s_;
  Octree& t_;
};

// Per receiver: the weighted sums for three channels.
struct Accumulator {
  std::vector<double> x;  // 3 × K
  std::array<double, 3> w{};
  int K;
  explicit Accumulator(int k) : x(3 * static_cast<std::size_t>(k), 0.0), K(k) {}
  // x += wc·s and w += wc·w_scale (w_scale: the node's area when wc is R_d alone).
  void add(const std::array<double, 3>& wc, const double* s, double w_scale = 1.0) {
    for (int c = 0; c < 3; ++c) {
      w[c] += wc[c] * w_scale;
      double* xc = &x[static_cast<std::size_t>(c) * K];
      for (int k = 0; k < K; ++k) xc[k] += wc[c] * s[k];
    }
  }
};

class Gatherer {
 public:
  Gatherer(const SubsurfaceSamples& s, const std::vector<subsurface::DipoleMaterial>& m,
           const SubsurfaceGatherOptions& o)
      : s_(s), materials_(m), options_(o), trees_(m.size()), members_(m.size()) {
    const std::size_t n = s.positions.size();
    for (std::size_t i = 0; i < n; ++i)
      if (s.material[i] >= 0)
        members_[static_cast<std::size_t>(s.material[i])].push_back(static_cast<uint32_t>(i));
    numerics::append_gauss_legendre(kDiscNodes, -numerics::kHalfPi, numerics::kHalfPi, &disc_t_,
                                    &disc_w_);
    self_.assign(3 * n, 0.0);
    for (std::size_t i = 0; i < n; ++i) {
      if (s.material[i] < 0) continue;
      const subsurface::DipoleMaterial& mat = materials_[static_cast<std::size_t>(s.material[i])];
      const double radius = std::sqrt(s.areas[i] * numerics::kInvPi);
      for (int c = 0; c < 3; ++c) {
        const subsurface::DipoleProfile& p = mat.channels[c];
        self_[3 * i + c] = p.total() - p.tail(radius);
      }
    }
    if (!o.reference)
      for (std::size_t m_i = 0; m_i < m.size(); ++m_i) {
        if (members_[m_i].empty()) continue;
        Octree& t = trees_[m_i];
        t.order = members_[m_i];
        OctreeBuilder b(s, t);
        b.build(0, static_cast<uint32_t>(t.order.size()), 0);
        b.aggregate(s.K);
        nodes_ += t.nodes.size();
      }
  }

  uint64_t nodes() const { return nodes_; }

  // A_i × the mean of R_d over a disc of area A_i centred at distance r from the receiver, in
  // the receiver's plane: ∫ R_d(s) L(s) ds over s ∈ [r − ρ, r + ρ], L(s) = 2s·acos((s² + r² −
  // ρ²)/(2sr)) the arc of the circle of radius s inside the disc, with s = r + ρ sin t so that the
  // square-root ends of L become smooth (docs/SUBSURFACE.md).
  std::array<double, 3> disc_weights(const subsurface::DipoleMaterial& mat, double area,
                                     double r) const {
    const double rho = std::sqrt(area * numerics::kInvPi);
    std::array<double, 3> w{};
    for (std::size_t q = 0; q < disc_t_.size(); ++q) {
      const double t = disc_t_[q];
      const double s = r + rho * std::sin(t);
      if (s <= 0) continue;
      const double c = std::clamp((s * s + r * r - rho * rho) / (2 * s * r), -1.0, 1.0);
      const double arc = (s < rho - r) ? numerics::kTwoPi * s : 2 * s * std::acos(c);
      const double jac = disc_w_[q] * rho * std::cos(t) * arc;
      for (int ch = 0; ch < 3; ++ch) w[ch] += jac * mat.channels[ch].profile(s);
    }
    return w;
  }

  std::array<double, 3> weights(const subsurface::DipoleMaterial& mat, double area,
                                double r) const {
    return {area * mat.channels[0].profile(r), area * mat.channels[1].profile(r),
            area * mat.channels[2].profile(r)};
  }

  void add_sample(std::size_t o, uint32_t i, const subsurface::DipoleMaterial& mat,
                  Accumulator& acc) const {
    const double* si = &s_.transfer[static_cast<std::size_t>(i) * s_.K];
    if (i == o) {
      acc.add({self_[3 * o], self_[3 * o + 1], self_[3 * o + 2]}, si);
      return;
    }
    const double r = glm::distance(s_.positions[o], s_.positions[i]);
    const double area = s_.areas[i];
    if (r * r < kNearFactor * kNearFactor * area * numerics::kInvPi)
      acc.add(disc_weights(mat, area, r), si);
    else
      acc.add(weights(mat, area, r), si);
  }

  // The receiver's sums; counts the evaluations into `nodes_used` and `samples_used`.
  Accumulator receive(std::size_t o, uint64_t& nodes_used, uint64_t& samples_used) const {
    Accumulator acc(s_.K);
    const std::size_t m = static_cast<std::size_t>(s_.material[o]);
    const subsurface::DipoleMaterial& mat = materials_[m];
    if (options_.reference) {
      for (uint32_t i : members_[m]) add_sample(o, i, mat, acc);
      samples_used += members_[m].size();
      return acc;
    }
    const Octree& t = trees_[m];
    const glm::dvec3 x = s_.positions[o];
    int stack[8 * kMaxDepth + 8];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = t.nodes[static_cast<std::size_t>(stack[--top])];
      const bool inside =
          glm::all(glm::lessThanEqual(node.lo, x)) && glm::all(glm::lessThanEqual(x, node.hi));
      const glm::dvec3 d = x - node.centroid;
      const double d2 = glm::dot(d, d);
      if (!inside && node.area < options_.epsilon * d2) {
        const std::size_t n = static_cast<std::size_t>(&node - t.nodes.data());
        acc.add(weights(mat, 1.0, std::sqrt(d2)), &t.sum_as[n * s_.K], node.area);
        ++nodes_used;
      } else if (node.leaf) {
        for (uint32_t j = node.first; j < node.first + node.count; ++j)
          add_sample(o, t.order[j], mat, acc);
        samples_used += node.count;
      } else {
        for (int c = 7; c >= 0; --c)
          if (node.child[c] >= 0) stack[top++] = node.child[c];
      }
    }
    return acc;
  }

 private:
  const SubsurfaceSamples& s_;
  const std::vector<subsurface::DipoleMaterial>& materials_;
  const SubsurfaceGatherOptions& options_;
  std::vector<Octree> trees_;
  std::vector<std::vector<uint32_t>> members_;
  std::vector<double> self_;
  std::vector<double> disc_t_, disc_w_;  // Gauss–Legendre on [−π/2, π/2]
  uint64_t nodes_ = 0;
};

}  // namespace

std::vector<double> gather_subsurface(const SubsurfaceSamples& samples,
                                      const std::vector<subsurface::DipoleMaterial>& materials,
                                      const SubsurfaceGatherOptions& options,
                                      SubsurfaceGatherStats* stats) {
  const std::size_t n = samples.positions.size();
  const int K = samples.K;
  std::vector<double> out(n * 3 * static_cast<std::size_t>(K), 0.0);
  const Gatherer g(samples, materials, options);
  std::atomic<uint64_t> nodes_used{0}, samples_used{0}, clamped{0};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 64),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      uint64_t nu = 0, su = 0, cl = 0;
                      for (std::size_t o = range.begin(); o != range.end(); ++o) {
                        if (samples.material[o] < 0) continue;
                        Accumulator acc = g.receive(o, nu, su);
                        const subsurface::DipoleMaterial& mat =
                            materials[static_cast<std::size_t>(samples.material[o])];
                        bool was_clamped = false;
                        for (int c = 0; c < 3; ++c) {
                          double scale = 1.0;
                          const double total = mat.channels[c].total();
                          if (options.energy_clamp && acc.w[c] > total) {
                            scale = total / acc.w[c];
                            was_clamped = true;
                          }
                          double* dst = &out[(o * 3 + c) * K];
                          for (int k = 0; k < K; ++k) dst[k] = scale * acc.x[c * K + k];
                        }
                        cl += was_clamped ? 1 : 0;
                      }
                      nodes_used += nu;
                      samples_used += su;
                      clamped += cl;
                    });
  if (stats) {
    stats->nodes = g.nodes();
    stats->node_evaluations = nodes_used;
    stats->sample_evaluations = samples_used;
    stats->clamped_receivers = clamped;
  }
  return out;
}

std::vector<double> subsurface_response(const SubsurfaceSamples& samples,
                                        const std::vector<subsurface::DipoleMaterial>& materials,
                                        const SubsurfaceGatherOptions& options) {
  SubsurfaceSamples ones = samples;
  ones.K = 1;
  ones.transfer.assign(samples.positions.size(), 1.0);
  SubsurfaceGatherOptions o = options;
  o.energy_clamp = false;
  return gather_subsurface(ones, materials, o);
}

}  // namespace prt::bake
