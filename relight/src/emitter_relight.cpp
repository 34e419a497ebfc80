// emitter_relight.cpp — see relight/emitter_relight.h.
#include "relight/emitter_relight.h"

#include <stdexcept>

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

}  // namespace prt::relight
