// relight/src/haar_relight.cpp — `prt relight` for Haar-wavelet files (relight/haar_relight.h).
#include "relight/haar_relight.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include "bake/glb_writer.h"
#include "bake/ray_caster.h"
#include "bake/scene_loader.h"
#include "prt/geometry_check.h"
#include "prt/haar_relighter.h"
#include "prt/haar_transfer_file.h"
#include "prt/haar_transform.h"
#include "relight/camera.h"
#include "relight/image_io.h"
#include "sh/rotation.h"

namespace prt::relight {
namespace {

constexpr int kRotationSubsamples = 4;  // per axis, per target texel

double elapsed_seconds(std::chrono::steady_clock::time_point since) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - since).count();
}

bool is_identity(const std::array<double, 9>& m) {
  for (int i = 0; i < 9; ++i)
    if (m[i] != (i % 4 == 0 ? 1.0 : 0.0)) return false;
  return true;
}

prt::CubeMap resample_or_throw(const sh::EnvMap& env, int size) {
  prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, size);
  if (!cube.ok()) throw std::runtime_error("environment: " + cube.status().message());
  return std::move(cube).value();
}

// Refuses outputs we cannot write before any work is done (run_relight's rules).
void check_output_path(const std::string& path, const std::string& allowed) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (allowed.find(ext.empty() ? std::string("?") : ext) == std::string::npos)
    throw std::runtime_error(path + ": unsupported file type '" + ext + "' (use " + allowed + ")");
  const std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (!dir.empty() && !std::filesystem::is_directory(dir))
    throw std::runtime_error(path + ": directory " + dir.string() + " does not exist");
}

}  // namespace

prt::CubeMap make_rotated_cube(const sh::EnvMap& env, int size, const std::array<double, 9>& m) {
  if (is_identity(m)) return resample_or_throw(env, size);
  const prt::CubeMap fine = resample_or_throw(env, std::min(prt::kMaxCubeSize, 2 * size));
  prt::CubeMap out = prt::make_black_cube_map(size);
  const int S = kRotationSubsamples;
  const double texel = 2.0 / size, sub = texel / S;
  for (int face = 0; face < prt::kCubeFaceCount; ++face) {
    for (int row = 0; row < size; ++row) {
      for (int col = 0; col < size; ++col) {
        double sum[3] = {0, 0, 0}, weight = 0;
        for (int sy = 0; sy < S; ++sy) {
          for (int sx = 0; sx < S; ++sx) {
            const double a0 = -1.0 + col * texel + sx * sub, b0 = -1.0 + row * texel + sy * sub;
            double d[3], src[3];
            prt::cube_face_point_direction(face, a0 + 0.5 * sub, b0 + 0.5 * sub, d);
            for (int i = 0; i < 3; ++i)  // Mᵀ·d
              src[i] = m[i] * d[0] + m[3 + i] * d[1] + m[6 + i] * d[2];
            int f = 0, c = 0, r = 0;
            if (!prt::direction_to_cube_texel(fine.size, src, &f, &c, &r)) continue;
            const double w = prt::cube_face_rect_solid_angle(a0, a0 + sub, b0, b0 + sub);
            const std::size_t at = 3 * ((std::size_t(f) * fine.size + r) * fine.size + c);
            for (int ch = 0; ch < 3; ++ch) sum[ch] += w * fine.rgb[at + ch];
            weight += w;
          }
        }
        const std::size_t at = 3 * ((std::size_t(face) * size + row) * size + col);
        for (int ch = 0; ch < 3; ++ch)
          out.rgb[at + ch] = weight > 0 ? static_cast<float>(sum[ch] / weight) : 0.f;
      }
    }
  }
  return out;
}

prt::SparseLighting project_haar_lighting(const sh::EnvMap& env, int size,
                                          const std::array<double, 9>& m,
                                          const HaarLightingOptions& options) {
  prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(make_rotated_cube(env, size, m));
  if (!wavelets.ok()) throw std::runtime_error("environment: " + wavelets.status().message());
  if (options.terms <= 0) return prt::keep_all_terms(*wavelets);
  return options.linear ? prt::select_linear(*wavelets, options.terms)
                        : prt::select_nonlinear(*wavelets, options.terms);
}

RelightSummary run_haar_relight(const RelightRequest& request, const HaarLightingOptions& options) {
  check_output_path(request.output_path, ".exr .hdr .png");
  if (!request.vertex_colors_path.empty()) check_output_path(request.vertex_colors_path, ".glb");
  if (!request.csv_path.empty()) check_output_path(request.csv_path, ".csv .txt");
  if (request.turntable_frames < 0 || request.turntable_frames > 3600)
    throw std::runtime_error("--turntable " + std::to_string(request.turntable_frames) +
                             ": frame count must be in 0..3600");
  RelightSummary summary;
  const bake::Scene scene = bake::load_scene(request.scene_path);
  prt::Result<prt::HaarTransferFile> file = prt::read_haar_transfer_file(request.transfer_path);
  if (!file.ok()) throw std::runtime_error(file.status().message());
  std::vector<float> xyz(3 * scene.vertex_count());
  for (std::size_t v = 0; v < scene.vertex_count(); ++v)
    for (int a = 0; a < 3; ++a) xyz[3 * v + a] = scene.positions[v][a];
  const prt::Status match =
      prt::check_geometry(file->info, xyz.data(), scene.vertex_count(), kGeometryTolerance);
  if (!match.ok())
    throw std::runtime_error(request.transfer_path + ": was not baked for " + scene.source_path +
                             ": " + match.message());
  const sh::EnvMap env =
      read_environment(request.environment_path, request.layout, &summary.layout_note);
  const float aspect = static_cast<float>(request.render.width) /
                       static_cast<float>(std::max(1, request.render.height));
  const Camera camera = parse_camera(request.camera, scene, aspect);
  make_camera_basis(camera, aspect);
  const int size = file->transfer.size;
  const prt::HaarRelighter relighter(std::move(file->transfer));
  summary.vertex_count = scene.vertex_count();
  summary.order = size;
  summary.window_note = std::string(options.linear ? "linear" : "non-linear") + " Haar, " +
                        (options.terms > 0 ? std::to_string(options.terms) : "all") +
                        " terms, cube " + std::to_string(size);
  const std::array<double, 9> rotation = sh::rotation_from_yaw_pitch_roll(
      request.lighting.yaw_pitch_roll_deg[0], request.lighting.yaw_pitch_roll_deg[1],
      request.lighting.yaw_pitch_roll_deg[2]);
  const bake::RayCaster caster(scene);
  const int frames = std::max(1, request.turntable_frames);
  std::vector<float> radiance(3 * scene.vertex_count());
  for (int frame = 0; frame < frames; ++frame) {
    const std::array<double, 9> m =
        request.turntable_frames > 0 ? turntable_rotation(rotation, frame, frames) : rotation;
    const prt::SparseLighting lighting = project_haar_lighting(env, size, m, options);
    auto start = std::chrono::steady_clock::now();
    const prt::Status shaded = relighter.shade(lighting, radiance.data());
    if (!shaded.ok()) throw std::runtime_error(request.transfer_path + ": " + shaded.message());
    summary.shade_seconds += elapsed_seconds(start);
    if (frame == 0) {
      for (std::size_t v = 0; v < scene.vertex_count(); ++v)
        if (std::min({radiance[3 * v], radiance[3 * v + 1], radiance[3 * v + 2]}) < 0.f)
          ++summary.negative_vertices;
      if (!request.vertex_colors_path.empty()) {
        std::vector<glm::vec3> colors(scene.vertex_count());
        for (std::size_t v = 0; v < colors.size(); ++v)
          colors[v] = glm::vec3(radiance[3 * v], radiance[3 * v + 1], radiance[3 * v + 2]);
        bake::write_glb(request.vertex_colors_path, scene, &colors);
        summary.files_written.push_back(request.vertex_colors_path);
      }
      if (!request.csv_path.empty()) {
        write_vertex_csv(request.csv_path, scene, radiance);
        summary.files_written.push_back(request.csv_path);
      }
    }
    start = std::chrono::steady_clock::now();
    const Image image = render(scene, caster, radiance, &env, m, camera, request.render);
    summary.render_seconds += elapsed_seconds(start);
    const std::string path = request.turntable_frames > 0
                                 ? turntable_frame_path(request.output_path, frame)
                                 : request.output_path;
    write_rendered_image(path, image, request.exposure_ev);
    summary.files_written.push_back(path);
  }
  return summary;
}

}  // namespace prt::relight
