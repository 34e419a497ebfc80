// emitter_relight.cpp — see relight/emitter_relight.h.
#include "relight/emitter_relight.h"

#include <chrono>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "prt/formats/geometry_check.h"
#include "relight_frames.h"

namespace prt::relight {

prt::EmitterResponses load_emitter_responses(const std::string& path) {
  prt::Result<prt::EmitterResponses> data = prt::read_emitter_responses(path);
  if (!data.ok()) throw std::runtime_error(data.status().message());
  return std::move(data).value();
}

scene::Scene scene_from_responses(const prt::EmitterResponses& data, const std::string& path) {
  scene::Scene s;
  const std::size_t v_count = data.vertex_count();
  s.positions.resize(v_count);
  s.normals.resize(v_count);
  s.albedo.assign(v_count, glm::vec3(1.f));
  for (std::size_t v = 0; v < v_count; ++v)
    for (int c = 0; c < 3; ++c) {
      s.positions[v][c] = data.positions[3 * v + c];
      s.normals[v][c] = data.normals[3 * v + c];
    }
  s.triangles.resize(data.triangle_count());
  for (std::size_t t = 0; t < s.triangles.size(); ++t)
    s.triangles[t] =
        glm::uvec3(data.triangles[3 * t], data.triangles[3 * t + 1], data.triangles[3 * t + 2]);
  scene::ScenePrimitive p;
  p.name = "responses";
  p.vertex_count = static_cast<uint32_t>(v_count);
  p.triangle_count = static_cast<uint32_t>(s.triangles.size());
  p.albedo = glm::vec3(1.f);
  s.primitives.push_back(p);
  s.source_path = path;
  return s;
}

void check_responses_match_scene(const prt::EmitterResponses& data, const std::string& path,
                                 const scene::Scene& scene) {
  const std::string head = path + ": was not computed for " +
                           (scene.source_path.empty() ? "this scene" : scene.source_path) + ": ";
  if (data.vertex_count() != scene.vertex_count())
    throw std::runtime_error(head + std::to_string(data.vertex_count()) +
                             " vertices, the scene has " + std::to_string(scene.vertex_count()) +
                             " (subdivide it alike: the same --max-edge as prt radiosity)");
  std::vector<float> xyz(3 * scene.vertex_count());
  for (std::size_t v = 0; v < scene.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) xyz[3 * v + c] = scene.positions[v][c];
  if (prt::geometry_fingerprint(xyz.data(), scene.vertex_count()) != data.fingerprint)
    throw std::runtime_error(head + "the geometry fingerprints differ (other vertex positions)");
}

std::vector<float> emitter_radiance(const prt::EmitterResponses& data, const std::string& path,
                                    const std::vector<prt::EmitterColor>& colors) {
  prt::Result<std::vector<float>> rgb = prt::emitter_colors(data, colors);
  if (!rgb.ok()) throw std::invalid_argument(path + ": " + rgb.status().message());
  std::vector<float> radiance(3 * data.vertex_count(), 0.f);
  const prt::Status s = prt::recombine_emitters(data, *rgb, radiance.data());
  if (!s.ok()) throw std::runtime_error(path + ": " + s.message());
  return radiance;
}

RelightSummary run_emitter_relight(const RelightRequest& request,
                                   const std::vector<prt::EmitterColor>& colors) {
  check_relight_outputs(request);
  if (request.turntable_frames > 0)
    throw std::invalid_argument(
        "--turntable does not apply to emitter responses (no lighting "
        "to turn)");
  const prt::EmitterResponses data = load_emitter_responses(request.transfer_path);
  emitter_radiance(data, request.transfer_path, colors);  // names and values checked first
  const scene::Scene scene = scene_from_responses(data, request.transfer_path);
  RelightSummary summary;
  summary.vertex_count = scene.vertex_count();
  summary.window_note =
      std::to_string(data.emitter_count()) + (data.emitter_count() == 1 ? " emitter" : " emitters");
  RelightRequest frames = request;
  frames.render.multiply_albedo = false;  // the responses are exit radiance
  const sh::EnvMap no_background;         // misses stay black
  detail::render_relight_frames(
      frames, scene, no_background, [](const std::array<double, 9>&) { return 0; },
      [&](int) { return emitter_radiance(data, request.transfer_path, colors); },  // timed
      &summary);
  return summary;
}

std::optional<GlossyEmitterLight> prepare_glossy_emitters(const RelightRequest& request,
                                                          const scene::Scene& scene,
                                                          const prt::GlossyTransferData& glossy,
                                                          const GlossyEmitterGatherer& gather) {
  if (request.emitters_path.empty()) return std::nullopt;
  const std::string& path = request.emitters_path;
  const prt::EmitterResponses responses = load_emitter_responses(path);
  check_responses_match_scene(responses, path, scene);
  prt::Result<std::vector<float>> colors = prt::emitter_colors(responses, request.emitter_colors);
  if (!colors.ok()) throw std::invalid_argument(path + ": " + colors.status().message());
  if (!gather) throw std::runtime_error(path + ": no emitter gather given to the glossy relight");
  GlossyEmitterLight light;
  light.colors = std::move(colors).value();
  light.geometry.order = glossy.order;
  light.geometry.vertex_count = glossy.vertex_count;
  light.geometry.positions = glossy.positions;
  light.geometry.normals = glossy.normals;
  light.geometry.tangents = glossy.tangents;
  light.geometry.materials = glossy.materials;
  light.geometry.material_of_vertex = glossy.material_of_vertex;
  const auto start = std::chrono::steady_clock::now();
  try {
    light.radiance = gather(scene, light.geometry, responses);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  light.gather_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (const prt::Status s = prt::validate_glossy_emitter_radiance(light.radiance); !s.ok())
    throw std::runtime_error(path + ": " + s.message());
  return light;
}

void add_glossy_emitters(const GlossyEmitterLight& light,
                         const std::vector<prt::BrdfProjection>& projections, const glm::vec3& eye,
                         std::vector<float>& radiance) {
  const std::size_t count = light.radiance.vertex_count;
  if (radiance.size() != 3 * count)
    throw std::runtime_error("glossy emitters: radiance of the wrong size");
  constexpr std::size_t kRange = 1024;
  const std::size_t ranges = (count + kRange - 1) / kRange;
  std::vector<std::string> errors(ranges);
  const double eye_xyz[3] = {eye.x, eye.y, eye.z};
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t r) {
    const std::size_t first = r * kRange, n = std::min(kRange, count - first);
    const prt::Status s =
        prt::shade_glossy_emitters(light.radiance, light.colors, light.geometry, projections,
                                   eye_xyz, first, n, &radiance[3 * first]);
    if (!s.ok()) errors[r] = s.message();
  });
  for (const std::string& error : errors)
    if (!error.empty()) throw std::runtime_error(error);
}

}  // namespace prt::relight
