// Cube-map geometry for the Haar-wavelet relighting path; see prt/haar/cube_map.h.
#include "prt/haar/cube_map.h"

#include <algorithm>
#include <cmath>

namespace prt {

bool is_valid_cube_size(int size) noexcept {
  return size >= kMinCubeSize && size <= kMaxCubeSize && (size & (size - 1)) == 0;
}

CubeMap make_black_cube_map(int size) {
  CubeMap cube;
  cube.size = size;
  cube.rgb.assign(static_cast<size_t>(kCubeFaceCount) * size * size * 3, 0.0f);
  return cube;
}

void cube_face_point_direction(int face, double a, double b, double dir[3]) noexcept {
  double x = 0, y = 0, z = 0;
  switch (face) {
    case 0:
      x = 1, y = -b, z = a;
      break;  // +X
    case 1:
      x = -1, y = -b, z = -a;
      break;  // −X
    case 2:
      x = a, y = 1, z = -b;
      break;  // +Y
    case 3:
      x = a, y = -1, z = b;
      break;  // −Y
    case 4:
      x = -a, y = -b, z = 1;
      break;  // +Z
    default:
      x = a, y = -b, z = -1;
      break;  // −Z
  }
  const double inv = 1.0 / std::sqrt(x * x + y * y + z * z);
  dir[0] = x * inv;
  dir[1] = y * inv;
  dir[2] = z * inv;
}

void cube_texel_direction(int size, int face, int col, int row, double dir[3]) noexcept {
  const double a = 2.0 * (col + 0.5) / size - 1.0;
  const double b = 2.0 * (row + 0.5) / size - 1.0;
  cube_face_point_direction(face, a, b, dir);
}

bool direction_to_cube_face_point(const double dir[3], int* face, double* a, double* b) noexcept {
  const double x = dir[0], y = dir[1], z = dir[2];
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z)) return false;
  const double ax = std::fabs(x), ay = std::fabs(y), az = std::fabs(z);
  if (ax >= ay && ax >= az) {
    if (ax == 0) return false;
    // +X: (1, −b, a); −X: (−1, −b, −a).
    *face = x > 0 ? 0 : 1;
    *a = (x > 0 ? z : -z) / ax;
    *b = -y / ax;
  } else if (ay >= az) {
    // +Y: (a, 1, −b); −Y: (a, −1, b).
    *face = y > 0 ? 2 : 3;
    *a = x / ay;
    *b = (y > 0 ? -z : z) / ay;
  } else {
    // +Z: (−a, −b, 1); −Z: (a, −b, −1).
    *face = z > 0 ? 4 : 5;
    *a = (z > 0 ? -x : x) / az;
    *b = -y / az;
  }
  return true;
}

bool direction_to_cube_texel(int size, const double dir[3], int* face, int* col,
                             int* row) noexcept {
  double a = 0, b = 0;
  if (!direction_to_cube_face_point(dir, face, &a, &b)) return false;
  // a, b ∈ [−1, 1]; the edge a = 1 belongs to the last column.
  *col = std::clamp(static_cast<int>(std::floor((a + 1.0) * 0.5 * size)), 0, size - 1);
  *row = std::clamp(static_cast<int>(std::floor((b + 1.0) * 0.5 * size)), 0, size - 1);
  return true;
}

namespace {
// Solid angle of the face rectangle [0, a]×[0, b] (signed), the texel-corner primitive.
double corner_solid_angle(double a, double b) noexcept {
  return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0));
}
}  // namespace

double cube_face_rect_solid_angle(double a0, double a1, double b0, double b1) noexcept {
  return corner_solid_angle(a1, b1) - corner_solid_angle(a0, b1) - corner_solid_angle(a1, b0) +
         corner_solid_angle(a0, b0);
}

double cube_texel_solid_angle(int size, int col, int row) noexcept {
  const double step = 2.0 / size;
  const double a0 = -1.0 + col * step, b0 = -1.0 + row * step;
  return cube_face_rect_solid_angle(a0, a0 + step, b0, b0 + step);
}

std::vector<double> cube_face_solid_angles(int size) {
  std::vector<double> omega(static_cast<size_t>(size) * size);
  for (int row = 0; row < size; ++row)
    for (int col = 0; col < size; ++col)
      omega[static_cast<size_t>(row) * size + col] = cube_texel_solid_angle(size, col, row);
  return omega;
}

void cube_map_power(const CubeMap& cube, double power[3]) {
  power[0] = power[1] = power[2] = 0.0;
  const int n = cube.size;
  if (n <= 0 || cube.rgb.size() != static_cast<size_t>(cube.texel_count()) * 3) return;
  const std::vector<double> omega = cube_face_solid_angles(n);
  const size_t face_texels = static_cast<size_t>(n) * n;
  for (int face = 0; face < kCubeFaceCount; ++face) {
    for (size_t i = 0; i < face_texels; ++i) {
      const float* px = &cube.rgb[(face * face_texels + i) * 3];
      for (int c = 0; c < 3; ++c) power[c] += static_cast<double>(px[c]) * omega[i];
    }
  }
}

}  // namespace prt
