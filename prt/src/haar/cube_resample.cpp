// Power-preserving resampling of an environment map to a cube map; see prt/haar/cube_map.h.
#include <algorithm>
#include <cmath>
#include <string>

#include "prt/haar/cube_map.h"
#include "sh/constants.h"
#include "sh/env_map.h"

namespace prt {

namespace {
using sh::kPi;
}  // namespace

Result<CubeMap> resample_to_cube(const sh::EnvMap& env, int size, CubeResampleStats* stats) {
  if (!is_valid_cube_size(size)) {
    return Status::Error("resample_to_cube: cube size " + std::to_string(size) +
                         " is not a power of two in [8, 128]");
  }
  const int w = env.width, h = env.height;
  if (w <= 0 || h <= 0 || env.rgb.size() != static_cast<size_t>(w) * static_cast<size_t>(h) * 3) {
    return Status::Error("resample_to_cube: environment map is empty or rgb.size() != 3*w*h");
  }

  std::string why;
  if (!sh::validate_layout(env.layout, w, h, &why)) {
    return Status::Error("resample_to_cube: " + why);
  }

  CubeResampleStats local;
  CubeResampleStats& st = stats ? *stats : local;
  st = CubeResampleStats{};

  // Pass 1: validity, exact source solid angles and the largest of them.
  std::vector<double> source_omega(static_cast<size_t>(w) * h, 0.0);
  double max_omega = 0.0;
  const std::vector<double> coarse_omega = sh::texel_solid_angles(env.layout, w, h);
  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      const size_t s = static_cast<size_t>(row) * w + col;
      const float* px = &env.rgb[3 * s];
      bool usable = true;
      for (int c = 0; c < 3; ++c) usable = usable && std::isfinite(px[c]) && px[c] >= 0.0f;
      if (!usable) {
        ++st.skipped_texels;
        continue;
      }
      const double omega = coarse_omega[s];
      if (!(omega > 0.0) || !std::isfinite(omega)) continue;  // outside the layout's domain
      source_omega[s] = omega;
      max_omega = std::max(max_omega, omega);
    }
  }

  // Sub-sample count per axis: about kSamplesPerCubeTexel sub-samples across a cube texel for
  // the largest source texel (so upsampling leaves no holes), at least 2, and at most what
  // keeps the total under kSampleBudget (a 2k×1k map gets S = 2).
  constexpr double kSamplesPerCubeTexel = 8.0;
  constexpr double kSampleBudget = 16777216.0;  // 2^24
  const double mean_cube_omega = 4.0 * kPi / (6.0 * size * size);
  const double wanted = std::ceil(kSamplesPerCubeTexel * std::sqrt(max_omega / mean_cube_omega));
  const double budget = std::floor(std::sqrt(kSampleBudget / (static_cast<double>(w) * h)));
  const int sub = static_cast<int>(std::max(2.0, std::min(wanted, budget)));
  st.subsamples_per_texel = int64_t{sub} * sub;
  const int fine_w = w * sub, fine_h = h * sub;

  // Exact solid angles of the fine grid: one bulk call when the table is modest (much faster
  // for angular maps), else per sub-texel.
  std::vector<double> fine_omega;
  if (static_cast<int64_t>(fine_w) * fine_h <= (int64_t{1} << 22)) {
    fine_omega = sh::texel_solid_angles(env.layout, fine_w, fine_h);
  }

  std::vector<double> power(static_cast<size_t>(kCubeFaceCount) * size * size * 3, 0.0);
  std::vector<double> sub_weight(static_cast<size_t>(sub) * sub);
  std::vector<int> sub_texel(static_cast<size_t>(sub) * sub);

  for (int row = 0; row < h; ++row) {
    for (int col = 0; col < w; ++col) {
      const size_t s = static_cast<size_t>(row) * w + col;
      const double omega = source_omega[s];
      if (omega == 0.0) continue;
      const float* px = &env.rgb[3 * s];
      // The sub-texels of the same layout at sub× resolution: directions and exact weights.
      double weight_sum = 0.0;
      int count = 0;
      for (int j = 0; j < sub; ++j) {
        for (int i = 0; i < sub; ++i) {
          double dir[3];
          const int fc = col * sub + i, fr = row * sub + j;
          if (!sh::texel_direction(env.layout, fine_w, fine_h, fc, fr, dir)) continue;
          const double wgt = fine_omega.empty()
                                 ? sh::texel_solid_angle(env.layout, fine_w, fine_h, fc, fr)
                                 : fine_omega[static_cast<size_t>(fr) * fine_w + fc];
          int face = 0, cc = 0, cr = 0;
          if (!(wgt > 0.0) || !direction_to_cube_texel(size, dir, &face, &cc, &cr)) continue;
          sub_weight[count] = wgt;
          sub_texel[count] = (face * size + cr) * size + cc;
          weight_sum += wgt;
          ++count;
        }
      }
      if (count == 0) {
        // No usable sub-texel (cannot happen for the supported layouts): the whole power
        // goes to the cube texel of the source texel's centre, so none is lost.
        double dir[3];
        int face = 0, cc = 0, cr = 0;
        if (!sh::texel_direction(env.layout, w, h, col, row, dir) ||
            !direction_to_cube_texel(size, dir, &face, &cc, &cr)) {
          continue;
        }
        sub_weight[0] = 1.0;
        sub_texel[0] = (face * size + cr) * size + cc;
        weight_sum = 1.0;
        count = 1;
      }
      const double scale = omega / weight_sum;
      for (int c = 0; c < 3; ++c) st.source_power[c] += static_cast<double>(px[c]) * omega;
      for (int k = 0; k < count; ++k) {
        const double share = sub_weight[k] * scale;
        double* dst = &power[static_cast<size_t>(sub_texel[k]) * 3];
        for (int c = 0; c < 3; ++c) dst[c] += static_cast<double>(px[c]) * share;
      }
    }
  }

  CubeMap cube = make_black_cube_map(size);
  const std::vector<double> cube_omega = cube_face_solid_angles(size);
  const size_t face_texels = static_cast<size_t>(size) * size;
  for (size_t t = 0; t < static_cast<size_t>(kCubeFaceCount) * face_texels; ++t) {
    const double inv = 1.0 / cube_omega[t % face_texels];
    for (int c = 0; c < 3; ++c) cube.rgb[3 * t + c] = static_cast<float>(power[3 * t + c] * inv);
  }
  cube_map_power(cube, st.cube_power);
  return cube;
}

}  // namespace prt
