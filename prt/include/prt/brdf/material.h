// prt/brdf/material.h — a BRDF as a value: which model and its parameters, as a scene file or
// the command line describes a material; make_brdf() turns it into a prt::brdf::Brdf.
//
// Conventions: those of prt/brdf/brdf.h (local frame: +z normal, +x tangent = the α_x
// direction, +y bitangent). Colours are linear RGB. A Material is cheap to copy and compare,
// so scenes, coefficient files and the command line can carry it; the Brdf it makes is built
// once per material and shared.
// Compiles as C++17.
#pragma once

#include <memory>
#include <string>

#include "prt/brdf/brdf.h"
#include "prt/brdf/microfacet.h"
#include "prt/brdf/ward.h"
#include "prt/core/status.h"

namespace prt::brdf {

enum class MaterialModel {
  kLambert,     // diffuse = reflectance
  kBlinnPhong,  // diffuse = k_L, specular = k_G, exponent = s
  kWard,        // diffuse = ρ_d, specular = ρ_s, alpha_x/alpha_y, ward_form
  kMicrofacet,  // diffuse = a Lambert layer added to the lobe (0 for a pure metal),
                // specular = F0 (Schlick), alpha_x/alpha_y, distribution, fresnel
  kMerl,        // merl_path: a MERL binary file
  kGltf,        // glTF 2.0 metallic-roughness as Appendix B mixes it (prt/brdf/gltf_pbr.h):
                // diffuse = baseColor, specular = the dielectric F0, metallic, alpha_x/alpha_y
                // (GGX, Schlick)
};

struct Material {
  MaterialModel model = MaterialModel::kLambert;
  Rgb diffuse = grey(0.8);
  Rgb specular = grey(0.0);
  double exponent = 0;  // Blinn-Phong
  double alpha_x = 0.5, alpha_y = 0.5;
  WardForm ward_form = WardForm::kNormalized;
  NormalDistribution distribution = NormalDistribution::kGgx;
  FresnelMode fresnel = FresnelMode::kSchlick;
  double eta = 1.5;       // FresnelMode::kDielectric
  double metallic = 0.0;  // kGltf
  std::string merl_path;

  // True for a pure Lambert material (the diffuse path applies unchanged).
  bool lambertian() const { return model == MaterialModel::kLambert; }
  // True when f depends on the azimuth of ωi and ωo about the normal only through their
  // difference (Lambert, Blinn-Phong, MERL, and Ward or microfacet with α_x = α_y).
  bool isotropic() const;
};

// A short description, e.g. "ggx(alpha 0.30x0.10, F0 0.95,0.64,0.54)", for logs and metadata.
std::string describe(const Material& material);

// Builds the BRDF. Errors (one line, no exception): the model's own parameter checks
// (a roughness of 0 or NaN, a negative exponent, …) and, for kMerl, the file's.
// A Lambert-plus-lobe microfacet material is the sum of the two BRDFs. make_brdf does not check
// energy: prt/brdf/energy_check.h does, once per material, where materials enter prt.
Result<std::shared_ptr<const Brdf>> make_brdf(const Material& material);

}  // namespace prt::brdf
