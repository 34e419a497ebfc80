// `prt report --translucency`: the approximations against the dipole bake (see
// report/translucency_report.h).
#include "report/translucency_report.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "bake/subsurface/subsurface_baker.h"
#include "bake/subsurface_approx/subsurface_approximations.h"
#include "prt/formats/transfer_file.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/environment_input.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/translucent_scene.h"
#include "translucency_report_outputs.h"

namespace prt::report {
namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The rotation (row-major) taking unit a to unit b (Rodrigues; a half turn about an axis ⊥ a
// when they are opposite).
std::array<double, 9> rotation_between(glm::dvec3 a, glm::dvec3 b) {
  glm::dvec3 axis = glm::cross(a, b);
  double s = glm::length(axis), c = glm::dot(a, b);
  if (s < 1e-12) {
    if (c > 0) return {1, 0, 0, 0, 1, 0, 0, 0, 1};
    axis = glm::normalize(
        glm::cross(a, std::fabs(a.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0)));
    s = 0;
    c = -1;
  } else {
    axis /= s;
  }
  const double t = 1 - c, x = axis.x, y = axis.y, z = axis.z;
  return {t * x * x + c,     t * x * y - s * z, t * x * z + s * y, t * x * y + s * z, t * y * y + c,
          t * y * z - s * x, t * x * z - s * y, t * y * z + s * x, t * z * z + c};
}

struct Lightings {
  std::vector<std::string> names;
  std::vector<ShLighting> lighting;
  glm::dvec3 dominant{0, 1, 0};
};

Lightings make_lightings(const TranslucencyReportOptions& o) {
  relight::EnvironmentUse use;
  use.sh_order = o.order;
  const relight::EnvironmentInput env =
      relight::read_checked_environment(o.environment_path, o.layout, use);
  Result<ShLighting> base = ShLighting::from_env_map(env.env, o.order);
  if (!base.ok()) throw std::runtime_error(o.environment_path + ": " + base.status().message());
  Lightings out;
  if (o.order >= 2) {  // the l = 1 band of the luminance: (x, y, z) ↔ k = 3, 1, 2
    const double w[3] = {0.2126, 0.7152, 0.0722};
    glm::dvec3 d(0);
    for (int c = 0; c < 3; ++c) {
      const double* l = base.value().coefficients_double(c);
      d += w[c] * glm::dvec3(l[3], l[1], l[2]);
    }
    if (glm::length(d) > 0) out.dominant = glm::normalize(d);
  }
  const double e = 20.0 * 3.14159265358979323846 / 180.0;
  const std::pair<const char*, glm::dvec3> targets[] = {{"back", {0, std::sin(e), -std::cos(e)}},
                                                        {"front", {0, std::sin(e), std::cos(e)}}};
  for (const auto& [name, target] : targets) {
    ShLighting l = base.value();
    const Status s = l.rotate(rotation_between(out.dominant, target));
    if (!s.ok()) throw std::runtime_error(o.environment_path + ": " + s.message());
    out.names.push_back(name);
    out.lighting.push_back(std::move(l));
  }
  return out;
}

// Exit radiance per vertex and channel (3 per vertex), B_c = Σ_k T_c,k L_c,k.
std::vector<double> relight_vertices(const prt::TransferData& t, const ShLighting& l) {
  const std::size_t kc = t.coefficients_per_channel();
  std::vector<double> b(t.vertex_count * 3, 0.0);
  for (std::size_t v = 0; v < t.vertex_count; ++v)
    for (int c = 0; c < 3; ++c) {
      const int tc = t.channels == 3 ? c : 0;
      const double* lc = l.coefficients_double(c);
      double s = 0;
      for (std::size_t k = 0; k < kc; ++k)
        s += double(t.coefficients[(v * t.channels + tc) * kc + k]) * lc[k];
      b[v * 3 + c] = s;
    }
  return b;
}

double relative_rms(const std::vector<double>& b, const std::vector<double>& ref,
                    const std::vector<char>& use) {
  double num = 0, den = 0;
  for (std::size_t v = 0; v < use.size(); ++v)
    if (use[v])
      for (int c = 0; c < 3; ++c) {
        const double d = b[v * 3 + c] - ref[v * 3 + c];
        num += d * d;
        den += ref[v * 3 + c] * ref[v * 3 + c];
      }
  return den > 0 ? std::sqrt(num / den) : 0.0;
}

subsurface::DipoleCoefficients preset_coefficients(const std::string& name) {
  Result<subsurface::SubsurfaceMaterial> m = subsurface::find_subsurface_preset(name);
  if (!m.ok()) throw std::runtime_error("--subsurface: " + m.status().message());
  return m.value().coefficients;
}

bake::BakeOptions shadowed_options(int order, int samples, uint64_t seed, uint64_t memory_limit) {
  bake::BakeOptions b;
  b.memory_limit = memory_limit;
  b.kind = prt::TransferKind::Shadowed;
  b.order = order;
  b.samples = samples;
  b.seed = seed;
  return b;
}

void write_transfer(const TranslucencyReportOptions& o, const std::string& scene_path,
                    const std::string& kind, const prt::TransferData& t,
                    TranslucencyReportResult& result) {
  const std::string path =
      (std::filesystem::path(o.output_dir) / translucency_transfer_name(scene_path, kind)).string();
  const Status s = prt::write_transfer_file(path, t);
  if (!s.ok()) throw std::runtime_error(path + ": " + s.message());
  result.files_written.push_back(path);
}

// The parts of one scene: every translucent primitive and "all".
void measure_scene(const TranslucencyReportOptions& o, const TranslucencyScene& ts,
                   const Lightings& lightings, TranslucencyReportResult& result) {
  const scene::Scene scene = scene::load_scene(ts.path);
  const std::string label = std::filesystem::path(ts.path).filename().string();
  std::vector<int32_t> group = bake::translucent_groups(scene);
  const std::vector<int32_t> opaque = o.opaque.empty() ? std::vector<int32_t>(group.size(), -1)
                                                       : bake::translucent_groups(scene, o.opaque);
  for (std::size_t v = 0; v < group.size(); ++v)
    if (opaque[v] >= 0) group[v] = -1;
  bake::SubsurfaceBakeOptions sub;
  sub.materials = {preset_coefficients(o.preset)};
  sub.mm_per_unit = ts.mm_per_unit > 0 ? ts.mm_per_unit : bake::default_mm_per_unit(scene);
  sub.vertex_material.resize(group.size());
  for (std::size_t v = 0; v < group.size(); ++v) sub.vertex_material[v] = group[v] >= 0 ? 0 : -1;
  if (o.log) o.log(label + ": dipole bake");
  const bake::BakeOptions bo = shadowed_options(o.order, o.samples, o.seed, o.memory_limit);
  const bake::SubsurfaceBakeResult dipole = bake::bake_subsurface_transfer(scene, bo, sub);
  write_transfer(o, ts.path, "dipole", dipole.bake.data, result);
  bake::BakeOptions so = bo;
  so.keep_albedo_apart = true;
  const prt::TransferData shadowed = bake::bake_transfer(scene, so).data;
  const scene::RayCaster caster(scene);
  bake::SubsurfaceApproximationInputs in;
  in.scene = &scene;
  in.caster = &caster;
  Result<subsurface::DipoleMaterial> m =
      subsurface::make_dipole(subsurface::scale_coefficients(sub.materials[0], sub.mm_per_unit));
  if (!m.ok()) throw std::runtime_error(m.status().message());
  in.material = m.value();
  in.group = group;
  in.shadowed = &shadowed;
  in.seed = o.seed;
  // The parts: "all" and each translucent primitive.
  // Vertices no triangle uses (zero area) are never drawn: left out of every part.
  const std::vector<double> areas = bake::vertex_areas(scene);
  std::vector<std::pair<std::string, std::vector<char>>> parts(1);
  parts[0].first = "all";
  parts[0].second.assign(group.size(), 0);
  for (std::size_t v = 0; v < group.size(); ++v) parts[0].second[v] = group[v] >= 0 && areas[v] > 0;
  for (const scene::ScenePrimitive& p : scene.primitives) {
    if (group[p.first_vertex] < 0 || scene.primitives.size() == 1) continue;
    std::vector<char> use(group.size(), 0);
    for (uint32_t v = p.first_vertex; v < p.first_vertex + p.vertex_count; ++v)
      use[v] = areas[v] > 0;
    parts.emplace_back(p.name, std::move(use));
  }
  for (bake::SubsurfaceApproximation a : bake::kAllApproximations) {
    if (o.log) o.log(label + ": " + bake::approximation_name(a));
    const prt::TransferData t = bake::approximate_subsurface(in, a);
    write_transfer(o, ts.path, bake::approximation_name(a), t, result);
    for (std::size_t li = 0; li < lightings.lighting.size(); ++li) {
      const std::vector<double> ref = relight_vertices(dipole.bake.data, lightings.lighting[li]);
      const std::vector<double> b = relight_vertices(t, lightings.lighting[li]);
      for (const auto& [part, use] : parts) {
        std::size_t count = 0;
        for (char u : use) count += u ? 1 : 0;
        result.errors.push_back({label, part, lightings.names[li], bake::approximation_name(a),
                                 count, relative_rms(b, ref, use)});
      }
    }
  }
}

// Lone marble spheres of growing size: the gathers' times.
void measure_timing(const TranslucencyReportOptions& o, TranslucencyReportResult& result) {
  const std::vector<int> rings =
      o.quick ? std::vector<int>{16, 32, 64} : std::vector<int>{16, 32, 64, 128};
  for (int r : rings) {
    scene::Scene s =
        scene::make_uv_sphere({0, 0, 0}, 10.f, r, 2 * r, false, glm::vec3(0.8f), "sphere");
    if (o.log) o.log("timing: " + std::to_string(s.positions.size()) + " vertices");
    TranslucencyTimingRow row;
    row.vertices = s.positions.size();
    bake::SubsurfaceBakeOptions sub;
    sub.materials = {preset_coefficients(o.preset)};
    sub.mm_per_unit = scene::kTranslucentMmPerUnit;
    const bake::BakeOptions bo = shadowed_options(3, 16, o.seed, o.memory_limit);
    const bake::SubsurfaceBakeResult h = bake::bake_subsurface_transfer(s, bo, sub);
    row.seconds_hierarchical = h.subsurface.seconds_gather;
    if (row.vertices <= kReferenceMaxVertices) {
      sub.gather.reference = true;
      const bake::SubsurfaceBakeResult ref = bake::bake_subsurface_transfer(s, bo, sub);
      row.seconds_reference = ref.subsurface.seconds_gather;
      double num = 0, den = 0;
      for (std::size_t i = 0; i < ref.bake.data.coefficients.size(); i += 9) {  // DC terms
        const double d = h.bake.data.coefficients[i] - ref.bake.data.coefficients[i];
        num += d * d;
        den += double(ref.bake.data.coefficients[i]) * ref.bake.data.coefficients[i];
      }
      row.reference_relative_rms = den > 0 ? std::sqrt(num / den) : 0;
    }
    bake::BakeOptions so = bo;
    so.keep_albedo_apart = true;
    const prt::TransferData shadowed = bake::bake_transfer(s, so).data;
    const scene::RayCaster caster(s);
    bake::SubsurfaceApproximationInputs in;
    in.scene = &s;
    in.caster = &caster;
    in.material = subsurface::make_dipole(sub.materials[0]).value();
    in.group = bake::translucent_groups(s);
    in.shadowed = &shadowed;
    const auto start = std::chrono::steady_clock::now();
    bake::approximate_subsurface(in, bake::SubsurfaceApproximation::kMeshDiffusion);
    row.seconds_mesh_diffusion = seconds_since(start);
    result.timing.push_back(row);
  }
}

}  // namespace

TranslucencyReportResult run_translucency_report(const TranslucencyReportOptions& o) {
  if (o.scenes.empty()) throw std::runtime_error("--translucency: no scene");
  preset_coefficients(o.preset);  // refuse an unknown preset before any work
  const Lightings lightings = make_lightings(o);
  TranslucencyReportResult result;
  std::filesystem::create_directories(o.output_dir);
  for (const TranslucencyScene& s : o.scenes) measure_scene(o, s, lightings, result);
  measure_timing(o, result);
  write_translucency_outputs(o, lightings.dominant, result);
  return result;
}

}  // namespace prt::report
