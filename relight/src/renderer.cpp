#include "relight/renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace prt::relight {
namespace {

// The world-space width a sub-pixel covers at a hit (renderer.h): t·angle/√max(|cos θ|, 1/16).
float footprint_width(const scene::Scene& scene, const scene::RayCaster::Hit& hit,
                      const glm::vec3& dir, float sub_pixel_angle) {
  const glm::uvec3 tri = scene.triangles[hit.triangle];
  const glm::vec3 n = glm::cross(scene.positions[tri.y] - scene.positions[tri.x],
                                 scene.positions[tri.z] - scene.positions[tri.x]);
  const float length = glm::length(n);
  const float cosine = length > 0.f ? std::fabs(glm::dot(n, dir)) / length : 1.f;
  return hit.t * sub_pixel_angle / std::sqrt(std::max(cosine, 1.f / 16.f));
}

}  // namespace

void look_up_background(const sh::EnvMap& background, const std::array<double, 9>& m,
                        const glm::vec3& dir, float rgb[3]) {
  // Mᵀ·d: column i of M dotted with d.
  const double d[3] = {dir.x, dir.y, dir.z};
  double source[3];
  for (int i = 0; i < 3; ++i) source[i] = m[i] * d[0] + m[3 + i] * d[1] + m[6 + i] * d[2];
  sh::sample_bilinear(background, source, rgb);
}

Image render(const scene::Scene& scene, const scene::RayCaster& caster,
             const std::vector<float>& vertex_radiance_rgb, const sh::EnvMap* background,
             const std::array<double, 9>& background_rotation, const Camera& camera,
             const RenderOptions& options) {
  if (vertex_radiance_rgb.size() != 3 * scene.vertex_count())
    throw std::runtime_error("render: " + std::to_string(vertex_radiance_rgb.size()) +
                             " radiance values for " + std::to_string(scene.vertex_count()) +
                             " vertices (need 3 per vertex)");
  if (options.width < 1 || options.height < 1 || options.width > 16384 || options.height > 16384)
    throw std::runtime_error("render: image size " + std::to_string(options.width) + "x" +
                             std::to_string(options.height) + " is out of range (1..16384)");
  if (options.samples_per_axis < 1 || options.samples_per_axis > 16)
    throw std::runtime_error("render: samples per axis " +
                             std::to_string(options.samples_per_axis) + " is out of range (1..16)");
  const float aspect = static_cast<float>(options.width) / static_cast<float>(options.height);
  const CameraBasis basis = make_camera_basis(camera, aspect);
  if (background && (background->width < 1 || background->height < 1 ||
                     background->rgb.size() < 3 * static_cast<std::size_t>(background->width) *
                                                  static_cast<std::size_t>(background->height)))
    background = nullptr;

  Image image;
  image.width = options.width;
  image.height = options.height;
  image.rgb.assign(3 * static_cast<std::size_t>(options.width) * options.height, 0.f);

  const int n = options.samples_per_axis;
  const double inv_samples = 1.0 / (static_cast<double>(n) * n);
  // Angle of one sub-pixel at the image centre (texture footprints, see renderer.h).
  const float sub_pixel_angle =
      2.f * basis.tan_half_yfov / static_cast<float>(options.height) / static_cast<float>(n);
  const double inv_w = 1.0 / options.width, inv_h = 1.0 / options.height;
  const float infinity = std::numeric_limits<float>::infinity();

  tbb::parallel_for(
      tbb::blocked_range<int>(0, options.height), [&](const tbb::blocked_range<int>& rows) {
        for (int row = rows.begin(); row != rows.end(); ++row) {
          for (int col = 0; col < options.width; ++col) {
            double sum[3] = {0, 0, 0};
            for (int sy = 0; sy < n; ++sy) {
              for (int sx = 0; sx < n; ++sx) {
                const double px = col + (sx + 0.5) / n, py = row + (sy + 0.5) / n;
                const auto ndc_x = static_cast<float>(2.0 * px * inv_w - 1.0);
                const auto ndc_y = static_cast<float>(1.0 - 2.0 * py * inv_h);
                const glm::vec3 dir = ray_direction(basis, ndc_x, ndc_y);
                const scene::RayCaster::Hit hit = caster.intersect(camera.eye, dir, 0.f, infinity);
                float rgb[3] = {0.f, 0.f, 0.f};
                if (hit.hit && !hit.front_face) {
                  // The back of a one-sided surface: black (renderer.h).
                } else if (hit.hit && hit.triangle < scene.triangles.size()) {
                  const glm::uvec3 tri = scene.triangles[hit.triangle];
                  const float w[3] = {1.f - hit.u - hit.v, hit.u, hit.v};
                  for (int corner = 0; corner < 3; ++corner) {
                    const float* b =
                        &vertex_radiance_rgb[3 * static_cast<std::size_t>(tri[corner])];
                    for (int c = 0; c < 3; ++c) rgb[c] += w[corner] * b[c];
                  }
                  if (options.multiply_albedo) {
                    const glm::vec3 albedo =
                        scene.albedo_at(hit.triangle, hit.u, hit.v,
                                        footprint_width(scene, hit, dir, sub_pixel_angle));
                    for (int c = 0; c < 3; ++c) rgb[c] *= albedo[c];
                  }
                } else if (!hit.hit && background) {
                  look_up_background(*background, background_rotation, dir, rgb);
                }
                for (int c = 0; c < 3; ++c) sum[c] += rgb[c];
              }
            }
            float* out = &image.rgb[3 * (static_cast<std::size_t>(row) * options.width + col)];
            for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(sum[c] * inv_samples);
          }
        }
        if (options.rows_done) options.rows_done(rows.end() - rows.begin());
      });
  return image;
}

}  // namespace prt::relight
