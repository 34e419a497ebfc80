// hierarchical_error — hierarchical radiosity (radiosity/hierarchical_solver.h) against the dense
// analytic solve on the same patches, with the error broken down (docs/RADIOSITY.md,
// "Hierarchical radiosity"; figures in docs/BENCHMARKS.md).
//
// Prints, over the non-emitting patches: the relative RMS of patch radiance (all channels;
// plain and area-weighted), the share of the squared error per surface (scene primitive) and for
// the ceiling patches above the lamp; and, with --links, the one-step transport error of each
// kind of link: the irradiance the links deliver from the dense solution's radiance against the
// dense matrix summed over the same patch pairs (so the kinds' errors add up to the whole).
// Usage: hierarchical_error [--max-edge L] [--epsilon E,E,…] [--rays K] [--passes P]
//                           [--cache FILE] [--links] [--coarse] [--worst] [--scene FILE]
//                           [--max-rms PERCENT]
//   default: the Cornell box of ../shared/data (white 0.73, red, green, light=20), --max-edge 30,
//   ε = 3e-5; --cache keeps the dense form factors between runs (computed when absent);
//   --coarse: the coarse transfer (HierarchicalOptions::fine_up_to = 0); --worst: the ceiling
//   patches over the lamp furthest from dense; --max-rms: exit 1 when the area-weighted relative
//   RMS of any solve exceeds PERCENT.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "radiosity/form_factor_cache.h"
#include "radiosity/form_factors.h"
#include "radiosity/hidden_patches.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/material_assignment.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

using namespace prt;
using namespace prt::radiosity;

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

struct Args {
  std::string scene = std::string(PRT_SHARED_DATA_DIR) + "/meshes/cornell_box.obj";
  double max_edge = 30;
  std::vector<double> epsilons{3e-5};
  int rays = 0, passes = 4;  // rays 0: the solver's default
  double max_rms = 0;        // percent; 0: no bound
  std::string cache;
  bool links = false, coarse = false, worst = false;
};

Args parse(int argc, char** argv) {
  Args a;
  for (int i = 1; i < argc; ++i) {
    const std::string k = argv[i];
    const auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s: missing value\n", k.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (k == "--max-edge") {
      a.max_edge = std::atof(next().c_str());
    } else if (k == "--epsilon") {
      a.epsilons.clear();
      std::string list = next();
      for (std::size_t at = 0; at <= list.size();) {
        const std::size_t comma = std::min(list.find(',', at), list.size());
        a.epsilons.push_back(std::atof(list.substr(at, comma - at).c_str()));
        at = comma + 1;
      }
    } else if (k == "--rays") {
      a.rays = std::atoi(next().c_str());
    } else if (k == "--max-rms") {
      a.max_rms = std::atof(next().c_str());
    } else if (k == "--passes") {
      a.passes = std::atoi(next().c_str());
    } else if (k == "--cache") {
      a.cache = next();
    } else if (k == "--scene") {
      a.scene = next();
    } else if (k == "--coarse") {
      a.coarse = true;
    } else if (k == "--worst") {
      a.worst = true;
    } else if (k == "--links") {
      a.links = true;
    } else {
      std::fprintf(stderr, "unknown option %s\n", k.c_str());
      std::exit(2);
    }
  }
  return a;
}

scene::Scene cornell(const Args& a) {
  scene::Scene s = scene::load_scene(a.scene);
  scene::apply_emission(s, {scene::parse_material_colour("--emission", "light=20")});
  scene::apply_albedo(s, {scene::parse_material_colour("--albedo", "white=0.73"),
                          scene::parse_material_colour("--albedo", "red=0.63,0.065,0.05"),
                          scene::parse_material_colour("--albedo", "green=0.14,0.45,0.091")});
  return scene::subdivide_to_edge_length(s, a.max_edge);
}

// Per-patch group: the primitive's name, "ceiling above lamp" for ceiling patches whose centroid
// lies over the lamp's footprint (grown by one patch edge).
std::vector<std::string> groups(const scene::Scene& s, const std::vector<Patch>& patches,
                                double edge) {
  std::vector<std::string> g(patches.size());
  glm::dvec3 lo(1e30), hi(-1e30);
  for (const scene::ScenePrimitive& p : s.primitives)
    for (uint32_t t = p.first_triangle; t < p.first_triangle + p.triangle_count; ++t) {
      g[t] = p.name;
      if (patches[t].emission != glm::dvec3(0.0))
        for (const glm::dvec3& c : patches[t].corners) lo = glm::min(lo, c), hi = glm::max(hi, c);
    }
  for (std::size_t t = 0; t < patches.size(); ++t) {
    const glm::dvec3 c = patches[t].centroid;
    if (g[t] == "ceiling" && c.x > lo.x - edge && c.x < hi.x + edge && c.z > lo.z - edge &&
        c.z < hi.z + edge)
      g[t] = "ceiling above lamp";
  }
  return g;
}

struct Error {
  double num = 0, den = 0, wnum = 0, wden = 0, signed_sum = 0, ref_sum = 0;
  void add(const glm::dvec3& a, const glm::dvec3& b, double area) {
    for (int c = 0; c < 3; ++c) {
      const double d = a[c] - b[c];
      num += d * d, den += b[c] * b[c];
      wnum += area * d * d, wden += area * b[c] * b[c];
      signed_sum += area * d, ref_sum += area * b[c];
    }
  }
};

// Prints the error of `h` against `d`; returns the area-weighted relative RMS.
double report(const std::vector<Patch>& patches, const std::vector<std::string>& group,
              const std::vector<glm::dvec3>& h, const std::vector<glm::dvec3>& d) {
  Error all;
  std::map<std::string, Error> by;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    if (patches[i].emission != glm::dvec3(0.0)) continue;
    all.add(h[i], d[i], patches[i].area);
    by[group[i]].add(h[i], d[i], patches[i].area);
  }
  std::printf("  relative RMS %.3f%% (area-weighted %.3f%%), reflected power %.4f of dense\n",
              100 * std::sqrt(all.num / all.den), 100 * std::sqrt(all.wnum / all.wden),
              1 + all.signed_sum / all.ref_sum);
  for (const auto& [name, e] : by)
    std::printf(
        "    %-20s share of squared error %5.1f%% (area-w. %5.1f%%), own rel. RMS %6.2f%%, "
        "bias %+.2f%%\n",
        name.c_str(), 100 * e.num / all.num, 100 * e.wnum / all.wnum,
        100 * std::sqrt(e.num / std::max(e.den, 1e-300)),
        100 * e.signed_sum / std::max(e.ref_sum, 1e-300));
  return std::sqrt(all.wnum / all.wden);
}

// The one-step transport error of each kind of link (see the top).
void link_report(const std::vector<Patch>& patches, const std::vector<std::string>& group,
                 const FormFactorMatrix& f, const std::vector<glm::dvec3>& dense,
                 const HierarchicalSolution& s) {
  const Hierarchy& h = s.hierarchy;
  const std::size_t n = patches.size();
  const auto kind = [&](const Link& l) {
    if (l.exact()) return 0;
    const HierarchyNode &r = h.nodes[l.receiver], &src = h.nodes[l.source_node()];
    if (r.planar && src.planar) return 1;
    if (!r.planar && src.planar) return 2;
    if (r.planar) return 3;
    return 4;
  };
  const char* names[5] = {"exact patch-patch", "point, surface-surface",
                          "point, cluster <- surface", "point, surface <- cluster",
                          "point, cluster <- cluster"};
  double ref = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (patches[i].emission == glm::dvec3(0.0))
      for (int c = 0; c < 3; ++c) ref += dense[i][c] * dense[i][c];
  std::vector<glm::dvec3> total_err(n, glm::dvec3(0.0));
  for (int k = 0; k < 5; ++k) {
    std::vector<Link> subset;
    for (const Link& l : s.links)
      if (kind(l) == k) subset.push_back(l);
    const std::vector<glm::dvec3> hh = gather_irradiance(patches, h, subset, s.stats.fine, dense);
    std::vector<glm::dvec3> hd(n, glm::dvec3(0.0));
    for (const Link& l : subset) {
      const HierarchyNode &r = h.nodes[l.receiver], &src = h.nodes[l.source_node()];
      for (uint32_t a = r.first; a < r.first + r.count; ++a) {
        const uint32_t p = h.order[a];
        glm::dvec3 sum(0.0);
        for (uint32_t b = src.first; b < src.first + src.count; ++b) {
          const uint32_t j = h.order[b];
          sum += double(f.at(j, p)) * patches[j].area * dense[j];
        }
        hd[p] += sum / patches[p].area;
      }
    }
    double num = 0, signed_sum = 0, ref_sum = 0;
    std::map<std::string, double> by;
    for (std::size_t i = 0; i < n; ++i) {
      if (patches[i].emission != glm::dvec3(0.0)) continue;
      const glm::dvec3 e = patches[i].albedo * (patches[i].visible * hh[i] - hd[i]);
      total_err[i] += e;
      for (int c = 0; c < 3; ++c) {
        num += e[c] * e[c];
        by[group[i]] += e[c] * e[c];
        signed_sum += patches[i].area * e[c];
        ref_sum += patches[i].area * dense[i][c];
      }
    }
    std::printf("  %-24s %9zu links: one-step error RMS %.3f%% of the radiance, power %+.3f%%\n",
                names[k], subset.size(), 100 * std::sqrt(num / ref), 100 * signed_sum / ref_sum);
    for (const auto& [name, e] : by)
      std::printf("      %-20s %.3f%%\n", name.c_str(), 100 * std::sqrt(e / ref));
  }
  double num = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (patches[i].emission == glm::dvec3(0.0))
      for (int c = 0; c < 3; ++c) num += total_err[i][c] * total_err[i][c];
  std::printf("  all links: one-step error RMS %.3f%%\n", 100 * std::sqrt(num / ref));
  // The dense transfer no link stands for (pairs the refinement culled or dropped).
  std::vector<glm::dvec3> full(n, glm::dvec3(0.0)), linked(n, glm::dvec3(0.0));
  for (std::size_t p = 0; p < n; ++p) {
    glm::dvec3 sum(0.0);
    for (std::size_t j = 0; j < n; ++j) sum += double(f.at(j, p)) * patches[j].area * dense[j];
    full[p] = sum / patches[p].area;
  }
  for (const Link& l : s.links) {
    const HierarchyNode &r = h.nodes[l.receiver], &src = h.nodes[l.source_node()];
    for (uint32_t a = r.first; a < r.first + r.count; ++a) {
      const uint32_t p = h.order[a];
      glm::dvec3 sum(0.0);
      for (uint32_t b = src.first; b < src.first + src.count; ++b) {
        const uint32_t j = h.order[b];
        sum += double(f.at(j, p)) * patches[j].area * dense[j];
      }
      linked[p] += sum / patches[p].area;
    }
  }
  num = 0;
  double signed_sum = 0, ref_sum = 0;
  std::map<std::string, double> by;
  for (std::size_t i = 0; i < n; ++i) {
    if (patches[i].emission != glm::dvec3(0.0)) continue;
    const glm::dvec3 e = patches[i].albedo * (linked[i] - full[i]);
    for (int c = 0; c < 3; ++c) {
      num += e[c] * e[c];
      by[group[i]] += e[c] * e[c];
      signed_sum += patches[i].area * e[c];
      ref_sum += patches[i].area * dense[i][c];
    }
  }
  std::printf("  dense transfer of no link: RMS %.3f%% of the radiance, power %+.3f%%\n",
              100 * std::sqrt(num / ref), 100 * signed_sum / ref_sum);
  for (const auto& [name, e] : by)
    std::printf("      %-20s %.3f%%\n", name.c_str(), 100 * std::sqrt(e / ref));
}

}  // namespace

int main(int argc, char** argv) {
  const Args a = parse(argc, argv);
  if (!std::filesystem::exists(a.scene)) {
    std::printf("SKIP: %s is missing (../shared/data beside the project)\n", a.scene.c_str());
    return 77;
  }
  const scene::Scene s = cornell(a);
  const scene::RayCaster caster(s);
  std::vector<Patch> patches = make_patches(s);
  std::printf("%s, --max-edge %g: %zu patches\n", a.scene.c_str(), a.max_edge, patches.size());
  FormFactorOptions fo;
  Clock::time_point t = Clock::now();
  FormFactorMatrix f;
  const uint64_t key = form_factor_key(patches, fo);
  if (!a.cache.empty() && std::filesystem::exists(a.cache)) {
    f = load_form_factors(a.cache, key);
  } else {
    f = compute_form_factors(patches, caster, fo);
    if (!a.cache.empty()) save_form_factors(a.cache, f, key, &fo);
  }
  SolveOptions so;
  so.tolerance = 1e-7;
  const Solution dense = solve_matrix(patches, f, so);
  std::printf("dense analytic (3 points, Gauss-Seidel): %.1f s\n", since(t));
  mark_hidden_parts(&patches, caster, fo);  // as solve_scene does (the dense solve ignores it)
  const std::vector<std::string> group = groups(s, patches, a.max_edge);
  bool failed = false;
  for (double eps : a.epsilons) {
    HierarchicalOptions ho;
    ho.links.epsilon = eps;
    ho.links.visibility_rays = a.rays;
    ho.max_passes = a.passes;
    if (a.coarse) ho.fine_up_to = 0;  // the coarse transfer, for comparison
    ho.solve.tolerance = 1e-7;
    t = Clock::now();
    const HierarchicalSolution h = solve_hierarchical(patches, caster, ho);
    std::printf("hierarchical eps %g: %.2f s, %zu links (%zu exact), %zu rays, %zu passes\n", eps,
                since(t), h.stats.links, h.stats.exact_links, h.stats.rays, h.stats.passes.size());
    const double rms = report(patches, group, h.solution.radiance, dense.radiance);
    if (a.max_rms > 0 && 100 * rms > a.max_rms) {
      std::printf("FAIL: eps %g: area-weighted relative RMS %.3f%% above --max-rms %g%%\n", eps,
                  100 * rms, a.max_rms);
      failed = true;
    }
    {  // is the solution the fixed point of its own links? L = v (E + ρ H(L))
      const std::vector<glm::dvec3> hh =
          gather_irradiance(patches, h.hierarchy, h.links, h.stats.fine, h.solution.radiance);
      std::vector<glm::dvec3> again(patches.size());
      for (std::size_t i = 0; i < patches.size(); ++i)
        again[i] = patches[i].visible * (patches[i].emission + patches[i].albedo * hh[i]);
      std::printf("  fixed point check:\n");
      report(patches, group, again, h.solution.radiance);
    }
    if (a.links) link_report(patches, group, f, dense.radiance, h);
    if (a.worst) {  // the ceiling patches over the lamp furthest from dense
      std::vector<std::size_t> ring;
      for (std::size_t i = 0; i < patches.size(); ++i)
        if (group[i] == "ceiling above lamp") ring.push_back(i);
      std::sort(ring.begin(), ring.end(), [&](std::size_t x, std::size_t y) {
        return std::abs(h.solution.radiance[x].x - dense.radiance[x].x) >
               std::abs(h.solution.radiance[y].x - dense.radiance[y].x);
      });
      for (std::size_t k = 0; k < std::min<std::size_t>(12, ring.size()); ++k) {
        const std::size_t i = ring[k];
        std::printf(
            "    patch %zu at (%.1f %.1f %.1f) area %.1f visible %.2f: dense %.4f, here %.4f\n", i,
            patches[i].centroid.x, patches[i].centroid.y, patches[i].centroid.z, patches[i].area,
            patches[i].visible, dense.radiance[i].x, h.solution.radiance[i].x);
      }
    }
  }
  return failed ? 1 : 0;
}
