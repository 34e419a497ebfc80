#include "prt/brdf/material.h"

#include <cstdio>
#include <utility>

#include "brdf/lobe_mix.h"
#include "prt/brdf/blinn_phong.h"
#include "prt/brdf/gltf_pbr.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/merl.h"

namespace prt::brdf {
namespace {

// A Lambert layer under a glossy lobe: f = f_diffuse + f_lobe. Sampling picks a lobe with
// probability proportional to the channel means of the diffuse reflectance and F0, and the
// pdf is the matching mixture, so f cos θ / pdf stays bounded where either lobe dominates.
class LayeredBrdf final : public Brdf {
 public:
  LayeredBrdf(Lambert diffuse, std::shared_ptr<const Brdf> lobe, double p_diffuse)
      : diffuse_(std::move(diffuse)), lobe_(std::move(lobe)), p_diffuse_(p_diffuse) {}

  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    return diffuse_.eval(wi, wo) + lobe_->eval(wi, wo);
  }
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override {
    const bool pick = detail::pick_diffuse(p_diffuse_, u1);
    BrdfSample s = pick ? diffuse_.sample(wo, u1, u2) : lobe_->sample(wo, u1, u2);
    if (s.pdf <= 0.0) return BrdfSample{};
    s.pdf = pdf(wo, s.wi);
    s.f = eval(s.wi, wo);
    return s;
  }
  double pdf(const Vec3& wo, const Vec3& wi) const override {
    return p_diffuse_ * diffuse_.pdf(wo, wi) + (1.0 - p_diffuse_) * lobe_->pdf(wo, wi);
  }
  bool reciprocal() const override { return lobe_->reciprocal(); }

 private:
  Lambert diffuse_;
  std::shared_ptr<const Brdf> lobe_;
  double p_diffuse_;
};

template <class T>
Result<std::shared_ptr<const Brdf>> share(Result<T> made) {
  if (!made) return made.status();
  return std::shared_ptr<const Brdf>(std::make_shared<T>(std::move(made).value()));
}

bool zero(const Rgb& c) {
  return c.r == 0.0 && c.g == 0.0 && c.b == 0.0;
}

std::string rgb_text(const Rgb& c) {
  char text[96];
  if (c.r == c.g && c.g == c.b)
    std::snprintf(text, sizeof text, "%.3g", c.r);
  else
    std::snprintf(text, sizeof text, "%.3g,%.3g,%.3g", c.r, c.g, c.b);
  return text;
}

}  // namespace

bool Material::isotropic() const {
  switch (model) {
    case MaterialModel::kWard:
    case MaterialModel::kMicrofacet:
    case MaterialModel::kGltf:
      return alpha_x == alpha_y;
    default:
      return true;
  }
}

std::string describe(const Material& m) {
  char text[160];
  switch (m.model) {
    case MaterialModel::kLambert:
      return "lambert(" + rgb_text(m.diffuse) + ")";
    case MaterialModel::kBlinnPhong:
      std::snprintf(text, sizeof text, "blinn-phong(kd %s, ks %s, s %.4g)",
                    rgb_text(m.diffuse).c_str(), rgb_text(m.specular).c_str(), m.exponent);
      return text;
    case MaterialModel::kWard:
      std::snprintf(text, sizeof text, "ward(rho_d %s, rho_s %s, alpha %.3gx%.3g)",
                    rgb_text(m.diffuse).c_str(), rgb_text(m.specular).c_str(), m.alpha_x,
                    m.alpha_y);
      return text;
    case MaterialModel::kMicrofacet:
      std::snprintf(text, sizeof text, "%s(alpha %.3gx%.3g, F0 %s, diffuse %s)",
                    distribution_name(m.distribution), m.alpha_x, m.alpha_y,
                    rgb_text(m.specular).c_str(), rgb_text(m.diffuse).c_str());
      return text;
    case MaterialModel::kMerl:
      return "merl(" + m.merl_path + ")";
    case MaterialModel::kGltf:
      std::snprintf(text, sizeof text, "gltf(base %s, metallic %.3g, alpha %.3gx%.3g, F0 %s)",
                    rgb_text(m.diffuse).c_str(), m.metallic, m.alpha_x, m.alpha_y,
                    rgb_text(m.specular).c_str());
      return text;
  }
  return "unknown";
}

Result<std::shared_ptr<const Brdf>> make_brdf(const Material& m) {
  switch (m.model) {
    case MaterialModel::kLambert:
      return share(Lambert::create(m.diffuse));
    case MaterialModel::kBlinnPhong:
      return share(BlinnPhong::create(m.diffuse, m.specular, m.exponent));
    case MaterialModel::kWard:
      return share(
          Ward::create(WardParams{m.diffuse, m.specular, m.alpha_x, m.alpha_y, m.ward_form}));
    case MaterialModel::kMerl:
      return share(MerlBrdf::read(m.merl_path));
    case MaterialModel::kGltf:
      return share(
          GltfPbr::create(GltfPbrParams{m.diffuse, m.metallic, m.alpha_x, m.alpha_y, m.specular}));
    case MaterialModel::kMicrofacet: {
      MicrofacetParams p;
      p.distribution = m.distribution;
      p.alpha_x = m.alpha_x;
      p.alpha_y = m.alpha_y;
      p.fresnel = m.fresnel;
      p.f0 = m.specular;
      p.eta = m.eta;
      Result<std::shared_ptr<const Brdf>> lobe = share(Microfacet::create(p));
      if (!lobe || zero(m.diffuse)) return lobe;
      Result<Lambert> diffuse = Lambert::create(m.diffuse);
      if (!diffuse) return diffuse.status();
      const double p_diffuse = detail::diffuse_probability(m.diffuse, m.specular);
      return std::shared_ptr<const Brdf>(std::make_shared<LayeredBrdf>(
          std::move(diffuse).value(), std::move(lobe).value(), p_diffuse));
    }
  }
  return Status::Error("unknown material model");
}

}  // namespace prt::brdf
