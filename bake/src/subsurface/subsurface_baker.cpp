// Diffuse SH transfer with subsurface scattering (bake/subsurface/subsurface_baker.h).
#include "bake/subsurface/subsurface_baker.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include "scene/scene_label.h"

namespace prt::bake {
namespace {

using Clock = std::chrono::steady_clock;

constexpr double kMaxTranslucentAlbedo = 0.999;  // the solve's ρ < 1 rule

}  // namespace

void validate_subsurface(const scene::Scene& scene, const BakeOptions& options,
                         const SubsurfaceBakeOptions& ss) {
  const std::string name = scene::scene_label(scene);
  if (options.kind != prt::TransferKind::Shadowed &&
      options.kind != prt::TransferKind::Interreflected)
    throw BakeError(name + ": subsurface transfer is shadowed or interreflected, not " +
                    transfer_kind_name(options.kind));
  if (options.adaptive.enabled)
    throw BakeError(name + ": subsurface transfer does not take adaptive sampling");
  if (scene.textured())
    throw BakeError(name +
                    ": subsurface transfer needs an untextured scene (a base-colour "
                    "texture is present)");
  if (ss.materials.empty()) throw BakeError(name + ": no subsurface material given");
  for (std::size_t m = 0; m < ss.materials.size(); ++m)
    if (Status s = subsurface::validate(ss.materials[m]); !s)
      throw BakeError(name + ": subsurface material " + std::to_string(m) + ": " + s.message());
  if (!ss.vertex_material.empty() && ss.vertex_material.size() != scene.positions.size())
    throw BakeError(name + ": one subsurface material index per vertex is needed");
  for (int32_t m : ss.vertex_material)
    if (m < -1 || m >= static_cast<int32_t>(ss.materials.size()))
      throw BakeError(name + ": subsurface material index " + std::to_string(m) +
                      " is out of range");
  if (!(ss.mm_per_unit >= 0) || !std::isfinite(ss.mm_per_unit))
    throw BakeError(name + ": the subsurface scale (mm per scene unit) must be finite and > 0");
  if (!(ss.gather.epsilon > 0) || !std::isfinite(ss.gather.epsilon))
    throw BakeError(name + ": the subsurface epsilon must be finite and > 0");
}

namespace {

// The samples without their transfer: positions, areas and materials per vertex.
SubsurfaceSamples make_samples(const scene::Scene& scene, const SubsurfaceBakeOptions& ss, int K) {
  SubsurfaceSamples s;
  const std::size_t V = scene.positions.size();
  s.positions.resize(V);
  for (std::size_t v = 0; v < V; ++v) s.positions[v] = glm::dvec3(scene.positions[v]);
  s.areas = vertex_areas(scene);
  s.material = ss.vertex_material.empty() ? std::vector<int32_t>(V, 0) : ss.vertex_material;
  // A vertex of no triangle has no area: it is no source and receives nothing.
  for (std::size_t v = 0; v < V; ++v)
    if (!(s.areas[v] > 0)) s.material[v] = -1;
  s.K = K;
  return s;
}

// The dipoles of the materials at the scale in use (mm per scene unit).
std::vector<subsurface::DipoleMaterial> make_dipoles(const SubsurfaceBakeOptions& ss,
                                                     double mm_per_unit) {
  std::vector<subsurface::DipoleMaterial> materials;
  for (const subsurface::DipoleCoefficients& c : ss.materials)
    materials.push_back(*subsurface::make_dipole(subsurface::scale_coefficients(c, mm_per_unit)));
  return materials;
}

// subsurface_solve_scene with the vertices' materials (−1 opaque) and the dipoles given.
scene::Scene with_translucent_albedo(const scene::Scene& scene,
                                     const std::vector<int32_t>& material,
                                     const std::vector<subsurface::DipoleMaterial>& materials) {
  scene::Scene solve_scene = scene;
  for (std::size_t v = 0; v < scene.positions.size(); ++v) {
    if (material[v] < 0) continue;
    const subsurface::DipoleMaterial& m = materials[static_cast<std::size_t>(material[v])];
    for (int c = 0; c < 3; ++c)
      solve_scene.albedo[v][c] =
          static_cast<float>(std::min(m.channels[c].total(), kMaxTranslucentAlbedo));
  }
  return solve_scene;
}

// The exit transfer of every vertex, V × 3 × K: the subsurface sum for translucent vertices,
// ρ_c·S for the others.
std::vector<double> exit_transfer(const scene::Scene& scene, SubsurfaceSamples& samples,
                                  const std::vector<subsurface::DipoleMaterial>& materials,
                                  const SubsurfaceGatherOptions& gather,
                                  SubsurfaceBakeStatistics& st) {
  const Clock::time_point t0 = Clock::now();
  std::vector<double> x = gather_subsurface(samples, materials, gather, &st.gather);
  st.seconds_gather = std::chrono::duration<double>(Clock::now() - t0).count();
  const std::size_t K = static_cast<std::size_t>(samples.K);
  for (std::size_t v = 0; v < samples.positions.size(); ++v) {
    if (samples.material[v] >= 0) continue;
    for (int c = 0; c < 3; ++c)
      for (std::size_t k = 0; k < K; ++k)
        x[(v * 3 + c) * K + k] = scene.albedo[v][c] * samples.transfer[v * K + k];
  }
  return x;
}

void add_metadata(prt::TransferData& data, const SubsurfaceBakeOptions& ss,
                  const SubsurfaceBakeStatistics& st) {
  nlohmann::json meta = data.metadata_json.empty()
                            ? nlohmann::json::object()
                            : nlohmann::json::parse(data.metadata_json, nullptr, false);
  if (meta.is_discarded()) meta = nlohmann::json::object();
  // The file holds 3-channel transfer with the albedo folded, whatever the inner bake said.
  meta["channels"] = 3;
  meta["albedo_folded"] = true;
  meta.erase("albedo_kept_apart");
  nlohmann::json sub;
  sub["model"] = "dipole (Jensen et al. 2001), straight-line distances";
  sub["mm_per_unit"] = st.mm_per_unit;
  sub["evaluation"] = ss.gather.reference ? "direct" : "hierarchical";
  if (!ss.gather.reference) sub["epsilon"] = ss.gather.epsilon;
  sub["energy_clamp"] = ss.gather.energy_clamp;
  sub["translucent_vertices"] = st.translucent_vertices;
  nlohmann::json mats = nlohmann::json::array();
  for (const subsurface::DipoleCoefficients& c : ss.materials) {
    nlohmann::json m;
    m["sigma_a_per_mm"] = c.sigma_a;
    m["sigma_s_prime_per_mm"] = c.sigma_s_prime;
    m["eta"] = c.eta;
    mats.push_back(m);
  }
  sub["materials"] = mats;
  meta["subsurface"] = sub;
  data.metadata_json = meta.dump();
}

}  // namespace

double default_mm_per_unit(const scene::Scene& scene) {
  if (scene.positions.empty()) return 1.0;
  glm::dvec3 lo(scene.positions[0]), hi(scene.positions[0]);
  for (const glm::vec3& p : scene.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const double diagonal = glm::distance(lo, hi);
  return diagonal > 0 ? 100.0 / diagonal : 1.0;
}

std::vector<double> vertex_areas(const scene::Scene& scene) {
  std::vector<double> areas(scene.positions.size(), 0.0);
  for (const glm::uvec3& t : scene.triangles) {
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    const double third = glm::length(glm::cross(b - a, c - a)) / 6.0;
    areas[t.x] += third;
    areas[t.y] += third;
    areas[t.z] += third;
  }
  return areas;
}

scene::Scene subsurface_solve_scene(const scene::Scene& scene, const SubsurfaceBakeOptions& ss) {
  const double mm_per_unit = ss.mm_per_unit > 0 ? ss.mm_per_unit : default_mm_per_unit(scene);
  return with_translucent_albedo(scene, make_samples(scene, ss, 1).material,
                                 make_dipoles(ss, mm_per_unit));
}

SubsurfaceBakeResult bake_subsurface_transfer(const scene::Scene& scene, const BakeOptions& options,
                                              const SubsurfaceBakeOptions& ss,
                                              ProgressSink* progress) {
  return bake_subsurface_transfer_with(scene, options, ss,
                                       [progress](const scene::Scene& s, const BakeOptions& o) {
                                         return bake_transfer(s, o, progress);
                                       });
}

SubsurfaceBakeResult bake_subsurface_transfer_with(const scene::Scene& scene,
                                                   const BakeOptions& options,
                                                   const SubsurfaceBakeOptions& ss,
                                                   const TransferBakeFunction& bake) {
  validate_subsurface(scene, options, ss);
  const Clock::time_point t_start = Clock::now();
  SubsurfaceBakeResult result;
  SubsurfaceBakeStatistics& st = result.subsurface;
  st.mm_per_unit = ss.mm_per_unit > 0 ? ss.mm_per_unit : default_mm_per_unit(scene);
  const std::vector<subsurface::DipoleMaterial> materials = make_dipoles(ss, st.mm_per_unit);
  const int K = options.order * options.order;
  SubsurfaceSamples samples = make_samples(scene, ss, K);
  for (int32_t m : samples.material) st.translucent_vertices += m >= 0 ? 1 : 0;

  if (options.kind == prt::TransferKind::Shadowed) {
    BakeOptions o = options;
    o.keep_albedo_apart = true;  // S alone, one channel
    o.precision = prt::Precision::F32;
    result.bake = bake(scene, o);
    samples.transfer.assign(result.bake.data.coefficients.begin(),
                            result.bake.data.coefficients.end());
    const std::vector<double> x = exit_transfer(scene, samples, materials, ss.gather, st);
    prt::TransferData& data = result.bake.data;
    data.channels = 3;
    data.albedo_folded = true;
    data.storage = options.precision;
    data.coefficients.assign(x.begin(), x.end());
  } else {
    // The solve's albedo: R_total for translucent vertices (their local response to bounce
    // light), the scene's for the others.
    const scene::Scene solve_scene = with_translucent_albedo(scene, samples.material, materials);
    BakeOptions o = options;
    o.direct_override = [&](const std::vector<double>& s) {
      samples.transfer = s;
      return exit_transfer(scene, samples, materials, ss.gather, st);
    };
    result.bake = bake(solve_scene, o);
  }
  add_metadata(result.bake.data, ss, st);
  result.bake.stats.seconds_total = std::chrono::duration<double>(Clock::now() - t_start).count();
  return result;
}

}  // namespace prt::bake
