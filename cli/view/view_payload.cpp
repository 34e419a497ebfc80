// cli/view/view_payload.cpp — the payloads of view_payload.h, from the relight/ functions that
// `prt relight` uses (so the page's camera, window and exposure are the offline render's).
#include "view_payload.h"

#include "glossy_payload.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <nlohmann/json.hpp>

#include "haar_payload.h"
#include "payload_parts.h"
#include "prt/core/half.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/transfer_data.h"
#include "relight/auto_camera.h"
#include "relight/auto_exposure.h"
#include "relight/emitter_relight.h"
#include "relight/environment_input.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "relight/shown_window.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "sh/window.h"
#include "view_preview.h"

namespace prt::cli::view {
namespace {

constexpr int kTransferWidth = 4096;      // texels per row of transfer.bin's texture
constexpr int kMaxTextureSide = 8192;     // what WebGL 2 implementations commonly allow
constexpr int kBackgroundSubsamples = 4;  // per axis, per texel of environment.bin

template <class T>
void append(std::vector<std::uint8_t>* out, const T* data, std::size_t count) {
  const std::size_t at = out->size();
  out->resize(at + count * sizeof(T));
  if (count > 0) std::memcpy(out->data() + at, data, count * sizeof(T));
}

// Appends a section and records it in the manifest.
template <class T>
void add_section(nlohmann::json* sections, std::vector<std::uint8_t>* out, const char* name,
                 const T* data, std::size_t count, const char* type) {
  (*sections)[name] = {{"offset", out->size()}, {"count", count}, {"type", type}};
  append(out, data, count);
}

std::vector<std::uint8_t> mesh_bytes(const ViewInputs& inputs, const scene::Scene& scene,
                                     const prt::TransferData& data, nlohmann::json* sections) {
  std::vector<std::uint8_t> out;
  const std::size_t v = scene.vertex_count();
  const std::size_t bytes =
      4 * (9 * v + (data.ao.empty() ? 0 : v) + (data.bent_normals.empty() ? 0 : 3 * v) +
           3 * scene.triangles.size());
  charge_payload(inputs, bytes, "the mesh");
  out.reserve(bytes);  // one allocation, no copies as it grows
  add_section(sections, &out, "positions", &scene.positions[0].x, 3 * v, "float32");
  add_section(sections, &out, "normals", &scene.normals[0].x, 3 * v, "float32");
  add_section(sections, &out, "albedo", &scene.albedo[0].x, 3 * v, "float32");
  if (!data.ao.empty()) add_section(sections, &out, "ao", data.ao.data(), v, "float32");
  if (!data.bent_normals.empty())
    add_section(sections, &out, "bent_normals", data.bent_normals.data(), 3 * v, "float32");
  add_section(sections, &out, "indices", &scene.triangles[0].x, 3 * scene.triangles.size(),
              "uint32");
  return out;
}

std::vector<std::uint8_t> transfer_bytes(const ViewInputs& inputs, const prt::TransferData& data,
                                         const std::string& what, nlohmann::json* layout) {
  const std::size_t per_vertex = std::size_t(data.channels) * data.coefficients_per_channel();
  const std::size_t texels_per_vertex = (per_vertex + 3) / 4;
  const std::size_t texels = texels_per_vertex * data.vertex_count;
  // A whole number of vertices per row (the shader finds a vertex's row with one division).
  std::size_t width = texels_per_vertex * (kTransferWidth / texels_per_vertex);
  if ((texels + width - 1) / width > std::size_t(kMaxTextureSide))
    width = texels_per_vertex * (kMaxTextureSide / texels_per_vertex);
  const std::size_t rows = std::max<std::size_t>(1, (texels + width - 1) / width);
  if (rows > std::size_t(kMaxTextureSide))
    throw std::runtime_error("the transfer takes " + std::to_string(texels) +
                             " texels, more than a " + std::to_string(kMaxTextureSide) +
                             "² texture");
  charge_payload(inputs, rows * width * 4 * sizeof(std::uint16_t), what);
  // Written in place, in parallel ranges of vertices (the halves do not depend on the split).
  std::vector<std::uint8_t> out(rows * width * 4 * sizeof(std::uint16_t), 0);
  auto* halves = reinterpret_cast<std::uint16_t*>(out.data());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, data.vertex_count, 4096),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t v = range.begin(); v < range.end(); ++v)
                        convert_floats_to_halves(&data.coefficients[v * per_vertex], per_vertex,
                                                 &halves[v * texels_per_vertex * 4]);
                    });
  *layout = {{"width", width},
             {"height", rows},
             {"texels_per_vertex", texels_per_vertex},
             {"vertices_per_row", width / texels_per_vertex},
             {"type", "float16 RGBA"}};
  return out;
}

std::vector<std::uint8_t> environment_bytes(const sh::EnvMap& env, int width) {
  const int height = width / 2;
  std::vector<std::uint16_t> halves(std::size_t(width) * height * 4);
  constexpr double kPi = 3.14159265358979323846;
  constexpr int n = kBackgroundSubsamples;
  for (int row = 0; row < height; ++row)
    for (int col = 0; col < width; ++col) {
      double sum[3] = {0, 0, 0};
      for (int sy = 0; sy < n; ++sy)
        for (int sx = 0; sx < n; ++sx) {
          const double u = (col + (sx + 0.5) / n) / width, v = (row + (sy + 0.5) / n) / height;
          const double phi = 2 * kPi * (u - 0.5), theta = kPi * v;  // u = 0.5 + atan2(z, x)/2π
          const glm::vec3 dir(float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                              float(std::sin(theta) * std::sin(phi)));
          float rgb[3];
          relight::look_up_background(env, relight::kIdentityRotation, dir, rgb);
          for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
        }
      std::uint16_t* texel = &halves[(std::size_t(row) * width + col) * 4];
      for (int c = 0; c < 3; ++c)
        texel[c] = float_to_half(float(std::min(65504.0, sum[c] / (n * n))));
      texel[3] = float_to_half(1.f);
    }
  std::vector<std::uint8_t> out;
  append(&out, halves.data(), halves.size());
  return out;
}

// The responses of inputs.emitters_path, checked against the scene (empty without one).
prt::EmitterResponses load_emitters(const ViewInputs& inputs, const scene::Scene& scene,
                                    const prt::TransferData& data) {
  if (inputs.emitters_path.empty()) return {};
  if (!data.albedo_folded)
    throw std::runtime_error(inputs.transfer_path +
                             ": keeps the albedo apart (textures); emitter responses are exit "
                             "radiance and cannot be added to it");
  prt::EmitterResponses responses = relight::load_emitter_responses(inputs.emitters_path);
  relight::check_responses_match_scene(responses, inputs.emitters_path, scene);
  return responses;
}

nlohmann::json emitters_json(const prt::EmitterResponses& responses) {
  nlohmann::json list = nlohmann::json::array();
  for (const prt::EmitterInfo& e : responses.emitters)
    list.push_back({{"name", e.name}, {"emission", e.emission}});
  return {{"url", "/api/emitters.bin"},
          {"emitters", list},
          {"layout", "float32 (e*V + v)*3 + c, per unit emission"}};
}

// The --also files: each loaded for `scene` and checked against `data` (the first file); their
// transfer payloads go to payload->also, their entries to the returned manifest array.
nlohmann::json add_also_files(const ViewInputs& inputs, const scene::Scene& scene,
                              const prt::TransferData& data, ViewPayload* payload) {
  nlohmann::json list = nlohmann::json::array();
  for (std::size_t i = 0; i < inputs.also_paths.size(); ++i) {
    const std::string& path = inputs.also_paths[i];
    if (is_glossy_view_file(path) || prt::is_haar_transfer_file(path))
      throw std::runtime_error(path + ": --also takes SH coefficient files only");
    const prt::TransferData other = relight::load_transfer_for_scene(path, scene);
    const auto differ = [&](const std::string& what, const std::string& a, const std::string& b) {
      throw std::runtime_error(path + ": " + what + " " + b + ", but " + inputs.transfer_path +
                               " has " + a + " (--also files must match it)");
    };
    if (other.order != data.order)
      differ("SH order", std::to_string(data.order), std::to_string(other.order));
    if (other.channels != data.channels)
      differ("channels", std::to_string(data.channels), std::to_string(other.channels));
    if (other.albedo_folded != data.albedo_folded)
      differ("albedo", data.albedo_folded ? "folded" : "apart",
             other.albedo_folded ? "folded" : "apart");
    nlohmann::json layout;
    payload->also.push_back(transfer_bytes(inputs, other, "the --also file " + path, &layout));
    layout["url"] = "/api/also" + std::to_string(i) + ".bin";
    const std::string name = std::filesystem::path(path).filename().string();
    list.push_back(
        {{"kind", prt::transfer_kind_name(other.kind)}, {"file", name}, {"transfer", layout}});
  }
  return list;
}

}  // namespace

ViewPayload build_view_payload(const ViewInputs& inputs) {
  const bool glossy = is_glossy_view_file(inputs.transfer_path);
  if ((glossy || prt::is_haar_transfer_file(inputs.transfer_path)) && !inputs.also_paths.empty())
    throw std::runtime_error(inputs.transfer_path + ": holds " +
                             (glossy ? "glossy transfer" : "Haar wavelets") +
                             "; --also applies to SH files");
  if (glossy) return build_glossy_view_payload(inputs);
  if (prt::is_haar_transfer_file(inputs.transfer_path)) return build_haar_view_payload(inputs);
  scene::Scene scene = scene::load_scene(inputs.scene_path);
  if (inputs.max_edge) scene = scene::subdivide_to_edge_length(scene, *inputs.max_edge);
  const prt::TransferData data = relight::load_transfer_for_scene(inputs.transfer_path, scene);
  const prt::EmitterResponses responses = load_emitters(inputs, scene, data);
  ViewPayload payload;
  const nlohmann::json also = add_also_files(inputs, scene, data, &payload);
  const int order = static_cast<int>(data.order);
  const sh::EnvMap env = payload_environment(inputs, order);
  relight::LightingOptions options;  // --window auto: chosen on the shaded vertices, as relight
  const prt::ShLighting unwindowed = relight::project_lighting(env, order, options);
  prt::Result<prt::Relighter> relighter = prt::Relighter::create(data);
  if (!relighter.ok())
    throw std::runtime_error(inputs.transfer_path + ": " + relighter.status().message());
  const auto shade = [&](const prt::ShLighting& lighting) {
    return relight::shade_all_vertices(*relighter, lighting, scene.vertex_count());
  };
  relight::ShownWindowSearch search(order);
  search.add_view(unwindowed, shade);
  const relight::ShownWindowChoice choice = search.choose();
  prt::ShLighting windowed = unwindowed;
  const std::string window_note = relight::apply_shown_window(choice, &windowed);
  std::vector<float> radiance = shade(windowed);
  if (!responses.emitters.empty()) {  // the first frame of prt relight --emitters adds them
    const std::vector<float> emitted =
        relight::emitter_radiance(responses, inputs.emitters_path, {});
    for (std::size_t i = 0; i < radiance.size(); ++i) radiance[i] += emitted[i];
  }
  const float exposure = payload_automatic_exposure(std::move(radiance), scene, data.albedo_folded);
  const scene::RayCaster caster(scene);
  const relight::CameraChoice camera = relight::choose_camera("auto", scene, caster, inputs.aspect);

  nlohmann::json manifest = payload_manifest_head(inputs, scene, prt::transfer_kind_name(data.kind),
                                                  order, int(data.channels), data.albedo_folded);
  manifest["sh_basis"] =
      "real orthonormal SH, no Condon-Shortley phase, k = l(l+1)+m, polar axis +z, glTF frame";
  nlohmann::json sections;
  payload.mesh = mesh_bytes(inputs, scene, data, &sections);
  manifest["mesh"] = {{"url", "/api/mesh.bin"}, {"sections", sections}};
  nlohmann::json layout;
  payload.transfer = transfer_bytes(inputs, data, "the transfer", &layout);
  layout["url"] = "/api/transfer.bin";
  manifest["transfer"] = layout;
  if (!also.empty()) manifest["also"] = also;
  if (scene.vertex_count() > kPreviewMinVertices && responses.emitters.empty()) {
    nlohmann::json preview;
    payload.preview =
        preview_bytes(scene, data, build_preview_mesh(scene, kPreviewVertices), &preview);
    charge_payload(inputs, payload.preview.size(), "the preview");
    manifest["preview"] = preview;
  }
  add_payload_lighting(unwindowed, choice, window_note, &manifest);
  add_payload_view(inputs, env, exposure, camera, &manifest, &payload);
  if (!responses.emitters.empty()) {
    manifest["emitters"] = emitters_json(responses);
    charge_payload(inputs, responses.responses.size() * sizeof(float), "the emitter responses");
    append(&payload.emitters, responses.responses.data(), responses.responses.size());
  }
  payload.manifest_json = manifest.dump(1);
  payload.summary = std::to_string(scene.vertex_count()) + " vertices, " +
                    prt::transfer_kind_name(data.kind) + " SH order " + std::to_string(order) +
                    "; " + window_note + "; exposure " + payload_exposure_text(exposure);
  return payload;
}

}  // namespace prt::cli::view

// The shared parts, for the payloads of other bases (payload_parts.h).
namespace prt::cli::view {

void charge_payload(const ViewInputs& inputs, std::uint64_t bytes, const std::string& what) {
  if (inputs.budget) inputs.budget->charge(bytes, what + " payload");
}

std::vector<std::uint8_t> payload_mesh_bytes(const ViewInputs& inputs, const scene::Scene& scene,
                                             const prt::TransferData& data,
                                             nlohmann::json* sections) {
  return mesh_bytes(inputs, scene, data, sections);
}

sh::EnvMap payload_environment(const ViewInputs& inputs, int sh_order) {
  if (inputs.environment_path.empty()) {  // uniform radiance 1
    sh::EnvMap env;
    env.layout = sh::EnvLayout::LatLong;
    env.width = 16;
    env.height = 8;
    env.rgb.assign(3 * 16 * 8, 1.f);
    return env;
  }
  relight::EnvironmentUse use;
  use.sh_order = sh_order;
  return relight::read_checked_environment(inputs.environment_path, std::nullopt, use).env;
}

// The automatic exposure as `prt relight` chooses it on its first frame (exit radiance: the
// vertex's albedo times the value when the file keeps the albedo apart).
float payload_automatic_exposure(std::vector<float> radiance, const scene::Scene& scene,
                                 bool albedo_folded) {
  if (!albedo_folded)
    for (std::size_t v = 0; v < scene.vertex_count(); ++v)
      for (int c = 0; c < 3; ++c) radiance[3 * v + c] *= scene.albedo[v][c];
  return relight::choose_auto_exposure(radiance);
}

nlohmann::json payload_manifest_head(const ViewInputs& inputs, const scene::Scene& scene,
                                     const std::string& kind, int order, int channels,
                                     bool albedo_folded) {
  nlohmann::json manifest;
  manifest["format"] = "prt-view 1";
  manifest["scene"] = inputs.scene_path;
  manifest["transfer_file"] = inputs.transfer_path;
  manifest["environment"] =
      inputs.environment_path.empty() ? "uniform radiance 1" : inputs.environment_path;
  manifest["kind"] = kind;
  manifest["order"] = order;
  manifest["channels"] = channels;
  manifest["albedo_folded"] = albedo_folded;
  manifest["vertex_count"] = scene.vertex_count();
  manifest["triangle_count"] = scene.triangles.size();
  return manifest;
}

void add_payload_lighting(const prt::ShLighting& unwindowed,
                          const relight::ShownWindowChoice& choice, const std::string& note,
                          nlohmann::json* manifest) {
  std::vector<double> lighting;
  for (int c = 0; c < 3; ++c)
    lighting.insert(lighting.end(), unwindowed.coefficients_double(c),
                    unwindowed.coefficients_double(c) + unwindowed.coefficient_count());
  (*manifest)["lighting"] = {{"coefficients", lighting},
                             {"layout", "channel-major radiance, 3 x order^2"}};
  (*manifest)["window"] = {
      {"name", sh::window_name(choice.window)}, {"strength", choice.strength}, {"note", note}};
}

void add_payload_view(const ViewInputs& inputs, const sh::EnvMap& env, float exposure,
                      const relight::CameraChoice& choice, nlohmann::json* manifest,
                      ViewPayload* payload) {
  const relight::Camera& c = choice.camera;
  (*manifest)["exposure_ev"] = exposure;
  (*manifest)["camera"] = {
      {"eye", {c.eye.x, c.eye.y, c.eye.z}},
      {"target", {c.target.x, c.target.y, c.target.z}},
      {"up", {c.up.x, c.up.y, c.up.z}},
      {"yfov_degrees", double(c.yfov_radians) * 180.0 / 3.14159265358979323846},
      {"aspect", inputs.aspect},
      {"origin", choice.origin}};
  const int width = inputs.background_width;
  charge_payload(inputs, std::uint64_t(width) * (width / 2) * 4 * sizeof(std::uint16_t),
                 "the background");
  payload->environment = environment_bytes(env, width);
  (*manifest)["background"] = {{"url", "/api/environment.bin"},
                               {"width", width},
                               {"height", width / 2},
                               {"type", "float16 RGBA lat-long"}};
}

std::string payload_exposure_text(float ev) {
  char text[32];
  std::snprintf(text, sizeof text, "%+.2f EV", double(ev));
  return text;
}

}  // namespace prt::cli::view
