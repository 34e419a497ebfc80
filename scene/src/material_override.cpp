#include "scene/material_override.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <stdexcept>

#include "prt/brdf/energy_check.h"

namespace prt::scene {
namespace {

using brdf::Material;
using brdf::MaterialModel;

class OverrideParser {
 public:
  OverrideParser(const std::string& text, const std::string& option)
      : text_(text), option_(option) {}

  [[noreturn]] void fail(const std::string& problem) const {
    throw std::invalid_argument(option_ + " " + text_ + ": " + problem);
  }

  MaterialOverride parse() {
    MaterialOverride out;
    static_cast<MaterialAssignment&>(out) =
        parse_material_assignment(option_, text_, AssignedValue::Brdf);
    const std::string& rest = out.value;
    const std::size_t colon = rest.find(':');
    const std::string model = rest.substr(0, colon);
    const std::string args = colon == std::string::npos ? "" : rest.substr(colon + 1);
    if (model == "merl") {
      if (args.empty()) fail("merl needs a file: NAME=merl:FILE");
      out.material.model = MaterialModel::kMerl;
      out.material.merl_path = args;
    } else {
      read_pairs(args);
      build(model, out);
      for (const auto& [key, used] : used_)
        if (!used) fail("unknown key '" + key + "' for " + model);
    }
    const Result<std::shared_ptr<const brdf::Brdf>> made = brdf::make_brdf(out.material);
    if (!made) fail(made.status().message());
    const Status energy = brdf::check_energy_conservation(out.material);
    if (!energy) fail("material '" + out.name + "' " + energy.message());
    return out;
  }

 private:
  void read_pairs(const std::string& args) {
    std::size_t start = 0;
    while (start <= args.size() && !args.empty()) {
      const std::size_t comma = std::min(args.find(',', start), args.size());
      const std::string pair = args.substr(start, comma - start);
      const std::size_t eq = pair.find('=');
      if (eq == std::string::npos || eq == 0) fail("'" + pair + "' is not KEY=VALUE");
      const std::string key = pair.substr(0, eq);
      if (values_.count(key)) fail("key '" + key + "' given twice");
      values_[key] = pair.substr(eq + 1);
      used_[key] = false;
      start = comma + 1;
    }
  }

  bool has(const char* key) const { return values_.count(key) > 0; }

  double number(const char* key, double fallback) {
    if (!has(key)) return fallback;
    used_[key] = true;
    return to_number(key, values_.at(key));
  }

  double to_number(const std::string& key, const std::string& text) const {
    char* end = nullptr;
    const double v = std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size())
      fail(key + " '" + text + "' is not a number");
    return v;  // NaN and infinities reach make_brdf's range checks
  }

  brdf::Rgb colour(const char* key, const brdf::Rgb& fallback) {
    if (!has(key)) return fallback;
    used_[key] = true;
    const std::string& text = values_.at(key);
    std::vector<double> parts;
    std::size_t start = 0;
    for (;;) {
      const std::size_t slash = text.find('/', start);
      parts.push_back(to_number(key, text.substr(start, slash - start)));
      if (slash == std::string::npos) break;
      start = slash + 1;
    }
    if (parts.size() == 1) return brdf::grey(parts[0]);
    if (parts.size() != 3) fail(std::string(key) + " '" + text + "': expected one value or r/g/b");
    return brdf::Rgb{parts[0], parts[1], parts[2]};
  }

  std::string word(const char* key, const std::string& fallback) {
    if (!has(key)) return fallback;
    used_[key] = true;
    return values_.at(key);
  }

  void require(const char* key, const std::string& model) const {
    if (!has(key)) fail(model + " needs " + key);
  }

  // α_x, α_y from ax/ay/alpha (and, for microfacets, roughness r: α = r²).
  void alphas(Material& m, const std::string& model, bool roughness_key) {
    const int given = int(has("alpha")) + int(has("ax")) + int(roughness_key && has("roughness"));
    if (given == 0) fail(model + " needs alpha, ax" + (roughness_key ? " or roughness" : ""));
    if (given > 1)
      fail("give only one of alpha, ax" + std::string(roughness_key ? ", roughness" : ""));
    double a = number("alpha", std::nan(""));
    if (has("ax")) a = number("ax", 0.0);
    if (roughness_key && has("roughness")) {
      const double r = number("roughness", 0.0);
      a = r * r;
    }
    m.alpha_x = a;
    m.alpha_y = number("ay", a);
  }

  void build(const std::string& model, MaterialOverride& out) {
    Material& m = out.material;
    if (model == "lambert") {
      m.model = MaterialModel::kLambert;
      if (has("albedo") && has("kd")) fail("give kd or albedo, not both");
      out.set_albedo = has("kd") || has("albedo");
      m.diffuse = colour(has("kd") ? "kd" : "albedo", m.diffuse);
    } else if (model == "blinn-phong") {
      require("ks", model);
      require("s", model);
      m.model = MaterialModel::kBlinnPhong;
      m.diffuse = colour("kd", brdf::grey(0.0));
      m.specular = colour("ks", brdf::grey(0.0));
      m.exponent = number("s", 0.0);
    } else if (model == "ward") {
      require("rho_s", model);
      m.model = MaterialModel::kWard;
      m.diffuse = colour("rho_d", brdf::grey(0.0));
      m.specular = colour("rho_s", brdf::grey(0.0));
      alphas(m, model, false);
      const std::string form = word("form", "normalized");
      if (form == "normalized")
        m.ward_form = brdf::WardForm::kNormalized;
      else if (form == "duer")
        m.ward_form = brdf::WardForm::kDuer;
      else if (form == "original")
        m.ward_form = brdf::WardForm::kOriginal;
      else
        fail("form '" + form + "': expected normalized, duer or original");
    } else if (model == "ggx" || model == "beckmann") {
      m.model = MaterialModel::kMicrofacet;
      m.distribution =
          model == "ggx" ? brdf::NormalDistribution::kGgx : brdf::NormalDistribution::kBeckmann;
      m.diffuse = colour("kd", brdf::grey(0.0));
      m.specular = colour("f0", brdf::grey(0.04));
      alphas(m, model, true);
      const std::string fresnel = word("fresnel", "schlick");
      if (fresnel == "schlick")
        m.fresnel = brdf::FresnelMode::kSchlick;
      else if (fresnel == "dielectric")
        m.fresnel = brdf::FresnelMode::kDielectric;
      else if (fresnel == "none")
        m.fresnel = brdf::FresnelMode::kNone;
      else
        fail("fresnel '" + fresnel + "': expected schlick, dielectric or none");
      m.eta = number("eta", 1.5);
    } else if (model == "gltf" || model == "gltf-additive") {
      gltf(model, m);
    } else {
      fail("unknown model '" + model +
           "' (expected lambert, blinn-phong, ward, ggx, beckmann, gltf, gltf-additive or merl)");
    }
  }

  // glTF metallic-roughness from base, metallic (default 0), roughness (α = r²): the spec's mix
  // (gltf) or F0 = mix(0.04, base, metallic) over an added Lambert layer base·(1 − metallic)
  // (gltf-additive).
  void gltf(const std::string& model, Material& m) {
    require("base", model);
    require("roughness", model);
    const brdf::Rgb base = colour("base", brdf::grey(1.0));
    const double metallic = number("metallic", 0.0);
    const double r = number("roughness", 0.0);
    m.alpha_x = m.alpha_y = r * r;
    m.distribution = brdf::NormalDistribution::kGgx;
    m.fresnel = brdf::FresnelMode::kSchlick;
    if (model == "gltf") {
      m.model = MaterialModel::kGltf;
      m.diffuse = base;
      m.metallic = metallic;
      m.specular = brdf::grey(0.04);
      return;
    }
    if (!(metallic >= 0.0 && metallic <= 1.0)) fail("metallic must be in [0, 1]");
    m.model = MaterialModel::kMicrofacet;
    m.diffuse = (1.0 - metallic) * base;
    m.specular = (1.0 - metallic) * brdf::grey(0.04) + metallic * base;
  }

  const std::string& text_;
  const std::string& option_;
  std::map<std::string, std::string> values_;
  std::map<std::string, bool> used_;
};

std::string rgb_text(const glm::vec3& c) {
  char text[64];
  if (c.x == c.y && c.y == c.z)
    std::snprintf(text, sizeof text, "%.3g", double(c.x));
  else
    std::snprintf(text, sizeof text, "%.3g,%.3g,%.3g", double(c.x), double(c.y), double(c.z));
  return text;
}

}  // namespace

MaterialOverride parse_material_override(const std::string& text, const std::string& option) {
  return OverrideParser(text, option).parse();
}

void apply_material_overrides(Scene& scene, const std::vector<MaterialOverride>& overrides) {
  for (const MaterialOverride& o : overrides) {
    std::vector<ScenePrimitive*> matched;
    for (std::size_t i : matched_primitives(scene, o)) matched.push_back(&scene.primitives[i]);
    for (ScenePrimitive* p : matched) {
      p->anisotropy_rotation = 0.f;
      p->anisotropy_rotation_of_vertex.clear();
      p->brdf_textured.clear();
      p->brdf_variants.clear();  // the override replaces the textured parameters too
      p->brdf_variant_of_vertex.clear();
      p->brdf_texture_problem.clear();
      if (!o.material.lambertian()) {
        p->brdf = o.material;
        continue;
      }
      p->brdf.reset();
      if (!o.set_albedo) continue;
      const brdf::Rgb& kd = o.material.diffuse;
      p->albedo = glm::vec3(float(kd.r), float(kd.g), float(kd.b));
      p->base_color_texture.reset();
      const std::size_t end = std::min<std::size_t>(scene.albedo.size(),
                                                    std::size_t(p->first_vertex) + p->vertex_count);
      for (std::size_t v = p->first_vertex; v < end; ++v) scene.albedo[v] = p->albedo;
    }
  }
}

std::vector<std::string> describe_materials(const Scene& scene) {
  std::vector<std::string> lines;
  for (const ScenePrimitive& p : scene.primitives) {
    std::string line = p.name;
    if (!p.material.empty()) line += " (material " + p.material + ")";
    line += ": " + (p.brdf ? brdf::describe(*p.brdf) : "lambert(" + rgb_text(p.albedo) + ")");
    if (p.base_color_texture) line += ", textured";
    if (!p.brdf_variants.empty())
      line += ", " + (p.brdf_textured.empty() ? std::string("parameters") : p.brdf_textured) +
              " textured: " + std::to_string(p.brdf_variants.size()) + " variants";
    if (!p.anisotropy_rotation_of_vertex.empty())
      line += ", anisotropy direction textured (tangent rotated per vertex)";
    if (!p.brdf_texture_problem.empty()) line += "; not used: " + p.brdf_texture_problem;
    if (p.anisotropy_rotation != 0.f) {
      char text[48];
      std::snprintf(text, sizeof text, ", tangent rotated %.3g rad", double(p.anisotropy_rotation));
      line += text;
    }
    lines.push_back(line);
  }
  return lines;
}

}  // namespace prt::scene
