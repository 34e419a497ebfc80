// relight/src/transfer_glb.cpp — the attributes and extras of relight/transfer_glb.h.
#include "relight/transfer_glb.h"

#include <nlohmann/json.hpp>

namespace prt::relight {

scene::GlbCustomData transfer_glb_data(const prt::TransferData& data, const scene::Scene& scene,
                                       const prt::ShLighting* lighting,
                                       const std::string& lighting_source) {
  scene::GlbCustomData custom;
  const std::size_t vertices = data.vertex_count;
  const std::size_t per_vertex = std::size_t(data.channels) * data.coefficients_per_channel();
  const std::size_t count = (per_vertex + 3) / 4;
  for (std::size_t j = 0; j < count; ++j) {
    scene::GlbCustomAttribute a;
    a.name = kTransferAttributePrefix + std::to_string(j);
    a.components = 4;
    a.values.assign(4 * vertices, 0.f);
    for (std::size_t v = 0; v < vertices; ++v)
      for (std::size_t e = 0; e < 4 && 4 * j + e < per_vertex; ++e)
        a.values[4 * v + e] = data.coefficients[v * per_vertex + 4 * j + e];
    custom.attributes.push_back(std::move(a));
  }
  if (!data.ao.empty()) custom.attributes.push_back({"_PRT_AO", 1, data.ao});
  if (!data.bent_normals.empty())
    custom.attributes.push_back({"_PRT_BENT_NORMAL", 3, data.bent_normals});
  if (!data.albedo_folded) {
    std::vector<float> albedo(3 * vertices);
    for (std::size_t v = 0; v < vertices; ++v)
      for (int c = 0; c < 3; ++c) albedo[3 * v + c] = scene.albedo[v][c];
    custom.attributes.push_back({"_PRT_ALBEDO", 3, std::move(albedo)});
  }
  nlohmann::json prt = {
      {"format", "prt-transfer-gltf 1"},
      {"kind", prt::transfer_kind_name(data.kind)},
      {"order", data.order},
      {"channels", data.channels},
      {"albedo_folded", data.albedo_folded},
      {"attribute_prefix", kTransferAttributePrefix},
      {"attribute_count", count},
      {"layout", "coefficient i = c*order^2 + k is component i mod 4 of _PRT_SH<i/4>"},
      {"sh_basis",
       "real orthonormal SH, no Condon-Shortley phase, k = l(l+1)+m, polar axis +z, "
       "glTF frame (+Y up)"}};
  custom.mesh_extras_json = nlohmann::json{{"prt", prt}}.dump();
  if (lighting) {
    std::vector<double> coefficients;
    for (int c = 0; c < 3; ++c)
      coefficients.insert(coefficients.end(), lighting->coefficients_double(c),
                          lighting->coefficients_double(c) + lighting->coefficient_count());
    nlohmann::json light = {{"order", lighting->order()},
                            {"coefficients", coefficients},
                            {"layout", "channel-major radiance SH, 3 x order^2"},
                            {"source", lighting_source}};
    custom.scene_extras_json = nlohmann::json{{"prt", {{"lighting", light}}}}.dump();
  }
  return custom;
}

}  // namespace prt::relight
