// radiosity/src/hierarchical_solver.cpp — see radiosity/hierarchical_solver.h.
#include "radiosity/hierarchical_solver.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace prt::radiosity {
namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

constexpr uint32_t kNoSlot = 0xFFFFFFFFu;
using Buckets = std::array<glm::dvec3, 6>;

double max_channel(const glm::dvec3& v) {
  return std::max(v.x, std::max(v.y, v.z));
}

// The state of the gather / push–pull iterations on one hierarchy and one set of links.
class LinkSolver {
 public:
  LinkSolver(const std::vector<Patch>& patches, const Hierarchy& h, bool fine, MemoryBudget* budget)
      : patches_(patches), h_(h), fine_(fine), budget_(budget) {
    const std::size_t n = h.nodes.size();
    std::size_t clusters = 0;
    slot_.assign(n, kNoSlot);
    for (std::size_t i = 0; i < n; ++i)
      if (!h.nodes[i].planar) slot_[i] = static_cast<uint32_t>(clusters++);
    charged_ = n * (2 * sizeof(glm::dvec3) + sizeof(float) + sizeof(uint32_t) + sizeof(uint64_t)) +
               (fine ? n * sizeof(uint32_t) + clusters * sizeof(Buckets)
                     : n * sizeof(glm::dvec3) + clusters * 2 * sizeof(Buckets));
    if (budget_) budget_->charge(charged_, "the hierarchical radiosity node state");
    radiance_.assign(n, glm::dvec3(0.0));
    irradiance_.assign(n, glm::dvec3(0.0));
    bmax_.assign(n, 0.f);
    sent_.assign(clusters, Buckets{});
    if (fine) {
      parent_.assign(n, kNoSlot);
      for (std::size_t i = 0; i < n; ++i)
        if (!h.nodes[i].leaf())
          parent_[h.nodes[i].left] = parent_[h.nodes[i].right] = static_cast<uint32_t>(i);
    } else {
      from_parent_.assign(n, glm::dvec3(0.0));
      received_.assign(clusters, Buckets{});
    }
    for (std::size_t p = 0; p < patches.size(); ++p) radiance_[h.leaf_of[p]] = patches[p].emission;
    pull();
  }
  ~LinkSolver() {
    if (budget_) budget_->release(charged_);
  }
  LinkSolver(const LinkSolver&) = delete;
  LinkSolver& operator=(const LinkSolver&) = delete;

  void set_links(const std::vector<Link>* links) {
    links_ = links;
    offsets_.assign(h_.nodes.size() + 1, 0);
    for (const Link& l : *links) ++offsets_[l.receiver + 1];
    for (std::size_t i = 0; i < h_.nodes.size(); ++i) offsets_[i + 1] += offsets_[i];
  }

  const std::vector<float>& bmax() const { return bmax_; }

  // The patches' leaf radiance (the state an iteration starts from; all else follows by pull).
  std::vector<glm::dvec3> leaf_radiance() const {
    std::vector<glm::dvec3> out(patches_.size());
    for (std::size_t p = 0; p < patches_.size(); ++p) out[p] = radiance_[h_.leaf_of[p]];
    return out;
  }
  void set_leaf_radiance(const std::vector<glm::dvec3>& radiance) {
    for (std::size_t p = 0; p < patches_.size(); ++p) radiance_[h_.leaf_of[p]] = radiance[p];
    pull();
  }

  // gather_irradiance (hierarchical_solver.h): radiance of the visible parts at the leaves, one
  // gather (and push); the patches' irradiance.
  std::vector<glm::dvec3> irradiance_from(const std::vector<glm::dvec3>& radiance) {
    for (std::size_t p = 0; p < patches_.size(); ++p) {
      const double v = patches_[p].visible;
      radiance_[h_.leaf_of[p]] = v > 0.0 ? radiance[p] / v : glm::dvec3(0.0);
    }
    pull();
    gather();
    if (!fine_) push();
    std::vector<glm::dvec3> out(patches_.size());
    for (std::size_t p = 0; p < patches_.size(); ++p) out[p] = irradiance_[h_.leaf_of[p]];
    return out;
  }

  // Iterates until the unshot power is at most options.tolerance of the emitted power.
  void iterate(const SolveOptions& options, Solution* out) {
    glm::dvec3 emitted(0.0);
    for (std::size_t p = 0; p < patches_.size(); ++p)
      emitted += double(h_.nodes[h_.leaf_of[p]].area) * patches_[p].emission;
    const double total = emitted.x + emitted.y + emitted.z;
    if (!(total > 0.0)) throw std::invalid_argument("hierarchical radiosity: nothing emits");
    out->energy.emitted = emitted;
    for (std::size_t k = 0; k < options.max_iterations; ++k) {
      const glm::dvec3 unshot = step(&out->energy);
      ++out->iterations;
      out->energy.unshot = unshot;
      out->relative_unshot = (unshot.x + unshot.y + unshot.z) / total;
      out->unshot_history.push_back(out->relative_unshot);
      if (out->relative_unshot <= options.tolerance) {
        out->converged = true;
        break;
      }
    }
  }

  void radiance_out(Solution* out) const {
    out->radiance.resize(patches_.size());
    for (std::size_t p = 0; p < patches_.size(); ++p)  // area means, as radiosity/patches.h
      out->radiance[p] = radiance_[h_.leaf_of[p]] * std::clamp(patches_[p].visible, 0.0, 1.0);
    out->display_radiance = out->radiance;
  }

 private:
  // One Jacobi iteration; returns the unshot power per channel and sets the energy account.
  glm::dvec3 step(EnergyAccount* energy) {
    gather();
    if (!fine_) push();
    glm::dvec3 unshot(0.0), leaving(0.0), arrived(0.0), absorbed(0.0);
    for (std::size_t p = 0; p < patches_.size(); ++p) {
      const Patch& patch = patches_[p];
      const uint32_t leaf = h_.leaf_of[p];
      const double area = h_.nodes[leaf].area;  // visible area
      const glm::dvec3 h = irradiance_[leaf];
      const glm::dvec3 next = patch.emission + patch.albedo * h;
      unshot += area * glm::abs(next - radiance_[leaf]);
      leaving += area * radiance_[leaf];
      arrived += area * h;
      absorbed += area * (glm::dvec3(1.0) - patch.albedo) * h;
      radiance_[leaf] = next;
    }
    pull();
    energy->absorbed = absorbed;
    energy->escaped = leaving - arrived;
    return unshot;
  }

  void gather() {
    if (fine_) {
      tbb::parallel_for(tbb::blocked_range<std::size_t>(0, patches_.size(), 256),
                        [&](const tbb::blocked_range<std::size_t>& range) {
                          for (std::size_t p = range.begin(); p != range.end(); ++p) {
                            const uint32_t leaf = h_.leaf_of[p];
                            irradiance_[leaf] = gather_at_patch(leaf);
                          }
                        });
      return;
    }
    const std::vector<HierarchyNode>& nodes = h_.nodes;
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, nodes.size(), 1024),
                      [&](const tbb::blocked_range<std::size_t>& range) {
                        for (std::size_t r = range.begin(); r != range.end(); ++r) gather_at(r);
                      });
  }

  // Fine transfer: the irradiance of the patch of `leaf` from its exact links and from the point
  // links of its leaf and of every ancestor (surface nodes and clusters), each evaluated at its
  // centroid with its own normal — the kernel's variation over a receiving node and its patches'
  // orientations resolved down to the patches instead of a constant (or six axis buckets) pushed
  // down the hierarchy. Costs Σ over links of the receiver's patches per iteration.
  glm::dvec3 gather_at_patch(uint32_t leaf) const {
    const HierarchyNode& nl = h_.nodes[leaf];
    if (!(nl.area > 0.f)) return glm::dvec3(0.0);
    const glm::dvec3 x(nl.centroid), n(nl.normal);
    glm::dvec3 power(0.0), sum(0.0), d;
    for (uint64_t k = offsets_[leaf]; k < offsets_[leaf + 1]; ++k) {
      const Link& link = (*links_)[k];
      if (link.exact()) power += double(link.g) * radiance_[link.source_node()];
    }
    for (uint32_t a = leaf; a != kNoSlot; a = parent_[a]) {
      const HierarchyNode& na = h_.nodes[a];
      for (uint64_t k = offsets_[a]; k < offsets_[a + 1]; ++k) {
        const Link& link = (*links_)[k];
        if (link.exact()) continue;
        const glm::dvec3 sent = sent_toward(link, na, x, &d);
        sum += sent * std::max(0.0, glm::dot(n, d));
      }
    }
    return power / double(nl.area) + sum;
  }

  // What a point link r ← s sends toward a receiving point at `x` (direction d to s's centroid):
  // the sender's radiance-weighted projected area toward −d times the link's g at distance
  // |x − c_s| (g holds V / (π r²) at the centroids).
  glm::dvec3 sent_toward(const Link& link, const HierarchyNode& nr, const glm::dvec3& x,
                         glm::dvec3* d_out) const {
    const HierarchyNode& ns = h_.nodes[link.source_node()];
    const glm::dvec3 delta = glm::dvec3(ns.centroid) - x;
    const double r2 = glm::dot(delta, delta);
    const glm::dvec3 d = delta / std::sqrt(r2);
    *d_out = d;
    glm::dvec3 sent(0.0);
    if (ns.planar) {
      sent = radiance_[link.source_node()] *
             (double(ns.area) * std::max(0.0, -glm::dot(glm::dvec3(ns.normal), d)));
    } else {
      const Buckets& q = sent_[slot_[link.source_node()]];
      for (int a = 0; a < 3; ++a) sent += std::abs(d[a]) * q[2 * a + (d[a] > 0.0)];
    }
    const glm::dvec3 c = glm::dvec3(ns.centroid) - glm::dvec3(nr.centroid);
    return sent * (double(link.g) * glm::dot(c, c) / r2);
  }

  void gather_at(std::size_t r) {
    const HierarchyNode& nr = h_.nodes[r];
    glm::dvec3 power(0.0);
    Buckets buckets{};
    const bool split = nr.planar && !nr.leaf();
    glm::dvec3 child_h[2] = {glm::dvec3(0.0), glm::dvec3(0.0)};
    for (uint64_t k = offsets_[r]; k < offsets_[r + 1]; ++k) {
      const Link& link = (*links_)[k];
      const uint32_t s = link.source_node();
      if (link.exact()) {
        power += double(link.g) * radiance_[s];
        continue;
      }
      glm::dvec3 d;
      if (split) {
        const uint32_t kids[2] = {nr.left, nr.right};
        for (int c = 0; c < 2; ++c) {
          const HierarchyNode& child = h_.nodes[kids[c]];
          const glm::dvec3 sent = sent_toward(link, nr, glm::dvec3(child.centroid), &d);
          child_h[c] += sent * std::max(0.0, glm::dot(glm::dvec3(nr.normal), d));
        }
        continue;
      }
      const glm::dvec3 sent = sent_toward(link, nr, glm::dvec3(nr.centroid), &d);
      if (nr.planar) {
        power += sent * (double(nr.area) * std::max(0.0, glm::dot(glm::dvec3(nr.normal), d)));
      } else {
        for (int a = 0; a < 3; ++a) {
          const int b = 2 * a + (d[a] < 0.0);
          buckets[b] += sent * (std::abs(d[a]) * double(nr.axis_area[b]));
        }
      }
    }
    if (split) {
      from_parent_[nr.left] = child_h[0];
      from_parent_[nr.right] = child_h[1];
    }
    if (nr.planar)
      irradiance_[r] = nr.area > 0.f ? power / double(nr.area) : glm::dvec3(0.0);
    else
      received_[slot_[r]] = buckets;
  }

  // Parents before children: hand down irradiance (planar) or bucket power (clusters).
  void push() {
    const std::vector<HierarchyNode>& nodes = h_.nodes;
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const HierarchyNode& n = nodes[i];
      if (n.leaf()) continue;
      for (uint32_t c : {n.left, n.right}) {
        const HierarchyNode& child = nodes[c];
        if (n.planar) {
          if (child.area > 0.f) irradiance_[c] += irradiance_[i] + from_parent_[c];
          continue;
        }
        const Buckets& from = received_[slot_[i]];
        glm::dvec3 power(0.0);
        for (int b = 0; b < 6; ++b) {
          if (!(n.axis_area[b] > 0.f)) continue;
          const glm::dvec3 share = from[b] * (double(child.axis_area[b]) / double(n.axis_area[b]));
          if (child.planar)
            power += share;
          else
            received_[slot_[c]][b] += share;
        }
        if (child.planar && child.area > 0.f) irradiance_[c] += power / double(child.area);
      }
    }
  }

  // Children before parents: area-weighted radiance (planar), radiance-weighted axis areas
  // (clusters), and the largest radiance channel below each node.
  void pull() {
    const std::vector<HierarchyNode>& nodes = h_.nodes;
    for (std::size_t k = nodes.size(); k-- > 0;) {
      const HierarchyNode& n = nodes[k];
      if (n.leaf()) {
        bmax_[k] = float(max_channel(radiance_[k]));
        continue;
      }
      const HierarchyNode &a = nodes[n.left], &b = nodes[n.right];
      bmax_[k] = std::max(bmax_[n.left], bmax_[n.right]);
      if (n.planar) {
        radiance_[k] =
            n.area > 0.f
                ? (double(a.area) * radiance_[n.left] + double(b.area) * radiance_[n.right]) /
                      double(n.area)
                : glm::dvec3(0.0);
        continue;
      }
      Buckets& q = sent_[slot_[k]];
      for (int i = 0; i < 6; ++i) q[i] = glm::dvec3(0.0);
      for (uint32_t c : {n.left, n.right}) {
        const HierarchyNode& child = nodes[c];
        for (int i = 0; i < 6; ++i)
          q[i] += child.planar ? radiance_[c] * double(child.axis_area[i]) : sent_[slot_[c]][i];
      }
    }
  }

  const std::vector<Patch>& patches_;
  const Hierarchy& h_;
  bool fine_;  // HierarchicalOptions::fine_up_to
  MemoryBudget* budget_;
  uint64_t charged_ = 0;
  const std::vector<Link>* links_ = nullptr;
  std::vector<uint64_t> offsets_;
  std::vector<uint32_t> slot_;
  std::vector<glm::dvec3> radiance_, irradiance_;
  // A planar node's point links evaluated at its children's centroids: their irradiance, each
  // child's own (push hands it down with the rest instead of the node's centroid value).
  std::vector<glm::dvec3> from_parent_;  // coarse transfer only
  std::vector<uint32_t> parent_;         // fine transfer only; kNoSlot for the root
  std::vector<float> bmax_;
  std::vector<Buckets> sent_, received_;
};

void check_options(const HierarchicalOptions& o) {
  if (!(o.links.epsilon > 0.0) || !std::isfinite(o.links.epsilon))
    throw std::invalid_argument("hierarchical radiosity: epsilon must be a finite positive number");
  if (o.max_passes < 1) throw std::invalid_argument("hierarchical radiosity: max_passes < 1");
  if (o.links.visibility_rays < 0 || o.fine_visibility_rays < 1 || o.coarse_visibility_rays < 1)
    throw std::invalid_argument("hierarchical radiosity: visibility rays < 1");
}

}  // namespace

namespace {

// The statistics of the hierarchy, the oracle's absolute ε, the transfer and the link options
// as the solve resolves them.
LinkOptions prepare(const std::vector<Patch>& patches, const HierarchicalOptions& options,
                    HierarchicalSolution* out) {
  HierarchicalStats& st = out->stats;
  st.patches = patches.size();
  st.nodes = out->hierarchy.nodes.size();
  st.planar_nodes = out->hierarchy.planar_nodes;
  st.clusters = out->hierarchy.clusters;
  double emission_max = 0.0;
  for (const Patch& p : patches) emission_max = std::max(emission_max, max_channel(p.emission));
  if (!(emission_max > 0.0)) throw std::invalid_argument("hierarchical radiosity: nothing emits");
  st.epsilon_absolute = options.links.epsilon * emission_max;
  st.fine = patches.size() <= options.fine_up_to;
  return resolved_link_options(patches.size(), options);
}

// Solves on out->links (set_links) from the solver's state; records the pass and the state the
// solve started from.
void solve_pass(LinkSolver& solver, const HierarchicalOptions& options, HierarchicalPass record,
                HierarchicalSolution* out) {
  HierarchicalStats& st = out->stats;
  const Clock::time_point t = Clock::now();
  out->last_start = solver.leaf_radiance();
  solver.set_links(&out->links);
  Solution solution;
  solver.iterate(options.solve, &solution);
  record.solve_seconds = since(t);
  record.iterations = solution.iterations;
  solution.iterations += out->solution.iterations;
  out->solution = std::move(solution);
  st.passes.push_back(record);
  st.link_seconds += record.link_seconds;
  st.solve_seconds += record.solve_seconds;
  st.rays += record.rays;
}

// Refinement passes, each followed by a solve: the first from the root's self-link (`resume`
// false) or from out->links (true), every later one from the links before it, until a later pass
// splits nothing or max_passes.
void refine_and_solve(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                      const HierarchicalOptions& options, bool resume, MemoryBudget* b,
                      HierarchicalSolution* out) {
  HierarchicalStats& st = out->stats;
  const LinkOptions link_options = prepare(patches, options, out);
  LinkSolver solver(patches, out->hierarchy, st.fine, b);
  const LinkRefiner refiner(patches, out->hierarchy, caster, link_options, b);
  for (int pass = 0; pass < options.max_passes; ++pass) {
    HierarchicalPass record;
    const Clock::time_point t = Clock::now();
    LinkStats ls;
    std::vector<Link> links =
        pass == 0 && !resume ? refiner.initial(solver.bmax(), st.epsilon_absolute, &ls)
                             : refiner.refine(out->links, solver.bmax(), st.epsilon_absolute, &ls);
    if (pass > 0 && ls.refined == 0) {
      b->release(links.size() * sizeof(Link));
      break;
    }
    if (pass > 0 || resume) b->release(out->links.size() * sizeof(Link));
    out->links = std::move(links);
    record.link_seconds = since(t);
    record.links = ls.links, record.exact_links = ls.exact_links, record.rays = ls.rays;
    record.refined = ls.refined;
    solve_pass(solver, options, record, out);
  }
  solver.radiance_out(&out->solution);
}

void finish(const MemoryBudget* b, uint64_t used_before, HierarchicalSolution* out) {
  HierarchicalStats& st = out->stats;
  st.links = out->links.size();
  st.exact_links = st.passes.back().exact_links;
  st.link_bytes = out->links.size() * sizeof(Link);
  st.budget_peak = b->peak() > used_before ? b->peak() - used_before : 0;
}

}  // namespace

LinkOptions resolved_link_options(std::size_t patches, const HierarchicalOptions& options) {
  const bool fine = patches <= options.fine_up_to;
  LinkOptions link_options = options.links;
  link_options.fine = fine;
  if (link_options.visibility_rays == 0)
    link_options.visibility_rays =
        fine ? options.fine_visibility_rays : options.coarse_visibility_rays;
  return link_options;
}

HierarchicalSolution solve_hierarchical(const std::vector<Patch>& patches,
                                        const scene::RayCaster& caster,
                                        const HierarchicalOptions& options, MemoryBudget* budget) {
  check_options(options);
  MemoryBudget unlimited;
  MemoryBudget* b = budget ? budget : &unlimited;
  const uint64_t used_before = b->used();
  HierarchicalSolution out;
  const Clock::time_point t = Clock::now();
  b->charge(hierarchy_bytes(patches.size()), "the radiosity hierarchy");
  out.hierarchy = build_hierarchy(patches);
  out.stats.hierarchy_seconds = since(t);
  refine_and_solve(patches, caster, options, false, b, &out);
  finish(b, used_before, &out);
  return out;
}

HierarchicalSolution resume_hierarchical(const std::vector<Patch>& patches,
                                         const scene::RayCaster& caster,
                                         const HierarchicalOptions& options, Hierarchy hierarchy,
                                         std::vector<Link> links,
                                         const std::vector<glm::dvec3>* start,
                                         MemoryBudget* budget) {
  check_options(options);
  if (hierarchy.order.size() != patches.size() || (start && start->size() != patches.size()))
    throw std::invalid_argument("resume_hierarchical: hierarchy or start of other patches");
  MemoryBudget unlimited;
  MemoryBudget* b = budget ? budget : &unlimited;
  const uint64_t used_before = b->used();
  b->charge(hierarchy_bytes(patches.size()), "the radiosity hierarchy");
  b->charge(links.size() * sizeof(Link), "the hierarchical radiosity links");
  HierarchicalSolution out;
  out.hierarchy = std::move(hierarchy);
  out.links = std::move(links);
  if (!start) {
    refine_and_solve(patches, caster, options, true, b, &out);
  } else {  // the links as they are, the last solve of the run that made them
    prepare(patches, options, &out);
    LinkSolver solver(patches, out.hierarchy, out.stats.fine, b);
    solver.set_leaf_radiance(*start);
    HierarchicalPass record;
    record.links = out.links.size();
    for (const Link& l : out.links) record.exact_links += l.exact();
    solve_pass(solver, options, record, &out);
    solver.radiance_out(&out.solution);
  }
  finish(b, used_before, &out);
  return out;
}

Solution solve_on_links(const std::vector<Patch>& patches, const Hierarchy& hierarchy,
                        const std::vector<Link>& links, bool fine, const SolveOptions& options,
                        MemoryBudget* budget) {
  LinkSolver solver(patches, hierarchy, fine, budget);
  solver.set_links(&links);
  Solution out;
  solver.iterate(options, &out);
  solver.radiance_out(&out);
  return out;
}

std::vector<glm::dvec3> gather_irradiance(const std::vector<Patch>& patches,
                                          const Hierarchy& hierarchy,
                                          const std::vector<Link>& links, bool fine,
                                          const std::vector<glm::dvec3>& radiance) {
  LinkSolver solver(patches, hierarchy, fine, nullptr);
  solver.set_links(&links);
  return solver.irradiance_from(radiance);
}

prt::EmitterResponses hierarchical_emitter_responses(const scene::Scene& scene,
                                                     const std::vector<Patch>& patches,
                                                     const HierarchicalSolution& solved,
                                                     const SolveOptions& options,
                                                     std::vector<EmitterSolveReport>* reports) {
  return emitter_responses(
      scene, patches,
      [&](const std::vector<Patch>& lit) {
        return solve_on_links(lit, solved.hierarchy, solved.links, solved.stats.fine, options);
      },
      reports);
}

}  // namespace prt::radiosity
