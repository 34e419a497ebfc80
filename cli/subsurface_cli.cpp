// The subsurface options of `prt bake` (cli/subsurface_cli.h).
#include "subsurface_cli.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "bake/subsurface/subsurface_baker.h"
#include "cli_parsing.h"
#include "command_registry.h"
#include "prt/formats/transfer_file.h"
#include "prt/subsurface/dipole.h"
#include "run_record.h"
#include "scene/material_assignment.h"
#include "subsurface_gltf.h"

namespace prt::cli {
namespace {

// The --subsurface value that takes each material's coefficients from its glTF extensions.
constexpr const char* kFromGltf = "gltf";

subsurface::Rgb parse_rgb(const std::string& option, const std::string& text) {
  std::vector<double> v = parse_number_list(option, text);
  if (v.size() == 1) v = {v[0], v[0], v[0]};
  if (v.size() != 3) throw UsageError(option + " " + text + ": expected r,g,b or one value");
  return {v[0], v[1], v[2]};
}

void require_positive(const std::string& option, const std::string& text,
                      const subsurface::Rgb& v) {
  for (double x : v)
    if (!(x > 0) || !std::isfinite(x))
      throw UsageError(option + " " + text + ": every component must be finite and > 0");
}

// The coefficients `custom` stands for (mm⁻¹).
subsurface::DipoleCoefficients custom_coefficients(const SubsurfaceArguments& a) {
  const double eta = a.eta.value_or(1.3);
  if (!a.color.empty()) {
    const subsurface::Rgb color = parse_rgb("--subsurface-color", a.color);
    const subsurface::Rgb mfp = parse_rgb("--mean-free-path", a.mean_free_path);
    for (double x : color)
      if (!(x > 0 && x < 1))
        throw UsageError("--subsurface-color " + a.color + ": every component must be in (0, 1)");
    require_positive("--mean-free-path", a.mean_free_path, mfp);
    Result<subsurface::DipoleCoefficients> c = subsurface::coefficients_from_color(color, mfp, eta);
    if (!c) throw UsageError("--subsurface custom: " + c.status().message());
    return *c;
  }
  subsurface::DipoleCoefficients c;
  c.sigma_a = parse_rgb("--sigma-a", a.sigma_a);
  c.sigma_s_prime = parse_rgb("--sigma-s", a.sigma_s);
  c.eta = eta;
  require_positive("--sigma-a", a.sigma_a, c.sigma_a);
  require_positive("--sigma-s", a.sigma_s, c.sigma_s_prime);
  return c;
}

subsurface::DipoleCoefficients material_of(const SubsurfaceArguments& a, const std::string& value,
                                           const std::string& text) {
  if (value == "custom") return custom_coefficients(a);
  Result<subsurface::SubsurfaceMaterial> p = subsurface::find_subsurface_preset(value);
  if (!p) throw UsageError("--subsurface " + text + ": " + p.status().message());
  subsurface::DipoleCoefficients c = p->coefficients;
  if (a.eta) c.eta = *a.eta;
  return c;
}

// The primitives among `primitives` whose glTF material has translucency extensions, and their
// coefficients (one material each); refuses a scene where none has them.
void assign_from_gltf(const scene::Scene& scene, const std::vector<std::size_t>& primitives,
                      const SubsurfaceArguments& a, const std::string& text,
                      bake::SubsurfaceBakeOptions* ss) {
  const double mm_per_unit = a.scale ? *a.scale : bake::default_mm_per_unit(scene);
  bool any = false;
  for (std::size_t p : primitives) {
    const scene::ScenePrimitive& prim = scene.primitives[p];
    if (!prim.translucency) continue;
    any = true;
    ss->materials.push_back(gltf_dipole_coefficients(scene.source_path, prim, mm_per_unit, a.eta));
    const int32_t index = static_cast<int32_t>(ss->materials.size() - 1);
    for (uint32_t v = prim.first_vertex; v < prim.first_vertex + prim.vertex_count; ++v)
      ss->vertex_material[v] = index;
  }
  if (!any)
    throw CommandError(scene.source_path + ": --subsurface " + text +
                       ": no material has KHR_materials_volume or "
                       "KHR_materials_diffuse_transmission");
}

// "VALUE" or "MATERIAL=VALUE": the name (empty: every primitive) and the value.
std::pair<std::string, std::string> split_assignment(const std::string& text) {
  const std::size_t eq = text.rfind('=');
  if (eq == std::string::npos) return {"", text};
  try {
    const scene::MaterialAssignment m =
        scene::parse_material_assignment("--subsurface", text, scene::AssignedValue::Colour);
    return {m.name, m.value};
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

}  // namespace

void add_subsurface_options(CLI::App* cmd, SubsurfaceArguments* a) {
  cmd->add_option(
         "--subsurface", a->subsurface,
         "Translucent: a preset of Jensen et al. 2001 (marble, skin1, skin2, wholemilk, "
         "skimmilk, ketchup, apple, chicken1, chicken2, cream, potato), custom, or gltf (the "
         "materials with KHR_materials_volume/_diffuse_transmission); "
         "MATERIAL=VALUE for one material (repeatable)")
      ->allow_extra_args(false);
  cmd->add_option("--sigma-a", a->sigma_a, "--subsurface custom: absorption r,g,b in 1/mm");
  cmd->add_option("--sigma-s", a->sigma_s, "--subsurface custom: reduced scattering r,g,b in 1/mm");
  cmd->add_option("--eta", a->eta, "--subsurface: relative index of refraction (>= 1; 1.3)");
  cmd->add_option("--subsurface-color", a->color,
                  "--subsurface custom: diffuse reflectance r,g,b in (0, 1), inverted");
  cmd->add_option("--mean-free-path", a->mean_free_path,
                  "--subsurface custom: diffuse mean free path 1/sigma_tr r,g,b in mm");
  cmd->add_option("--subsurface-scale", a->scale,
                  "--subsurface: millimetres per scene unit (default: bounding-box diagonal = "
                  "100 mm)");
  cmd->add_option("--subsurface-epsilon", a->epsilon,
                  "--subsurface: solid-angle criterion of the hierarchical sum (0.2)");
  cmd->add_flag("--subsurface-reference", a->reference,
                "--subsurface: the direct O(n^2) sum instead of the hierarchy (slow)");
}

void check_subsurface_usage(const SubsurfaceArguments& a, const CLI::App& cmd,
                            const std::string& other) {
  const auto given = [&cmd](const char* o) { return cmd.count(o) > 0; };
  const char* coefficient_options[] = {"--sigma-a", "--sigma-s", "--subsurface-color",
                                       "--mean-free-path"};
  const char* all_options[] = {"--eta", "--subsurface-scale", "--subsurface-epsilon",
                               "--subsurface-reference"};
  if (!a.given()) {
    for (const char* o : coefficient_options)
      if (given(o)) throw UsageError(std::string(o) + " applies to --subsurface custom only");
    for (const char* o : all_options)
      if (given(o)) throw UsageError(std::string(o) + " applies to --subsurface only");
    return;
  }
  if (!other.empty()) throw UsageError("--subsurface does not apply to " + other);
  bool custom = false;
  for (const std::string& text : a.subsurface) {
    const auto [name, value] = split_assignment(text);
    if (value == "custom") {
      custom = true;
      continue;
    }
    if (value == kFromGltf) continue;
    if (!subsurface::find_subsurface_preset(value).ok())
      throw UsageError("--subsurface " + text + ": " +
                       subsurface::find_subsurface_preset(value).status().message());
  }
  const bool by_sigma = given("--sigma-a") || given("--sigma-s");
  const bool by_color = given("--subsurface-color") || given("--mean-free-path");
  if (!custom) {
    for (const char* o : coefficient_options)
      if (given(o)) throw UsageError(std::string(o) + " applies to --subsurface custom only");
  } else {
    if (by_sigma && by_color)
      throw UsageError(
          "--sigma-a/--sigma-s and --subsurface-color/--mean-free-path are two ways "
          "to give the coefficients: use one");
    if (!by_sigma && !by_color)
      throw UsageError(
          "--subsurface custom needs --sigma-a and --sigma-s, or "
          "--subsurface-color and --mean-free-path");
    if (by_sigma && !(given("--sigma-a") && given("--sigma-s")))
      throw UsageError("--subsurface custom needs both --sigma-a and --sigma-s");
    if (by_color && !(given("--subsurface-color") && given("--mean-free-path")))
      throw UsageError("--subsurface custom needs both --subsurface-color and --mean-free-path");
    (void)custom_coefficients(a);  // refuses bad values now
  }
  if (a.eta && !(*a.eta >= 1 && std::isfinite(*a.eta)))
    throw UsageError("--eta " + std::to_string(*a.eta) + ": must be finite and >= 1");
  if (a.scale && !(*a.scale > 0 && std::isfinite(*a.scale)))
    throw UsageError("--subsurface-scale: must be a finite number of millimetres > 0");
  if (a.epsilon && !(*a.epsilon > 0 && std::isfinite(*a.epsilon)))
    throw UsageError("--subsurface-epsilon: must be finite and > 0");
  if (a.reference && a.epsilon)
    throw UsageError("--subsurface-epsilon does not apply to --subsurface-reference");
}

bake::SubsurfaceBakeOptions subsurface_bake_options(const scene::Scene& scene,
                                                    const SubsurfaceArguments& a) {
  bake::SubsurfaceBakeOptions ss;
  ss.vertex_material.assign(scene.positions.size(), -1);
  for (const std::string& text : a.subsurface) {
    const auto [name, value] = split_assignment(text);
    std::vector<std::size_t> primitives;
    if (name.empty()) {
      for (std::size_t p = 0; p < scene.primitives.size(); ++p) primitives.push_back(p);
    } else {
      scene::MaterialAssignment m;
      m.name = name;
      m.value = value;
      m.text = text;
      m.option = "--subsurface";
      try {
        primitives = scene::matched_primitives(scene, m);
      } catch (const std::invalid_argument& e) {
        throw UsageError(e.what());
      }
    }
    if (value == kFromGltf) {
      assign_from_gltf(scene, primitives, a, text, &ss);
      continue;
    }
    ss.materials.push_back(material_of(a, value, text));
    const int32_t index = static_cast<int32_t>(ss.materials.size() - 1);
    for (std::size_t p : primitives) {
      const scene::ScenePrimitive& prim = scene.primitives[p];
      for (uint32_t v = prim.first_vertex; v < prim.first_vertex + prim.vertex_count; ++v)
        ss.vertex_material[v] = index;
    }
  }
  ss.mm_per_unit = a.scale.value_or(0.0);
  if (a.epsilon) ss.gather.epsilon = *a.epsilon;
  ss.gather.reference = a.reference;
  return ss;
}

void run_subsurface_bake(const scene::Scene& scene, const std::string& output,
                         const bake::BakeOptions& options, const SubsurfaceArguments& a,
                         bool quiet) {
  const bake::SubsurfaceBakeOptions ss = subsurface_bake_options(scene, a);
  const bake::SubsurfaceBakeResult r = bake::bake_subsurface_transfer(scene, options, ss);
  const prt::Status written = prt::write_transfer_file(output, r.bake.data);
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("rays", r.bake.stats.seconds_rays);
  if (r.bake.stats.seconds_solve > 0)
    run_record().phase("interreflection solve", r.bake.stats.seconds_solve);
  run_record().phase("subsurface sum", r.subsurface.seconds_gather);
  run_record().phase("bake", r.bake.stats.seconds_total);
  if (quiet) return;
  std::printf(
      "baked %s subsurface transfer of %s: %llu vertices (%llu translucent), order %d, 3 "
      "channels; %.4g mm per scene unit%s; %s sum in %.2f s (%llu receivers clamped, largest "
      "response %.3f "
      "of R_total); rays "
      "%.2f s; wrote %s\n",
      bake::transfer_kind_name(options.kind), scene.source_path.c_str(),
      static_cast<unsigned long long>(r.bake.stats.vertices),
      static_cast<unsigned long long>(r.subsurface.translucent_vertices), options.order,
      r.subsurface.mm_per_unit, a.scale ? "" : " (bounding-box diagonal = 100 mm)",
      a.reference ? "direct" : "hierarchical", r.subsurface.seconds_gather,
      static_cast<unsigned long long>(r.subsurface.gather.clamped_receivers),
      r.subsurface.gather.largest_response, r.bake.stats.seconds_rays, output.c_str());
}

}  // namespace prt::cli
