// radiosity/src/links.cpp — see radiosity/links.h.
#include "radiosity/links.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#include <tbb/task_group.h>

#include "numerics/constants.h"
#include "radiosity/form_factors.h"

namespace prt::radiosity {
namespace {

constexpr float kSameNormal = 1.f - 1e-6f;
constexpr uint32_t kSpawnPatches = 20000;  // spawn a task for pairs holding more patches
// Exact links: nearby patches (centroids nearer than kExactNear × the sum of two corner distances
// each) have the sender's quadrature refined, up to 4^kExactLevels sub-triangles, until a finer
// level changes F_rs by at most kExactTolerance (exact_g). Measured on the closed box (768
// patches): worst patch 0.76% → 0.045%; on a 13k-triangle level, links 1.4–2× the time.
constexpr int kExactLevels = 2;
constexpr double kExactNear = 1.0;
constexpr double kExactTolerance = 1e-4;
// Fine visibility of point links (links.h, LinkOptions::fine): split a partly visible link while
// B_s·F̂ > ε / kPartialSplit, one whose rays all were blocked while B_s·F̂ > ε / kHiddenSplit. (A
// check of all-or-none estimates with 4× the rays was written here but never ran: its loop ended
// first. Made to run, it cost 3.9× the rays for 1.30% against dense instead of 1.41%; 12 rays a
// link everywhere reach 0.87% for 3.7×: HierarchicalOptions::fine_visibility_rays.) The coarse
// rules (the ones before) split partly visible links while B_s·F̂ > 2ε only and never split or check
// others; on the Cornell box at 9,624 patches (docs/BENCHMARKS.md) their 4 rays a link left partial
// views undetected (0.73% of the reflected power dropped by links whose 4 rays were all blocked;
// the ceiling beside the lamp lit through the lamp).
constexpr double kPartialSplit = 20;
constexpr double kHiddenSplit = 5;

uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

struct Random {
  uint64_t state;
  double uniform() { return double(mix(state++) >> 11) * 0x1.0p-53; }
  uint32_t below(uint32_t n) { return static_cast<uint32_t>(uniform() * n) % n; }
};

// Is the bounding box of `box` wholly on or behind the plane of planar node `plane`?
bool behind(const HierarchyNode& plane, const HierarchyNode& box) {
  const float tolerance = 1e-6f * (plane.radius + box.radius);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 q((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                      (c & 4) ? box.hi.z : box.lo.z);
    if (glm::dot(plane.normal, q - plane.centroid) > tolerance) return false;
  }
  return true;
}

glm::dvec3 barycentric_point(const Patch& p, double a, double b) {
  return p.corners[0] * a + p.corners[1] * b + p.corners[2] * (1.0 - a - b);
}

// point_polygon_form_factor for a triangle, without its allocations when the whole triangle is in
// front of x (the same terms in the same order; clipped triangles go to it).
double triangle_form_factor(const glm::dvec3& x, const glm::dvec3& n,
                            const std::vector<glm::dvec3>& t) {
  for (const glm::dvec3& c : t)
    if (glm::dot(n, c - x) < 0.0) return point_polygon_form_factor(x, n, t);
  double sum = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    const glm::dvec3 a = t[k] - x, b = t[(k + 1) % 3] - x;
    const glm::dvec3 c = glm::cross(a, b);
    const double length = glm::length(c);
    if (!(length > 0.0)) continue;
    sum += std::atan2(length, glm::dot(a, b)) * glm::dot(n, c) / length;
  }
  return std::clamp(std::abs(sum) / numerics::kTwoPi, 0.0, 1.0);
}

struct Local {
  std::vector<Link> links;
  uint64_t charged = 0;
  std::size_t rays = 0, exact = 0, refined = 0;
};

// What the oracle sees of a pair, before visibility.
struct PairGeometry {
  bool cull = false, both_leaves = false, must_split = false;
  bool split_receiver = false;  // a partly hidden receiver (hierarchy.h) whose light matters
  double distance = 0, denominator = 0;  // π r² + max(A_r, A_s)
  double fhat = 0;                       // F̂ (see links.h)
  double error = 0;                      // B_s · F̂ · min(1, (R_r + R_s)/r)
};

}  // namespace

struct LinkRefiner::Work {
  const LinkRefiner& self;
  const std::vector<float>& bmax;
  double epsilon;
  tbb::enumerable_thread_specific<Local> locals;

  const HierarchyNode& node(uint32_t i) const { return self.h_.nodes[i]; }
  const Patch& patch_of(const HierarchyNode& n) const {
    return self.patches_[self.h_.order[n.first]];
  }

  void emit(const Link& link) {
    Local& local = locals.local();
    if (local.links.size() == local.links.capacity()) {
      const std::size_t cap = local.links.capacity(), grown = std::max<std::size_t>(4096, 2 * cap);
      if (self.budget_)
        self.budget_->charge((grown - cap) * sizeof(Link), "the hierarchical radiosity links");
      local.charged += (grown - cap) * sizeof(Link);
      local.links.reserve(grown);
    }
    local.links.push_back(link);
  }

  // The point form factor from x (receiving as node r) to y (sending as node s).
  static double kernel(const HierarchyNode& nr, const glm::vec3& x, const HierarchyNode& ns,
                       const glm::vec3& y) {
    const glm::vec3 delta = y - x;
    const float d2 = glm::dot(delta, delta);
    if (!(d2 > 0.f)) return 0.0;
    const glm::vec3 d = delta / std::sqrt(d2);
    return double(projected_area(nr, d)) * double(projected_area(ns, -d)) /
           (double(nr.area) * numerics::kPi * double(d2));
  }

  // How much the point form factor changes over the receiver's and the sender's boxes: its
  // largest minus its smallest value at the centroids and at the eight corners of either box
  // (the other end at its centroid).
  static double kernel_spread(const HierarchyNode& nr, const HierarchyNode& ns) {
    const double centre = kernel(nr, nr.centroid, ns, ns.centroid);
    double lo = centre, hi = centre;
    for (int c = 0; c < 8; ++c) {
      const glm::vec3 pick(c & 1 ? 1.f : 0.f, c & 2 ? 1.f : 0.f, c & 4 ? 1.f : 0.f);
      const glm::vec3 xr = nr.lo + pick * (nr.hi - nr.lo), ys = ns.lo + pick * (ns.hi - ns.lo);
      const double a = kernel(nr, xr, ns, ns.centroid), b = kernel(nr, nr.centroid, ns, ys);
      lo = std::min(lo, std::min(a, b));
      hi = std::max(hi, std::max(a, b));
    }
    return hi - lo;
  }

  PairGeometry geometry(uint32_t r, uint32_t s) const {
    PairGeometry g;
    const HierarchyNode &nr = node(r), &ns = node(s);
    if (!(nr.area > 0.f) || !(ns.area > 0.f)) return g.cull = true, g;
    if (nr.planar && ns.planar &&
        (glm::dot(nr.normal, ns.normal) >= kSameNormal || behind(nr, ns) || behind(ns, nr)))
      return g.cull = true, g;
    if (nr.planar && !ns.planar && behind(nr, ns)) return g.cull = true, g;
    if (ns.planar && !nr.planar && behind(ns, nr)) return g.cull = true, g;
    g.both_leaves = nr.leaf() && ns.leaf();
    if (g.both_leaves) return g;
    const glm::vec3 delta = ns.centroid - nr.centroid;
    g.distance = glm::length(glm::dvec3(delta));
    const double reach = double(nr.radius) + double(ns.radius);
    if (!(g.distance > reach)) return g.must_split = true, g;
    const glm::vec3 d = glm::vec3(glm::dvec3(delta) / g.distance);
    const double pr = projected_area(nr, d), ps = projected_area(ns, -d);
    g.denominator = numerics::kPi * g.distance * g.distance;
    g.fhat = pr * ps / (g.denominator * nr.area);
    if (g.fhat <= 0.0) {
      // Facing away at the centroids, yet parts may face each other: refine unless even the
      // bound F ≤ A_s / (π (r − R_r − R_s)²) makes the light negligible.
      const double gap = g.distance - reach;
      const double bound = std::min(1.0, double(ns.area) / (numerics::kPi * gap * gap));
      if (double(bmax[s]) * bound * (reach / g.distance) > epsilon) return g.must_split = true, g;
      return g.cull = true, g;
    }
    g.error = double(bmax[s]) * kernel_spread(nr, ns);
    g.split_receiver = self.options_.fine && nr.partly_hidden && !nr.leaf() &&
                       double(bmax[s]) * g.fhat > epsilon / kPartialSplit;
    return g;
  }

  // Calls visit(q) for the quadrature points of s's midpoint subdivision into 4^level
  // sub-triangles, the degree-2 three-point rule on each; q holds barycentric weights of the first
  // two corners. Level 0 is the dense analytic entry's rule.
  template <class Visit>
  static void for_each_point(int level, Visit&& visit) {
    static constexpr double kW[3][3] = {
        {2.0 / 3, 1.0 / 6, 1.0 / 6}, {1.0 / 6, 2.0 / 3, 1.0 / 6}, {1.0 / 6, 1.0 / 6, 2.0 / 3}};
    const int n = 1 << level;
    const auto rule = [&](const glm::dvec2& a, const glm::dvec2& b, const glm::dvec2& c) {
      for (int k = 0; k < 3; ++k) visit(a * kW[k][0] + b * kW[k][1] + c * kW[k][2]);
    };
    for (int i = 0; i < n; ++i)
      for (int j = 0; i + j < n; ++j) {
        const glm::dvec2 a(double(n - i - j) / n, double(i) / n),
            b(double(n - i - j - 1) / n, double(i + 1) / n),
            c(double(n - i - j - 1) / n, double(i) / n);
        rule(a, b, c);
        if (i + j + 1 < n) rule(b, glm::dvec2(double(n - i - j - 2) / n, double(i + 1) / n), c);
      }
  }

  // The mean over the points of `level` of Lambert's formula from s to r, unoccluded.
  static double unoccluded(const Patch& r, const Patch& s, const std::vector<glm::dvec3>& polygon,
                           int level) {
    double sum = 0.0;
    int points = 0;
    for_each_point(level, [&](const glm::dvec2& q) {
      ++points;
      const glm::dvec3 x = barycentric_point(s, q.x, q.y);
      if (glm::dot(r.normal, x - r.centroid) > 0.0)
        sum += triangle_form_factor(x, s.normal, polygon);
    });
    return sum / points;
  }

  // The mean over the points of `level` of Lambert's formula from s to r with one visibility ray
  // from each point to the point with the same barycentric weights on r; *open gets it unoccluded.
  double occluded_mean(const Patch& r, uint32_t r_index, const Patch& s, uint32_t s_index,
                       const std::vector<glm::dvec3>& polygon, int level, double* open,
                       Local& local) const {
    double sum = 0.0, unblocked = 0.0;
    int points = 0;
    for_each_point(level, [&](const glm::dvec2& q) {
      ++points;
      const glm::dvec3 x = barycentric_point(s, q.x, q.y);
      if (glm::dot(r.normal, x - r.centroid) <= 0.0) return;
      const double f = triangle_form_factor(x, s.normal, polygon);
      if (f <= 0.0) return;
      unblocked += f;
      const glm::dvec3 y = barycentric_point(r, q.x, q.y);
      const glm::vec3 o = self.caster_.surface_origin(s_index, glm::vec3(x), glm::vec3(s.normal));
      const glm::vec3 t = self.caster_.surface_origin(r_index, glm::vec3(y), glm::vec3(r.normal));
      const glm::vec3 d = t - o;
      const float length = glm::length(d);
      ++local.rays;
      if (!(length > 0.f) || !self.caster_.occluded(o, d / length, 0.f, length)) sum += f;
    });
    *open = unblocked / points;
    return sum / points;
  }

  // A_s·F_sr of two patches (links.h, exact): Lambert's formula (exact over r) at the three
  // points of s with a visibility ray each — the dense analytic entry. Where the kernel varies
  // over s (nearby patches) that rule errs: the unoccluded value is refined on sub-triangles
  // (for_each_point) to the coarsest level that the next changes by at most kExactTolerance in
  // F_rs (at most kExactLevels), and scaled by the three points' visible fraction (weighted by
  // the kernel), so that no rays are added.
  float exact_g(const Patch& r, uint32_t r_index, const Patch& s, uint32_t s_index,
                Local& local) const {
    std::vector<glm::dvec3> polygon(r.corners.begin(), r.corners.end());
    double open = 0.0;
    const double seen = occluded_mean(r, r_index, s, s_index, polygon, 0, &open, local);
    double f = open;
    const double reach =
        kExactNear *
        (glm::length(r.corners[0] - r.centroid) + glm::length(s.corners[0] - s.centroid) +
         glm::length(r.corners[1] - r.centroid) + glm::length(s.corners[1] - s.centroid));
    const bool near = glm::length(s.centroid - r.centroid) < reach;
    for (int level = 0; near && level < kExactLevels; ++level) {
      const double finer = unoccluded(r, s, polygon, level + 1);
      const bool converged = std::abs(finer - f) * s.area <= kExactTolerance * r.area;
      f = finer;
      if (converged) break;
    }
    if (f == open) return static_cast<float>(s.area * seen);
    if (open > 0.0) return static_cast<float>(s.area * f * (seen / open));
    // No point of the three-point rule faces r: visibility from the level-1 points.
    const double seen1 = occluded_mean(r, r_index, s, s_index, polygon, 1, &open, local);
    return open > 0.0 ? static_cast<float>(s.area * f * (seen1 / open)) : 0.f;
  }

  // A patch of the sending node, drawn in proportion to its largest radiance channel (by
  // rejection against the node's bound, at most 16 tries; uniformly when the node is dark), so
  // that visibility is sampled where the light leaves: a lamp clustered with the ceiling behind it
  // is not judged by the ceiling's rays.
  uint32_t source_sample(const HierarchyNode& ns, Random& random) const {
    uint32_t patch = self.h_.order[ns.first + random.below(ns.count)];
    const float bound = bmax[&ns - self.h_.nodes.data()];
    if (!(bound > 0.f) || ns.count == 1) return patch;
    for (int k = 0; k < 16; ++k) {
      if (random.uniform() * bound <= bmax[self.h_.leaf_of[patch]]) return patch;
      patch = self.h_.order[ns.first + random.below(ns.count)];
    }
    return patch;
  }

  // A patch of the receiving node, drawn in proportion to its visible fraction (by rejection, at
  // most 16 tries).
  uint32_t receiver_sample(const HierarchyNode& nr, Random& random) const {
    uint32_t patch = self.h_.order[nr.first + random.below(nr.count)];
    for (int k = 0; k < 16 && nr.count > 1; ++k) {
      if (random.uniform() <= self.patches_[patch].visible) return patch;
      patch = self.h_.order[nr.first + random.below(nr.count)];
    }
    return patch;
  }

  // The fraction of facing sample pairs of r and s that see each other; −1 if no sample pair
  // faces.
  double visibility(uint32_t r, uint32_t s, Local& local) {
    const HierarchyNode &nr = node(r), &ns = node(s);
    Random random{mix(self.options_.seed ^ mix((uint64_t(r) << 32) | s))};
    const int wanted = std::max(1, self.options_.visibility_rays);
    int facing = 0, visible = 0;
    for (int tries = 0; tries < 8 * wanted && facing < wanted; ++tries) {
      const uint32_t a = receiver_sample(nr, random);
      const uint32_t b = source_sample(ns, random);
      const Patch &pa = self.patches_[a], &pb = self.patches_[b];
      double u = random.uniform(), v = random.uniform();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const glm::dvec3 x = barycentric_point(pa, u, v);
      u = random.uniform(), v = random.uniform();
      if (u + v > 1.0) u = 1.0 - u, v = 1.0 - v;
      const glm::dvec3 y = barycentric_point(pb, u, v);
      if (glm::dot(pa.normal, y - x) <= 0.0 || glm::dot(pb.normal, x - y) <= 0.0) continue;
      ++facing;
      const glm::vec3 o = self.caster_.surface_origin(a, glm::vec3(x), glm::vec3(pa.normal));
      const glm::vec3 t = self.caster_.surface_origin(b, glm::vec3(y), glm::vec3(pb.normal));
      const glm::vec3 d = t - o;
      const float length = glm::length(d);
      ++local.rays;
      if (!(length > 0.f) || !self.caster_.occluded(o, d / length, 0.f, length)) ++visible;
    }
    return facing == 0 ? -1.0 : double(visible) / facing;
  }

  void split(uint32_t r, uint32_t s, bool receiver = false) {
    const HierarchyNode &nr = node(r), &ns = node(s);
    const bool split_source = !receiver && (nr.leaf() || (!ns.leaf() && ns.radius > nr.radius));
    const auto run = [&](uint32_t a0, uint32_t b0, uint32_t a1, uint32_t b1) {
      if (nr.count + ns.count > kSpawnPatches) {
        tbb::task_group group;
        group.run([&] { pair(a0, b0); });
        pair(a1, b1);
        group.wait();
      } else {
        pair(a0, b0);
        pair(a1, b1);
      }
    };
    if (split_source)
      run(r, ns.left, r, ns.right);
    else
      run(nr.left, s, nr.right, s);
  }

  // Refines the link r ← s from scratch.
  void pair(uint32_t r, uint32_t s) {
    const PairGeometry g = geometry(r, s);
    if (g.cull) return;
    if (g.both_leaves) {
      const HierarchyNode &nr = node(r), &ns = node(s);
      Local& local = locals.local();
      const float value = exact_g(patch_of(nr), self.h_.order[nr.first], patch_of(ns),
                                  self.h_.order[ns.first], local);
      if (value > 0.f) {
        ++local.exact;
        emit({r, s | Link::kExact, value});
      }
      return;
    }
    if (g.must_split || g.error > epsilon) return split(r, s);
    if (g.split_receiver) return split(r, s, true);
    const double transfer = double(bmax[s]) * g.fhat;  // B_s·F̂, without visibility
    const bool fine = self.options_.fine;
    const double partial_split = fine ? kPartialSplit : 0.5;  // coarse: B_s·F̂ > 2ε
    const double v = visibility(r, s, locals.local());
    if (v < 0.0 && transfer > epsilon) return split(r, s);  // facing parts rare
    if (v < 0.0) return;
    if (v == 0.0 && fine && transfer > epsilon / kHiddenSplit) return split(r, s);
    if (v == 0.0) return;
    if (v < 1.0 && transfer > epsilon / partial_split) return split(r, s);
    emit({r, s, static_cast<float>(v / g.denominator)});
  }

  // Refines the root's (or any node's) interaction with itself.
  void self_pair(uint32_t n) {
    const HierarchyNode& nn = node(n);
    if (nn.leaf() || nn.planar) return;  // a plane does not see itself
    if (nn.count > kSpawnPatches) {
      tbb::task_group group;
      group.run([&] { self_pair(nn.left); });
      group.run([&] { self_pair(nn.right); });
      group.run([&] { pair(nn.left, nn.right); });
      pair(nn.right, nn.left);
      group.wait();
    } else {
      self_pair(nn.left);
      self_pair(nn.right);
      pair(nn.left, nn.right);
      pair(nn.right, nn.left);
    }
  }

  // An existing link against the new bound: kept or refined.
  void recheck(const Link& link) {
    if (link.exact()) return emit(link);
    const uint32_t r = link.receiver, s = link.source_node();
    const PairGeometry g = geometry(r, s);
    const double v = double(link.g) * g.denominator;
    const bool fine = self.options_.fine;
    const bool matters = double(bmax[s]) * g.fhat > epsilon / (fine ? kPartialSplit : 0.5);
    bool partial = v < 0.999 && matters;
    if (fine && !g.cull && !g.must_split && g.error <= epsilon && !partial && matters)
      partial = visibility(r, s, locals.local()) < 1.0;  // all visible: re-sampled
    if (!g.cull && !g.must_split && g.error <= epsilon && !partial && !g.split_receiver)
      return emit(link);
    ++locals.local().refined;
    split(r, s, g.split_receiver && !g.must_split && g.error <= epsilon);
  }

  std::vector<Link> collect(LinkStats* stats) {
    std::size_t total = 0;
    uint64_t charged = 0;
    *stats = LinkStats{};
    for (const Local& local : locals) {
      total += local.links.size();
      charged += local.charged;
      stats->rays += local.rays;
      stats->exact_links += local.exact;
      stats->refined += local.refined;
    }
    if (self.budget_)
      self.budget_->charge(total * sizeof(Link), "the hierarchical radiosity links");
    std::vector<Link> links;
    links.reserve(total);
    for (Local& local : locals) {
      links.insert(links.end(), local.links.begin(), local.links.end());
      std::vector<Link>().swap(local.links);
    }
    if (self.budget_) self.budget_->release(charged);
    tbb::parallel_sort(links.begin(), links.end(), [](const Link& a, const Link& b) {
      return a.receiver != b.receiver ? a.receiver < b.receiver : a.source < b.source;
    });
    stats->links = links.size();
    stats->exact_links = 0;
    for (const Link& l : links) stats->exact_links += l.exact();
    return links;
  }
};

LinkRefiner::LinkRefiner(const std::vector<Patch>& patches, const Hierarchy& hierarchy,
                         const scene::RayCaster& caster, const LinkOptions& options,
                         MemoryBudget* budget)
    : patches_(patches), h_(hierarchy), caster_(caster), options_(options), budget_(budget) {}

std::vector<Link> LinkRefiner::initial(const std::vector<float>& bmax, double epsilon,
                                       LinkStats* stats) const {
  Work work{*this, bmax, epsilon, {}};
  work.self_pair(0);
  return work.collect(stats);
}

std::vector<Link> LinkRefiner::refine(const std::vector<Link>& links,
                                      const std::vector<float>& bmax, double epsilon,
                                      LinkStats* stats) const {
  Work work{*this, bmax, epsilon, {}};
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, links.size(), 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t k = range.begin(); k != range.end(); ++k)
                        work.recheck(links[k]);
                    });
  return work.collect(stats);
}

}  // namespace prt::radiosity
