#include "relight/relight_pipeline.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "prt/core/atomic_file.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/transfer_file.h"
#include "relight/auto_exposure.h"
#include "relight/emitter_relight.h"
#include "relight/image_io.h"
#include "relight/shown_window.h"
#include "relight/tone_map.h"
#include "relight_frames.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "sh/rotation.h"

namespace prt::relight {
namespace {

std::string lower_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

void check_image_extension(const std::string& path) {
  const std::string ext = lower_extension(path);
  if (ext != ".exr" && ext != ".hdr" && ext != ".png")
    throw std::runtime_error(path + ": unsupported image type '" + ext +
                             "' (use .exr, .hdr or .png)");
}

void check_parent_directory(const std::string& path) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty() && !std::filesystem::is_directory(parent))
    throw std::runtime_error(path + ": directory " + parent.string() + " does not exist");
}

// The emitters' radiance per vertex (empty without request.emitters_path).
std::vector<float> emitters_for_scene(const RelightRequest& request, const scene::Scene& scene,
                                      const prt::TransferData& data) {
  if (request.emitters_path.empty()) return {};
  if (!data.albedo_folded)
    throw std::runtime_error(request.transfer_path +
                             ": keeps the albedo apart (textures); emitter responses are exit "
                             "radiance and cannot be added to it");
  const prt::EmitterResponses responses = load_emitter_responses(request.emitters_path);
  check_responses_match_scene(responses, request.emitters_path, scene);
  return emitter_radiance(responses, request.emitters_path, request.emitter_colors);
}

std::vector<float> flatten_positions(const scene::Scene& scene) {
  std::vector<float> xyz(3 * scene.vertex_count());
  for (std::size_t i = 0; i < scene.vertex_count(); ++i)
    for (int c = 0; c < 3; ++c) xyz[3 * i + c] = scene.positions[i][c];
  return xyz;
}

}  // namespace

void check_relight_outputs(const RelightRequest& request) {
  check_image_extension(request.output_path);
  check_parent_directory(request.output_path);
  if (!request.vertex_colors_path.empty()) {
    if (lower_extension(request.vertex_colors_path) != ".glb")
      throw std::runtime_error(request.vertex_colors_path + ": vertex colours are written as .glb");
    check_parent_directory(request.vertex_colors_path);
  }
  if (!request.csv_path.empty()) check_parent_directory(request.csv_path);
  if (request.turntable_frames < 0 || request.turntable_frames > 3600)
    throw std::runtime_error("--turntable " + std::to_string(request.turntable_frames) +
                             ": frame count must be in 0..3600");
}

void check_transfer_matches_scene(const prt::TransferData& data, const std::string& transfer_path,
                                  const scene::Scene& scene) {
  const std::vector<float> positions = flatten_positions(scene);
  const prt::Status match =
      prt::check_geometry(data, positions.data(), scene.vertex_count(), kGeometryTolerance);
  if (!match.ok())
    throw std::runtime_error(
        transfer_path + ": was not baked for " +
        (scene.source_path.empty() ? std::string("this scene") : scene.source_path) + ": " +
        match.message());
}

prt::TransferData load_transfer_for_scene(const std::string& transfer_path,
                                          const scene::Scene& scene) {
  prt::Result<prt::TransferData> data = prt::read_transfer_file(transfer_path);
  if (!data.ok()) {
    const std::string message = data.status().message();
    // The runtime names the file already; add it only when it does not.
    if (message.rfind(transfer_path, 0) == 0) throw std::runtime_error(message);
    throw std::runtime_error(transfer_path + ": " + message);
  }
  check_transfer_matches_scene(*data, transfer_path, scene);
  return std::move(data).value();
}

prt::ShLighting project_lighting(const sh::EnvMap& env, int order, const LightingOptions& options,
                                 std::string* note) {
  prt::Result<prt::ShLighting> projected = prt::ShLighting::from_env_map(env, order);
  if (!projected.ok()) throw std::runtime_error(projected.status().message());
  prt::ShLighting lighting = std::move(projected).value();
  sh::Window window = options.window;
  double strength = options.window_strength;
  char text[160];
  if (window == sh::Window::Auto) {
    const int k = lighting.coefficient_count();
    std::vector<double> coefficients(3 * static_cast<std::size_t>(k));
    for (int c = 0; c < 3; ++c)
      std::copy(lighting.coefficients_double(c), lighting.coefficients_double(c) + k,
                coefficients.begin() + static_cast<std::ptrdiff_t>(c) * k);
    const sh::WindowChoice choice = sh::choose_window_auto(coefficients.data(), 3, order);
    window = choice.window;
    strength = choice.strength;
    std::snprintf(text, sizeof text,
                  "window auto: %s, strength %.3g; min irradiance %.3g before, %.3g after",
                  sh::window_name(window), strength, choice.min_irradiance_before,
                  choice.min_irradiance_after);
  } else if (window == sh::Window::None) {
    std::snprintf(text, sizeof text, "no window");
  } else {
    if (!(strength > 0.0)) strength = sh::default_window_strength(window, order);
    std::snprintf(text, sizeof text, "window %s, strength %.3g", sh::window_name(window), strength);
  }
  const prt::Status windowed = lighting.apply_window(window, strength);
  if (!windowed.ok()) throw std::runtime_error("--window: " + windowed.message());
  if (note) *note = text;
  return lighting;
}

std::array<double, 9> multiply_rotations(const std::array<double, 9>& a,
                                         const std::array<double, 9>& b) {
  std::array<double, 9> r{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double sum = 0;
      for (int k = 0; k < 3; ++k) sum += a[3 * i + k] * b[3 * k + j];
      r[3 * i + j] = sum;
    }
  return r;
}

std::array<double, 9> turntable_rotation(const std::array<double, 9>& base, int frame,
                                         int frame_count) {
  if (frame_count <= 0) return base;
  const double yaw = 360.0 * frame / frame_count;
  return multiply_rotations(sh::rotation_from_yaw_pitch_roll(yaw, 0.0, 0.0), base);
}

std::array<double, 9> frame_rotation(const RelightRequest& request, int frame) {
  const std::array<double, 3>& ypr = request.lighting.yaw_pitch_roll_deg;
  const std::array<double, 9> base = sh::rotation_from_yaw_pitch_roll(ypr[0], ypr[1], ypr[2]);
  return request.turntable_frames > 0
             ? turntable_rotation(base, frame, std::max(1, request.turntable_frames))
             : base;
}

prt::ShLighting rotate_lighting(const prt::ShLighting& lighting, const std::array<double, 9>& m) {
  prt::ShLighting rotated = lighting;
  const prt::Status status = rotated.rotate(m);
  if (!status.ok()) throw std::runtime_error("--rotate: " + status.message());
  return rotated;
}

std::vector<float> shade_all_vertices(const prt::Relighter& relighter,
                                      const prt::ShLighting& lighting, std::size_t vertex_count) {
  std::vector<float> radiance(3 * vertex_count, 0.f);
  constexpr std::size_t kRange = 4096;  // a multiple of the kernel's 16-vertex blocks
  const std::size_t ranges = (vertex_count + kRange - 1) / kRange;
  std::vector<std::string> errors(ranges);
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t r) {
    const std::size_t first = r * kRange;
    const std::size_t count = std::min(kRange, vertex_count - first);
    const prt::Status status = relighter.shade(lighting, first, count, &radiance[3 * first]);
    if (!status.ok()) errors[r] = status.message();
  });
  for (const std::string& error : errors)
    if (!error.empty()) throw std::runtime_error("shading: " + error);
  return radiance;
}

void write_rendered_image(const std::string& path, const Image& image, float exposure_ev) {
  const std::string ext = lower_extension(path);
  if (ext == ".png") {
    std::vector<float> encoded(image.rgb.size());
    tone_map(image.rgb.data(), image.rgb.size(), exposure_ev, encoded.data());
    write_image(path, image.width, image.height, 3, encoded.data());
  } else if (ext == ".exr" || ext == ".hdr") {
    // Negative radiance (SH ringing, counted per vertex by the caller) is clamped to 0 as the
    // PNG's tone curve does; NaN stays NaN.
    std::vector<float> clamped(image.rgb);
    for (float& v : clamped)
      if (v < 0.f) v = 0.f;
    write_image(path, image.width, image.height, 3, clamped.data());
  } else {
    check_image_extension(path);
  }
}

void write_vertex_csv(const std::string& path, const scene::Scene& scene,
                      const std::vector<float>& radiance_rgb,
                      const std::vector<float>* per_unit_albedo) {
  if (radiance_rgb.size() != 3 * scene.vertex_count() ||
      (per_unit_albedo && per_unit_albedo->size() != radiance_rgb.size()))
    throw std::runtime_error(path + ": radiance count does not match the scene's vertices");
  const prt::Status written = prt::replace_file_atomically(path, [&](const std::string& temporary) {
    std::FILE* file = std::fopen(temporary.c_str(), "wb");
    if (!file) return prt::Status::Error(path + ": cannot open for writing");
    bool ok =
        std::fputs(per_unit_albedo ? "index,x,y,z,r,g,b,r_per_albedo,g_per_albedo,b_per_albedo\n"
                                   : "index,x,y,z,r,g,b\n",
                   file) >= 0;
    for (std::size_t i = 0; ok && i < scene.vertex_count(); ++i) {
      const glm::vec3& p = scene.positions[i];
      const float* b = &radiance_rgb[3 * i];
      ok = std::fprintf(file, "%zu,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", i, p.x, p.y, p.z, b[0], b[1],
                        b[2]) > 0;
      if (ok && per_unit_albedo) {
        const float* s = &(*per_unit_albedo)[3 * i];
        ok = std::fprintf(file, ",%.9g,%.9g,%.9g", s[0], s[1], s[2]) > 0;
      }
      ok = ok && std::fputc('\n', file) != EOF;
    }
    const int error = ok ? 0 : errno;  // the first failed write's reason
    const bool closed = std::fclose(file) == 0;
    if (ok && closed) return prt::Status::Ok();
    return prt::Status::Error(path + ": cannot write " + temporary + ": " +
                              std::strerror(ok ? errno : error));
  });
  if (!written.ok()) throw std::runtime_error(written.message());
}

std::string turntable_frame_path(const std::string& path, int frame) {
  const std::filesystem::path p(path);
  char index[32];
  std::snprintf(index, sizeof index, "_%03d", frame);
  return (p.parent_path() / (p.stem().string() + index + p.extension().string())).string();
}

RelightSummary run_relight(const RelightRequest& request) {
  // 1. Validate every input before writing anything.
  check_relight_outputs(request);
  RelightSummary summary;
  scene::Scene scene = scene::load_scene(request.scene_path);
  if (request.max_edge) scene = scene::subdivide_to_edge_length(scene, *request.max_edge);
  const prt::TransferData data = load_transfer_for_scene(request.transfer_path, scene);
  const std::vector<float> emitted = emitters_for_scene(request, scene, data);
  // --window auto is chosen on the vertices as shaded in every frame (relight/shown_window.h).
  detail::ShEnvironment lit = detail::read_sh_environment(request, static_cast<int>(data.order),
                                                          scene.vertex_count(), &summary);
  const sh::EnvMap& env = lit.env;
  prt::ShLighting& base = lit.base;
  const bool window_on_vertices = lit.window_on_vertices;
  prt::Result<prt::Relighter> relighter = prt::Relighter::create(data);
  if (!relighter.ok())
    throw std::runtime_error(request.transfer_path + ": " + relighter.status().message());
  if (window_on_vertices) {
    ShownWindowSearch search(base.order());
    const ShadeVertices shade = [&](const prt::ShLighting& lighting) {
      return shade_all_vertices(*relighter, lighting, scene.vertex_count());
    };
    for (int frame = 0; frame < std::max(1, request.turntable_frames); ++frame)
      search.add_view(rotate_lighting(base, frame_rotation(request, frame)), shade);
    summary.window_note = apply_shown_window(search.choose(), &base);
  }
  RelightRequest frames = request;
  frames.render.multiply_albedo = !data.albedo_folded;  // textures applied per pixel

  // 2. Shade, render, write: one frame, or the turntable's frames.
  detail::render_relight_frames(
      frames, scene, env, [&](const std::array<double, 9>& m) { return rotate_lighting(base, m); },
      [&](const prt::ShLighting& lighting) {
        std::vector<float> radiance =
            shade_all_vertices(*relighter, lighting, scene.vertex_count());
        for (std::size_t i = 0; i < emitted.size(); ++i) radiance[i] += emitted[i];
        return radiance;
      },
      &summary);
  return summary;
}

std::string describe_view(const RelightRequest& request, const RelightSummary& summary) {
  const bool png = lower_extension(request.output_path) == ".png";
  std::string text = png || request.vertex_colors_tonemapped
                         ? describe_exposure(summary.exposure_ev, summary.exposure_auto)
                         : "linear image, no exposure applied";
  if (!summary.camera_note.empty()) text += "\n" + summary.camera_note;
  return text;
}

}  // namespace prt::relight
