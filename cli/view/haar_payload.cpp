// cli/view/haar_payload.cpp — the payload of a Haar-wavelet file (haar_payload.h).
#include "haar_payload.h"

#include <array>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "payload_parts.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transform.h"
#include "relight/environment_input.h"
#include "relight/haar_relight.h"
#include "relight/relight_pipeline.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace prt::cli::view {
namespace {

constexpr std::array<double, 9> kIdentity = {1, 0, 0, 0, 1, 0, 0, 0, 1};

// Appends `count` elements at the next multiple of 16 bytes and records the section.
template <class T>
void add_section(nlohmann::json* sections, std::vector<std::uint8_t>* out, const char* name,
                 const T* data, std::size_t count, const char* type) {
  const std::size_t at = (out->size() + 15) / 16 * 16;
  out->resize(at + count * sizeof(T), 0);
  if (count > 0) std::memcpy(out->data() + at, data, count * sizeof(T));
  (*sections)[name] = {{"offset", at}, {"count", count}, {"type", type}};
}

std::vector<std::uint8_t> transfer_bytes(const ViewInputs& inputs, const prt::HaarTransfer& t,
                                         const prt::CubeMap& cube, const prt::CubeMap& fine,
                                         nlohmann::json* sections) {
  const std::uint64_t values =
      t.values_i16.size() * 2 + t.values_i8.size() + t.values_f32.size() * 4;
  charge_payload(inputs,
                 4 * (t.offsets.size() + t.vertices.size() + std::size_t(t.vertex_count) +
                      cube.rgb.size() + fine.rgb.size()) +
                     values,
                 "the wavelet transfer");
  std::vector<std::uint8_t> out;
  std::vector<std::uint32_t> offsets(t.offsets.begin(), t.offsets.end());
  add_section(sections, &out, "offsets", offsets.data(), offsets.size(), "uint32");
  offsets = {};
  add_section(sections, &out, "vertices", t.vertices.data(), t.vertices.size(), "uint32");
  if (t.quantization == prt::HaarQuantization::Bits16)
    add_section(sections, &out, "values", t.values_i16.data(), t.values_i16.size(), "int16");
  else if (t.quantization == prt::HaarQuantization::Bits8)
    add_section(sections, &out, "values", t.values_i8.data(), t.values_i8.size(), "int8");
  else
    add_section(sections, &out, "values", t.values_f32.data(), t.values_f32.size(), "float32");
  std::vector<float> steps = t.vertex_step;
  if (steps.empty()) steps.assign(std::size_t(t.vertex_count), 1.f);
  add_section(sections, &out, "steps", steps.data(), steps.size(), "float32");
  add_section(sections, &out, "cube", cube.rgb.data(), cube.rgb.size(), "float32");
  add_section(sections, &out, "fine_cube", fine.rgb.data(), fine.rgb.size(), "float32");
  return out;
}

void refuse_sh_only_options(const ViewInputs& inputs) {
  if (!inputs.emitters_path.empty())
    throw std::runtime_error(inputs.transfer_path +
                             ": holds Haar wavelets; --emitters applies to SH files");
  if (inputs.max_edge)
    throw std::runtime_error(inputs.transfer_path +
                             ": holds Haar wavelets; --max-edge applies to SH files");
}

}  // namespace

ViewPayload build_haar_view_payload(const ViewInputs& inputs) {
  refuse_sh_only_options(inputs);
  const scene::Scene scene = scene::load_scene(inputs.scene_path);
  prt::Result<prt::HaarTransferFile> file = prt::read_haar_transfer_file(inputs.transfer_path);
  if (!file.ok()) throw std::runtime_error(file.status().message());
  relight::check_transfer_matches_scene(file->info, inputs.transfer_path, scene);
  const prt::HaarTransfer& transfer = file->transfer;
  if (transfer.entry_count() > std::numeric_limits<std::uint32_t>::max())
    throw std::runtime_error(inputs.transfer_path + ": " + std::to_string(transfer.entry_count()) +
                             " transfer entries, more than the page's 32-bit offsets hold");
  const sh::EnvMap env = payload_environment(inputs, 0);
  const int size = transfer.size, fine_size = std::min(prt::kMaxCubeSize, 2 * size);
  const prt::CubeMap cube = relight::make_rotated_cube(env, size, kIdentity);
  prt::Result<prt::CubeMap> fine = prt::resample_to_cube(env, fine_size);
  if (!fine.ok()) throw std::runtime_error("environment: " + fine.status().message());

  // The first frame as prt relight shades it (default terms, unrotated), for the exposure.
  relight::HaarLightingOptions lighting_options;
  lighting_options.terms = kHaarDefaultTerms;
  const prt::SparseLighting lighting =
      relight::project_haar_lighting(env, size, kIdentity, lighting_options);
  std::vector<float> radiance(3 * scene.vertex_count());
  const prt::Status shaded = prt::shade_index_lists(transfer, lighting, radiance.data());
  if (!shaded.ok()) throw std::runtime_error(inputs.transfer_path + ": " + shaded.message());
  const bool folded = file->info.albedo_folded;
  const float exposure = payload_automatic_exposure(std::move(radiance), scene, folded);
  const scene::RayCaster caster(scene);
  const relight::CameraChoice camera = relight::choose_camera("auto", scene, caster, inputs.aspect);

  ViewPayload payload;
  nlohmann::json manifest =
      payload_manifest_head(inputs, scene, prt::transfer_kind_name(file->info.kind), size,
                            int(transfer.channels), folded);
  manifest["haar_basis"] = prt::kHaarBasisConvention;
  nlohmann::json mesh_sections;
  payload.mesh = payload_mesh_bytes(inputs, scene, file->info, &mesh_sections);
  manifest["mesh"] = {{"url", "/api/mesh.bin"}, {"sections", mesh_sections}};
  nlohmann::json sections;
  payload.transfer = transfer_bytes(inputs, transfer, cube, *fine, &sections);
  const int bits = static_cast<int>(transfer.quantization);
  manifest["haar"] = {{"url", "/api/transfer.bin"},         {"cube_size", size},
                      {"fine_cube_size", fine_size},        {"channels", transfer.channels},
                      {"entries", transfer.entry_count()},  {"quantization_bits", bits},
                      {"default_terms", kHaarDefaultTerms}, {"sections", sections}};
  manifest["transfer"] = {{"url", "/api/transfer.bin"}};
  manifest["window"] = {{"name", "none"}, {"strength", 0.0}, {"note", "Haar: no window"}};
  add_payload_view(inputs, env, exposure, camera, &manifest, &payload);
  payload.manifest_json = manifest.dump(1);
  payload.summary = std::to_string(scene.vertex_count()) + " vertices, Haar cube " +
                    std::to_string(size) + ", " + std::to_string(transfer.entry_count()) +
                    " entries (" + std::to_string(bits) + "-bit); non-linear lighting, " +
                    std::to_string(kHaarDefaultTerms) + " terms; exposure " +
                    payload_exposure_text(exposure);
  return payload;
}

}  // namespace prt::cli::view
