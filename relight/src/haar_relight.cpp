// relight/src/haar_relight.cpp — `prt relight` for Haar-wavelet files (relight/haar_relight.h).
#include "relight/haar_relight.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "prt/formats/haar_transfer_file.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transform.h"
#include "relight/environment_input.h"
#include "relight/image_io.h"
#include "relight_frames.h"
#include "scene/scene_loader.h"

namespace prt::relight {
namespace {

constexpr int kRotationSubsamples = 4;  // per axis, per target texel

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
  check_relight_outputs(request);
  RelightSummary summary;
  const scene::Scene scene = scene::load_scene(request.scene_path);
  prt::Result<prt::HaarTransferFile> file = prt::read_haar_transfer_file(request.transfer_path);
  if (!file.ok()) throw std::runtime_error(file.status().message());
  check_transfer_matches_scene(file->info, request.transfer_path, scene);
  RelightRequest frames = request;
  frames.render.multiply_albedo = !file->info.albedo_folded;
  EnvironmentInput input = read_checked_environment(request.environment_path, request.layout);
  const sh::EnvMap env = std::move(input.env);
  summary.layout_note = input.layout_note;
  const int size = file->transfer.size;
  const prt::HaarRelighter relighter(std::move(file->transfer));
  summary.vertex_count = scene.vertex_count();
  summary.order = size;
  const int64_t coefficients = int64_t{6} * size * size;  // terms beyond these: all of them
  summary.window_note =
      std::string(options.linear ? "linear" : "non-linear") + " Haar, " +
      (options.terms > 0 && options.terms < coefficients ? std::to_string(options.terms)
                                                         : "all " + std::to_string(coefficients)) +
      " terms, cube " + std::to_string(size);
  detail::render_relight_frames(
      frames, scene, env,
      [&](const std::array<double, 9>& m) { return project_haar_lighting(env, size, m, options); },
      [&](const prt::SparseLighting& lighting) {
        std::vector<float> radiance(3 * scene.vertex_count());
        const prt::Status shaded = relighter.shade(lighting, radiance.data());
        if (!shaded.ok()) throw std::runtime_error(request.transfer_path + ": " + shaded.message());
        return radiance;
      },
      &summary);
  return summary;
}

}  // namespace prt::relight
