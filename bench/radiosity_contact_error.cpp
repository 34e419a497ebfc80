// radiosity_contact_error — per-vertex radiosity against a path tracer at the vertices, before
// and after hidden patch parts are kept out of the vertex radiance (radiosity/hidden_patches.h;
// docs/RADIOSITY.md, "Contacts"). One solve; the vertex radiance is taken both ways from it.
// Prints, over the lit vertices (reference ≥ 1% of the mean vertex reference, emitters left
// out; fixtures/radiosity/vertex_reference.h): the RMS of the per-vertex
// relative error, the radiance-weighted RMS, the count above 20%, the reference's own noise;
// the same for the vertices the change touched, for those in the lamp's penumbra (some but not
// all of 64 shadow rays to the emitters blocked: where shadow-boundary meshing, D1/D2, would
// act) and for the rest.
// Usage: radiosity_contact_error [--quick] [--max-edge L] [--method analytic|rays|hemicube]
//                                [--samples N] [--csv OUT]
//   default: the Cornell box of ../shared/data (white 0.73, red, green, light=20, as in
//   docs/RADIOSITY.md), --max-edge 29, analytic form factors, 1024 paths per vertex;
//   --quick: the block-on-a-floor scene of fixtures/radiosity/contact_scene.h (for the tests).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include "fixtures/radiosity/contact_scene.h"
#include "fixtures/radiosity/vertex_reference.h"
#include "radiosity/form_factors.h"
#include "radiosity/hidden_patches.h"
#include "radiosity/patches.h"
#include "radiosity/solver.h"
#include "scene/material_assignment.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

using namespace prt;

namespace {

// Fraction of `count` shadow rays from vertex v (lifted along n) to points on the emitters that
// arrive; −1 when no emitter lies in front of it.
double emitter_visibility(const scene::Scene& s, const std::vector<radiosity::Patch>& patches,
                          const scene::RayCaster& caster, const glm::dvec3& x, const glm::dvec3& n,
                          int count) {
  std::vector<uint32_t> emitters;
  for (uint32_t t = 0; t < patches.size(); ++t)
    if (patches[t].emission != glm::dvec3(0.0)) emitters.push_back(t);
  int in_front = 0, arrive = 0;
  for (int k = 0; k < count; ++k) {
    const radiosity::Patch& e = patches[emitters[k % emitters.size()]];
    // A fixed lattice of barycentrics per emitter.
    const double a = std::fmod(0.5 + k * 0.6180339887, 1.0),
                 b = std::fmod(0.5 + k * 0.7548776662, 1.0);
    const double u = a + b > 1.0 ? 1.0 - a : a, w = a + b > 1.0 ? 1.0 - b : b;
    const glm::dvec3 y =
        e.corners[0] + u * (e.corners[1] - e.corners[0]) + w * (e.corners[2] - e.corners[0]);
    const glm::dvec3 d = y - x;
    if (glm::dot(d, n) <= 0.0 || glm::dot(-d, e.normal) <= 0.0) continue;
    ++in_front;
    const double len = glm::length(d);
    arrive +=
        caster.occluded(glm::vec3(x), glm::vec3(d / len), 0.f, float(len * (1 - 1e-4))) ? 0 : 1;
  }
  (void)s;
  return in_front == 0 ? -1.0 : double(arrive) / in_front;
}

void print(const char* what, const test::VertexErrors& e) {
  std::printf(
      "  %-34s %5zu lit  RMS %6.2f%%  weighted %6.2f%%  >20%% %5zu  (reference noise %.2f%%)\n",
      what, e.lit, 100 * e.rms, 100 * e.weighted_rms, e.over_20, 100 * e.rms_noise);
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  double max_edge = 29;
  int samples = 0;  // 0: 1024, or 256 with --quick
  std::string method = "analytic", csv;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool more = i + 1 < argc;
    if (a == "--quick")
      quick = true;
    else if (a == "--max-edge" && more)
      max_edge = std::atof(argv[++i]);
    else if (a == "--samples" && more)
      samples = std::atoi(argv[++i]);
    else if (a == "--method" && more)
      method = argv[++i];
    else if (a == "--csv" && more)
      csv = argv[++i];
    else {
      std::fprintf(stderr,
                   "usage: radiosity_contact_error [--quick] [--max-edge L] [--method "
                   "analytic|rays|hemicube] [--samples N] [--csv OUT]\n");
      return 2;
    }
  }
  scene::Scene s;
  if (quick) {
    s = test::contact_scene(24);
    if (samples == 0) samples = 256;
  } else {
    const std::string path = std::string(PRT_SHARED_DATA_DIR) + "/meshes/cornell_box.obj";
    if (!std::ifstream(path)) {
      std::printf("skipped: %s not found\n", path.c_str());
      return 0;
    }
    s = scene::load_scene(path);
    scene::apply_emission(s, {scene::parse_material_colour("--emission", "light=20")});
    scene::apply_albedo(s, {scene::parse_material_colour("--albedo", "white=0.73"),
                            scene::parse_material_colour("--albedo", "red=0.63,0.065,0.05"),
                            scene::parse_material_colour("--albedo", "green=0.14,0.45,0.091")});
    s = scene::subdivide_to_edge_length(s, max_edge);
  }
  if (samples == 0) samples = 1024;
  radiosity::FormFactorOptions ff;
  if (method == "rays") {
    ff.method = radiosity::FormFactorMethod::Rays;
    ff.rays_per_patch = 1024;
    ff.emitter_rows = radiosity::EmitterRows::Reciprocal;
  } else if (method == "hemicube") {
    ff.method = radiosity::FormFactorMethod::Hemicube;
  } else if (method != "analytic") {
    std::fprintf(stderr, "--method %s: analytic, rays or hemicube\n", method.c_str());
    return 2;
  }
  std::vector<radiosity::Patch> patches = radiosity::make_patches(s);
  const scene::RayCaster caster(s);
  radiosity::SolveOptions so;
  so.tolerance = 1e-4;
  const radiosity::Solution sol =
      radiosity::solve_matrix(patches, radiosity::compute_form_factors(patches, caster, ff), so);
  const std::vector<float> before = radiosity::vertex_radiance(s, patches, sol.radiance);
  const auto t0 = std::chrono::steady_clock::now();
  radiosity::mark_hidden_parts(&patches, caster, ff);
  const double mark_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::vector<float> after = radiosity::vertex_radiance(s, patches, sol.radiance);
  // A variant: partly hidden patches only where a vertex has no wholly visible patch.
  std::vector<float> whole_only(3 * s.vertex_count(), 0.f);
  {
    std::vector<glm::dvec3> sum(s.vertex_count(), glm::dvec3(0.0)), psum = sum;
    std::vector<double> w(s.vertex_count(), 0.0), pw = w;
    for (uint32_t t = 0; t < patches.size(); ++t)
      for (int k = 0; k < 3; ++k) {
        const uint32_t v = s.triangles[t][k];
        if (patches[t].visible == 1.0)
          sum[v] += patches[t].area * sol.radiance[t], w[v] += patches[t].area;
        else if (patches[t].visible > 0.0)
          psum[v] += patches[t].area * sol.radiance[t],
              pw[v] += patches[t].area * patches[t].visible;
      }
    for (std::size_t v = 0; v < s.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c)
        whole_only[3 * v + c] = float(w[v] > 0    ? sum[v][c] / w[v]
                                      : pw[v] > 0 ? psum[v][c] / pw[v]
                                                  : 0.0);
  }
  std::size_t hidden = 0, partly = 0;
  for (const radiosity::Patch& p : patches)
    hidden += p.visible == 0.0, partly += p.visible > 0.0 && p.visible < 1.0;
  std::printf(
      "%s, %s form factors: %zu patches (%zu hidden, %zu partly), %zu vertices, %d paths per "
      "vertex\n",
      quick ? "block on a floor" : "Cornell box", method.c_str(), patches.size(), hidden, partly,
      s.vertex_count(), samples);
  std::printf("visible fractions: %.3f s\n", mark_seconds);
  std::vector<double> visible(patches.size());
  for (std::size_t t = 0; t < patches.size(); ++t) visible[t] = patches[t].visible;
  const test::VertexReference ref = test::vertex_reference(s, samples, &visible);
  // Vertex classes: touched by the change; in the emitters' penumbra; the rest.
  const std::size_t n = s.vertex_count();
  std::vector<bool> touched(n, false), penumbra(n, false), rest(n, false);
  std::vector<glm::dvec3> normal(n, glm::dvec3(0.0));
  for (uint32_t t = 0; t < patches.size(); ++t)
    for (int k = 0; k < 3; ++k) normal[s.triangles[t][k]] += patches[t].area * patches[t].normal;
  for (std::size_t v = 0; v < n; ++v) {
    for (int c = 0; c < 3; ++c) touched[v] = touched[v] || before[3 * v + c] != after[3 * v + c];
    const double len = glm::length(normal[v]);
    if (!ref.compared[v] || !(len > 0.0)) continue;
    const glm::dvec3 nv = normal[v] / len;
    const double vis = emitter_visibility(
        s, patches, caster, glm::dvec3(s.positions[v]) + 1e-4 * max_edge * nv, nv, 64);
    penumbra[v] = !touched[v] && vis > 0.0 && vis < 1.0;
    rest[v] = !touched[v] && !penumbra[v];
  }
  for (int pass = 0; pass < 3; ++pass) {
    const std::vector<float>& l = pass == 0 ? before : pass == 1 ? after : whole_only;
    std::printf("%s:\n", pass == 0   ? "before (area means of all patches)"
                         : pass == 1 ? "after (hidden parts left out)"
                                     : "variant (wholly visible patches first)");
    print("all lit vertices", test::vertex_errors(l, ref));
    print("touched by the change", test::vertex_errors(l, ref, &touched));
    print("lamp's penumbra (not touched)", test::vertex_errors(l, ref, &penumbra));
    print("the rest", test::vertex_errors(l, ref, &rest));
  }
  if (!csv.empty()) {
    std::ofstream out(csv);
    out << "vertex,x,y,z,ref_r,ref_g,ref_b,before_r,before_g,before_b,after_r,after_g,after_b,"
           "touched,penumbra\n";
    for (std::size_t v = 0; v < n; ++v) {
      if (!ref.compared[v]) continue;
      out << v << ',' << s.positions[v].x << ',' << s.positions[v].y << ',' << s.positions[v].z;
      for (int c = 0; c < 3; ++c) out << ',' << ref.radiance[v][c];
      for (int c = 0; c < 3; ++c) out << ',' << before[3 * v + c];
      for (int c = 0; c < 3; ++c) out << ',' << after[3 * v + c];
      out << ',' << touched[v] << ',' << penumbra[v] << '\n';
    }
  }
  return 0;
}
