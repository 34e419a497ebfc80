// radiosity/links.h — the links of hierarchical radiosity: which node of the element hierarchy
// (radiosity/hierarchy.h) gathers light from which, found by refinement (Hanrahan, Salzman &
// Aupperle 1991; with clusters, Smits, Arvo & Greenberg 1994 and Sillion 1995).
//
// A link r ← s carries the power from node s to node r. Two kinds:
//   exact (both ends are patches): g = A_s·F_sr, F_sr by Lambert's point-to-polygon formula at the
//     three quadrature points of s with one visibility ray each (the dense analytic method's
//     entry, radiosity/form_factors.h); for nearby patches the unoccluded value is integrated on
//     sub-triangles of s until it changes by at most 1e-4 (a closed scene's F_rs then sum to 1
//     per receiver within 1e-3) and scaled by the three points' visible fraction; power = g·L_s.
//   point (at least one end a cluster or surface node): g = V / (π r² + max(A_r, A_s)), r the
//     distance between the centroids, V the fraction of `visibility_rays` segments between
//     random points of random patches of r and s (pairs that face each other; the patches of s
//     drawn in proportion to their radiance, so that a lamp clustered with a dark ceiling is
//     judged by its own rays) that nothing blocks; power = g·P_r(d)·S_s(−d), d the unit direction
//     from r to s, P_r the projected area of r (radiosity/hierarchy.h) and S_s the
//     radiance-weighted projected area of s. The max(A) term is the point-to-disc regularisation
//     (Wallace, Elmquist & Haines 1989).
// Oracle ("BF refinement" with an error factor): the estimated error of a point link in the
// receiver's irradiance is  B_s · F̂ · min(1, (R_r + R_s) / r),  F̂ = P_r P_s / ((π r² + max A)
// A_r) without visibility, B_s the largest radiance (channel) of any patch in s, R the nodes'
// radii; a link whose error exceeds ε, whose nodes are closer than R_r + R_s, or whose
// visibility is partial (0 < V < 1) while B_s·F̂/2 > ε, is refined by splitting the larger node
// (by radius; a patch is never split). With LinkOptions::fine the visibility rules are stricter
// (there), since a receiver's patches take its links' visibility as their own: 4 rays that all
// pass, or all are blocked, leave a partly visible pair undetected (0.58% of the Cornell box's
// reflected light dropped by links whose 4 rays were blocked; the ceiling beside its lamp lit
// through the lamp). Pairs that cannot exchange light are dropped: two planar
// nodes with the same normal, or one whose bounding box lies wholly behind the other's plane.
// The links of a node and its descendants partition the light it receives: refinement replaces a
// link by links to the children of one end. Links are sorted by (receiver, source) and do not
// depend on the thread count. Memory: 12 bytes a link, charged to the budget before it grows.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/memory_budget.h"
#include "radiosity/hierarchy.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

struct Link {
  static constexpr uint32_t kExact = 0x80000000u;
  uint32_t receiver = 0;
  uint32_t source = 0;  // node index, | kExact for an exact link
  float g = 0.f;
  uint32_t source_node() const { return source & ~kExact; }
  bool exact() const { return (source & kExact) != 0; }
};

struct LinkOptions {
  double epsilon = 3e-5;    // error bound, relative to the largest emitted radiance (channel)
  int visibility_rays = 0;  // 0: HierarchicalOptions picks (fine or coarse transfer)
  uint64_t seed = 1;
  // Fine visibility (see above): split partly visible links while B_s·F̂ > ε/20 (else 2ε), links
  // whose rays were all blocked while B_s·F̂ > ε/5 (else never), re-sample an all-visible link
  // that matters (above ε/20) in every later pass, and refine receivers down to partly hidden
  // patches (hierarchy.h) while B_s·F̂ > ε/20.
  bool fine = true;
};

struct LinkStats {
  std::size_t links = 0, exact_links = 0;
  std::size_t rays = 0;     // visibility rays cast in this pass
  std::size_t refined = 0;  // links of the previous pass that were split (0 on the first)
};

class LinkRefiner {
 public:
  // `caster` is built on the scene whose triangles are `patches`; `budget` may be null.
  LinkRefiner(const std::vector<Patch>& patches, const Hierarchy& hierarchy,
              const scene::RayCaster& caster, const LinkOptions& options, MemoryBudget* budget);

  // Links from the root's link to itself, refined against `bmax` (per node: the largest
  // radiance channel of its patches) with the absolute bound `epsilon`.
  std::vector<Link> initial(const std::vector<float>& bmax, double epsilon, LinkStats* stats) const;
  // `links` re-checked against a new `bmax`: kept, or refined further.
  std::vector<Link> refine(const std::vector<Link>& links, const std::vector<float>& bmax,
                           double epsilon, LinkStats* stats) const;

 private:
  struct Work;
  const std::vector<Patch>& patches_;
  const Hierarchy& h_;
  const scene::RayCaster& caster_;
  LinkOptions options_;
  MemoryBudget* budget_;
};

}  // namespace prt::radiosity
