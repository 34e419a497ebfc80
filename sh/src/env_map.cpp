// sh/src/env_map.cpp — environment-map layouts (conventions and formulas in sh/env_map.h).
#include "sh/env_map.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "numerics/gauss_legendre.h"
#include "sh/constants.h"

namespace prt::sh {
namespace {

// ---- cube faces -------------------------------------------------------------------------------
// A face: direction = normal + a·right + b·down, with a (right) and b (down) in [−1, 1].
struct CubeFace {
  std::array<double, 3> normal, right, down;
};

// Cross faces, by cell; index = row * 3 + col; faces with an all-zero normal are empty cells.
constexpr CubeFace kNoFace{{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
constexpr CubeFace kPosX{{1, 0, 0}, {0, 0, 1}, {0, -1, 0}};
constexpr CubeFace kNegX{{-1, 0, 0}, {0, 0, -1}, {0, -1, 0}};
constexpr CubeFace kPosY{{0, 1, 0}, {1, 0, 0}, {0, 0, -1}};
constexpr CubeFace kNegY{{0, -1, 0}, {1, 0, 0}, {0, 0, 1}};
constexpr CubeFace kNegZ{{0, 0, -1}, {1, 0, 0}, {0, -1, 0}};
constexpr CubeFace kPosZCross{{0, 0, 1}, {1, 0, 0}, {0, 1, 0}};    // stored upside down
constexpr CubeFace kPosZFaces{{0, 0, 1}, {-1, 0, 0}, {0, -1, 0}};  // seen from the centre

constexpr std::array<CubeFace, 12> kCrossCells = {kNoFace, kPosY,      kNoFace,  //
                                                  kNegX,   kNegZ,      kPosX,    //
                                                  kNoFace, kNegY,      kNoFace,  //
                                                  kNoFace, kPosZCross, kNoFace};
constexpr std::array<CubeFace, 6> kStackedFaces = {kPosX, kNegX, kPosY, kNegY, kPosZFaces, kNegZ};

bool is_empty(const CubeFace& face) {
  return face.normal[0] == 0 && face.normal[1] == 0 && face.normal[2] == 0;
}

// The face holding texel (col, row) of a cube layout, its size and the texel's position inside
// the face. False for empty cells.
bool locate_cube_texel(EnvLayout layout, int width, int height, int col, int row, CubeFace* face,
                       int* size, int* face_col, int* face_row) {
  if (layout == EnvLayout::Cross) {
    const int s = width / 3;
    if (s <= 0 || height != 4 * s || width != 3 * s) return false;
    *face = kCrossCells[(row / s) * 3 + col / s];
    *size = s;
    *face_col = col % s;
    *face_row = row % s;
  } else {
    const int s = width;
    if (s <= 0 || height != 6 * s) return false;
    *face = kStackedFaces[row / s];
    *size = s;
    *face_col = col;
    *face_row = row % s;
  }
  return !is_empty(*face);
}

// atan(ab/√(a²+b²+1)): the solid angle of the face rectangle [0, a] × [0, b] (signed).
double corner_solid_angle(double a, double b) {
  return std::atan2(a * b, std::sqrt(a * a + b * b + 1.0));
}

double cube_texel_solid_angle(int size, int face_col, int face_row) {
  const double a0 = 2.0 * face_col / size - 1.0, a1 = 2.0 * (face_col + 1) / size - 1.0;
  const double b0 = 2.0 * face_row / size - 1.0, b1 = 2.0 * (face_row + 1) / size - 1.0;
  return corner_solid_angle(a1, b1) - corner_solid_angle(a0, b1) - corner_solid_angle(a1, b0) +
         corner_solid_angle(a0, b0);
}

// ---- lat-long -----------------------------------------------------------------------------------
// (cos θ0 − cos θ1)·2π/W for row band [θ0, θ1], written as 2 sin(θ̄) sin(Δθ/2) for accuracy.
double latlong_row_solid_angle(int width, int height, int row) {
  const double theta0 = kPi * row / height, theta1 = kPi * (row + 1) / height;
  const double band = 2.0 * std::sin(0.5 * (theta0 + theta1)) * std::sin(0.5 * (theta1 - theta0));
  return band * 2.0 * kPi / width;
}

// ---- angular ------------------------------------------------------------------------------------
// G(r)/r² = (1 − cos πr)/r² = 2 (sin(πr/2)/r)², continuous at r = 0 (π²/2).
double g_over_r2(double r) {
  if (r < 1e-8) return 0.5 * kPi * kPi;
  const double s = std::sin(0.5 * kPi * r) / r;
  return 2.0 * s * s;
}

// Gauss–Legendre rules mapped to [0, 1]: 3 points for short pieces, 6 points per sub-piece
// otherwise.
struct QuadratureRule {
  std::vector<double> nodes, weights;
  explicit QuadratureRule(int n) {
    numerics::gauss_legendre(n, &nodes, &weights);
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      nodes[i] = 0.5 * (nodes[i] + 1.0);
      weights[i] *= 0.5;
    }
  }
};

const QuadratureRule& short_piece_rule() {
  static const QuadratureRule rule(3);
  return rule;
}
const QuadratureRule& long_piece_rule() {
  static const QuadratureRule rule(6);
  return rule;
}

// ∫ G̃(r) dφ along the straight segment p0 → p1 of the (u, v) plane, G̃(r) = 1 − cos(π min(r, 1)).
// The segment is split where it crosses the unit circle; outside pieces give 2·Δφ exactly,
// inside pieces are integrated by Gauss–Legendre: 3 points for pieces of length ≤ 0.01 (texel
// edges of maps ≥ 200 wide), else 6 points on each of ⌈length/0.05⌉ sub-pieces. The integrand is
// entire in the parameter with derivatives of order π^k, so the error bound of the n-point rule,
// ∝ length^(2n)·f^(2n)/(2n)!, is below 1e-14 relative in both cases.
double angular_edge_integral(double u0, double v0, double u1, double v1) {
  const double eu = u1 - u0, ev = v1 - v0;
  const double length2 = eu * eu + ev * ev;
  if (length2 == 0.0) return 0.0;
  // Split parameters: roots of |p0 + t e|² = 1 inside (0, 1).
  std::array<double, 4> cuts{0.0, 1.0, 1.0, 1.0};
  int cut_count = 1;
  const double half_b = u0 * eu + v0 * ev;
  const double c = u0 * u0 + v0 * v0 - 1.0;
  const double discriminant = half_b * half_b - length2 * c;
  if (discriminant > 0.0) {
    const double root = std::sqrt(discriminant);
    // Stable quadratic roots.
    const double q = half_b >= 0 ? -(half_b + root) : -(half_b - root);
    double t1 = q / length2, t2 = q != 0.0 ? c / q : t1;
    if (t1 > t2) std::swap(t1, t2);
    if (t1 > 0.0 && t1 < 1.0) cuts[cut_count++] = t1;
    if (t2 > 0.0 && t2 < 1.0) cuts[cut_count++] = t2;
  }
  cuts[cut_count++] = 1.0;
  const double cross = u0 * ev - v0 * eu;  // p0 × e: dφ = cross / r² dt
  double total = 0.0;
  for (int piece = 0; piece + 1 < cut_count; ++piece) {
    const double ta = cuts[piece], tb = cuts[piece + 1];
    if (tb <= ta) continue;
    const double tm = 0.5 * (ta + tb);
    const double um = u0 + tm * eu, vm = v0 + tm * ev;
    if (um * um + vm * vm >= 1.0) {
      const double ua = u0 + ta * eu, va = v0 + ta * ev;
      const double ub = u0 + tb * eu, vb = v0 + tb * ev;
      total += 2.0 * std::atan2(ua * vb - va * ub, ua * ub + va * vb);
      continue;
    }
    if (cross == 0.0) continue;  // the segment's line passes through the centre: dφ = 0
    const double piece_length = (tb - ta) * std::sqrt(length2);
    const bool short_piece = piece_length <= 0.01;
    const QuadratureRule& rule = short_piece ? short_piece_rule() : long_piece_rule();
    const int sub_pieces =
        short_piece ? 1 : std::max(1, static_cast<int>(std::ceil(piece_length / 0.05)));
    const double h = (tb - ta) / sub_pieces;
    double sum = 0.0;
    for (int s = 0; s < sub_pieces; ++s) {
      const double start = ta + s * h;
      for (std::size_t i = 0; i < rule.nodes.size(); ++i) {
        const double t = start + h * rule.nodes[i];
        const double u = u0 + t * eu, v = v0 + t * ev;
        sum += rule.weights[i] * g_over_r2(std::sqrt(u * u + v * v));
      }
    }
    total += cross * h * sum;
  }
  return total;
}

// Texel (col, row) of a w×w angular map spans u ∈ [u(col), u(col+1)], v ∈ [v(row+1), v(row)].
double angular_u(int width, int col) {
  return 2.0 * col / width - 1.0;
}
double angular_v(int width, int row) {
  return 1.0 - 2.0 * row / width;
}

// Distance from the image centre to the nearest point of the texel's square.
double angular_min_radius(int width, int col, int row) {
  const double u0 = angular_u(width, col), u1 = angular_u(width, col + 1);
  const double v0 = angular_v(width, row + 1), v1 = angular_v(width, row);
  const double u = std::clamp(0.0, u0, u1), v = std::clamp(0.0, v0, v1);
  return std::sqrt(u * u + v * v);
}

// Bottom edge at v(row+1) directed +u; right edge at u(col+1) directed +v; the top and left
// edges are the same integrals as the neighbours' bottom and right edges, reversed.
double angular_horizontal_edge(int width, int col, int row_line) {
  const double v = angular_v(width, row_line);
  return angular_edge_integral(angular_u(width, col), v, angular_u(width, col + 1), v);
}
double angular_vertical_edge(int width, int col_line, int row) {
  const double u = angular_u(width, col_line);
  return angular_edge_integral(u, angular_v(width, row + 1), u, angular_v(width, row));
}

double angular_texel_solid_angle(int width, int col, int row) {
  if (angular_min_radius(width, col, row) >= 1.0) return 0.0;
  return angular_horizontal_edge(width, col, row + 1) + angular_vertical_edge(width, col + 1, row) -
         angular_horizontal_edge(width, col, row) - angular_vertical_edge(width, col, row);
}

bool in_range(int width, int height, int col, int row) {
  return width > 0 && height > 0 && col >= 0 && row >= 0 && col < width && row < height;
}

bool normalise(const double in[3], double out[3]) {
  const double length = std::sqrt(in[0] * in[0] + in[1] * in[1] + in[2] * in[2]);
  if (!(length > 0.0) || !std::isfinite(length)) return false;
  for (int i = 0; i < 3; ++i) out[i] = in[i] / length;
  return true;
}

// Face and face-local (a, b) of a direction on a cube layout; returns the face index (cross cell
// index or stacked face index).
int cube_face_of(EnvLayout layout, const double d[3], double* a, double* b) {
  const double ax = std::abs(d[0]), ay = std::abs(d[1]), az = std::abs(d[2]);
  int stacked;  // index into kStackedFaces
  if (ax >= ay && ax >= az) {
    stacked = d[0] >= 0 ? 0 : 1;
  } else if (ay >= az) {
    stacked = d[1] >= 0 ? 2 : 3;
  } else {
    stacked = d[2] >= 0 ? 4 : 5;
  }
  int index = stacked;
  CubeFace face = kStackedFaces[stacked];
  if (layout == EnvLayout::Cross) {
    static constexpr std::array<int, 6> kCellOfStacked = {5, 3, 1, 7, 10, 4};
    index = kCellOfStacked[stacked];
    face = kCrossCells[index];
  }
  const double n = d[0] * face.normal[0] + d[1] * face.normal[1] + d[2] * face.normal[2];
  *a = (d[0] * face.right[0] + d[1] * face.right[1] + d[2] * face.right[2]) / n;
  *b = (d[0] * face.down[0] + d[1] * face.down[1] + d[2] * face.down[2]) / n;
  return index;
}

}  // namespace

const char* layout_name(EnvLayout layout) noexcept {
  switch (layout) {
    case EnvLayout::LatLong:
      return "latlong";
    case EnvLayout::Angular:
      return "angular";
    case EnvLayout::Cross:
      return "cross";
    case EnvLayout::Faces:
      return "faces";
  }
  return "unknown";
}

bool parse_layout(std::string_view text, EnvLayout* layout) noexcept {
  if (text == "latlong" || text == "lat-long" || text == "equirect") {
    *layout = EnvLayout::LatLong;
  } else if (text == "angular" || text == "probe") {
    *layout = EnvLayout::Angular;
  } else if (text == "cross") {
    *layout = EnvLayout::Cross;
  } else if (text == "faces") {
    *layout = EnvLayout::Faces;
  } else {
    return false;
  }
  return true;
}

bool validate_layout(EnvLayout layout, int width, int height, std::string* why) noexcept {
  auto fail = [&](const char* reason) {
    if (why) *why = reason;
    return false;
  };
  if (width <= 0 || height <= 0) return fail("the image is empty");
  switch (layout) {
    case EnvLayout::LatLong:
      if (width != 2 * height) return fail("a lat-long map must be twice as wide as it is high");
      break;
    case EnvLayout::Angular:
      if (width != height) return fail("an angular map must be square");
      break;
    case EnvLayout::Cross:
      if (width % 3 != 0 || 3 * height != 4 * width)
        return fail("a vertical cross must be 3:4 with a width divisible by 3");
      break;
    case EnvLayout::Faces:
      if (height != 6 * width) return fail("stacked faces must be 6 times as high as wide");
      break;
  }
  return true;
}

EnvLayout guess_layout(int width, int height, bool* ok) noexcept {
  const EnvLayout candidates[] = {EnvLayout::LatLong, EnvLayout::Angular, EnvLayout::Cross,
                                  EnvLayout::Faces};
  for (EnvLayout layout : candidates) {
    if (validate_layout(layout, width, height, nullptr)) {
      if (ok) *ok = true;
      return layout;
    }
  }
  if (ok) *ok = false;
  return EnvLayout::LatLong;
}

bool texel_direction(EnvLayout layout, int width, int height, int col, int row,
                     double dir[3]) noexcept {
  if (!in_range(width, height, col, row)) return false;
  switch (layout) {
    case EnvLayout::LatLong: {
      const double theta = kPi * (row + 0.5) / height;
      const double phi = 2.0 * kPi * ((col + 0.5) / width - 0.5);
      const double s = std::sin(theta);
      dir[0] = s * std::cos(phi);
      dir[1] = std::cos(theta);
      dir[2] = s * std::sin(phi);
      return true;
    }
    case EnvLayout::Angular: {
      if (width != height) return false;
      double u = 2.0 * (col + 0.5) / width - 1.0;
      double v = 1.0 - 2.0 * (row + 0.5) / width;
      double r = std::sqrt(u * u + v * v);
      if (r > 1.0) {
        const double r_min = angular_min_radius(width, col, row);
        if (r_min >= 1.0) return false;
        const double scale = 0.5 * (r_min + 1.0) / r;
        u *= scale;
        v *= scale;
        r *= scale;
      }
      const double theta = kPi * r;
      // sin θ / r = π sinc(π r), finite at the centre.
      const double sin_over_r = r < 1e-12 ? kPi : std::sin(theta) / r;
      dir[0] = sin_over_r * u;
      dir[1] = sin_over_r * v;
      dir[2] = -std::cos(theta);
      return true;
    }
    case EnvLayout::Cross:
    case EnvLayout::Faces: {
      CubeFace face;
      int size, face_col, face_row;
      if (!locate_cube_texel(layout, width, height, col, row, &face, &size, &face_col, &face_row))
        return false;
      const double a = 2.0 * (face_col + 0.5) / size - 1.0;
      const double b = 2.0 * (face_row + 0.5) / size - 1.0;
      double d[3];
      for (int i = 0; i < 3; ++i) d[i] = face.normal[i] + a * face.right[i] + b * face.down[i];
      return normalise(d, dir);
    }
  }
  return false;
}

double texel_solid_angle(EnvLayout layout, int width, int height, int col, int row) noexcept {
  if (!in_range(width, height, col, row)) return 0.0;
  switch (layout) {
    case EnvLayout::LatLong:
      return latlong_row_solid_angle(width, height, row);
    case EnvLayout::Angular:
      if (width != height) return 0.0;
      return angular_texel_solid_angle(width, col, row);
    case EnvLayout::Cross:
    case EnvLayout::Faces: {
      CubeFace face;
      int size, face_col, face_row;
      if (!locate_cube_texel(layout, width, height, col, row, &face, &size, &face_col, &face_row))
        return 0.0;
      return cube_texel_solid_angle(size, face_col, face_row);
    }
  }
  return 0.0;
}

std::vector<double> texel_solid_angles(EnvLayout layout, int width, int height) {
  if (width <= 0 || height <= 0) return {};
  std::vector<double> out(static_cast<std::size_t>(width) * height, 0.0);
  if (layout == EnvLayout::LatLong) {
    for (int row = 0; row < height; ++row) {
      const double omega = latlong_row_solid_angle(width, height, row);
      std::fill_n(out.begin() + static_cast<std::ptrdiff_t>(row) * width, width, omega);
    }
  } else if (layout == EnvLayout::Angular) {
    if (width != height) return out;
    const int w = width;
    // horizontal[line][col], line = 0..w; vertical[row][line], line = 0..w.
    std::vector<double> horizontal(static_cast<std::size_t>(w + 1) * w);
    std::vector<double> vertical(static_cast<std::size_t>(w) * (w + 1));
    auto near_disc = [&](int col, int row) { return angular_min_radius(w, col, row) < 1.0; };
    for (int line = 0; line <= w; ++line) {
      for (int col = 0; col < w; ++col) {
        const bool needed =
            (line < w && near_disc(col, line)) || (line > 0 && near_disc(col, line - 1));
        horizontal[static_cast<std::size_t>(line) * w + col] =
            needed ? angular_horizontal_edge(w, col, line) : 0.0;
      }
    }
    for (int row = 0; row < w; ++row) {
      for (int line = 0; line <= w; ++line) {
        const bool needed =
            (line < w && near_disc(line, row)) || (line > 0 && near_disc(line - 1, row));
        vertical[static_cast<std::size_t>(row) * (w + 1) + line] =
            needed ? angular_vertical_edge(w, line, row) : 0.0;
      }
    }
    for (int row = 0; row < w; ++row) {
      for (int col = 0; col < w; ++col) {
        if (!near_disc(col, row)) continue;
        out[static_cast<std::size_t>(row) * w + col] =
            horizontal[static_cast<std::size_t>(row + 1) * w + col] +
            vertical[static_cast<std::size_t>(row) * (w + 1) + col + 1] -
            horizontal[static_cast<std::size_t>(row) * w + col] -
            vertical[static_cast<std::size_t>(row) * (w + 1) + col];
      }
    }
  } else {
    for (int row = 0; row < height; ++row)
      for (int col = 0; col < width; ++col)
        out[static_cast<std::size_t>(row) * width + col] =
            texel_solid_angle(layout, width, height, col, row);
  }
  return out;
}

bool direction_to_texel(EnvLayout layout, int width, int height, const double dir[3], double* col,
                        double* row) noexcept {
  double d[3];
  if (width <= 0 || height <= 0 || !normalise(dir, d)) return false;
  switch (layout) {
    case EnvLayout::LatLong: {
      const double u = 0.5 + std::atan2(d[2], d[0]) / (2.0 * kPi);
      const double v = std::acos(std::clamp(d[1], -1.0, 1.0)) / kPi;
      *col = u * width;
      *row = v * height;
      return true;
    }
    case EnvLayout::Angular: {
      if (width != height) return false;
      const double rho = std::sqrt(d[0] * d[0] + d[1] * d[1]);
      const double theta = std::atan2(rho, -d[2]);
      const double r = theta / kPi;
      double u = 0.0, v = 0.0;
      if (rho > 0.0) {
        u = r * d[0] / rho;
        v = r * d[1] / rho;
      } else if (d[2] > 0.0) {
        u = 1.0;  // +Z is the whole rim; pick its rightmost point
      }
      *col = 0.5 * (u + 1.0) * width;
      *row = 0.5 * (1.0 - v) * width;
      return true;
    }
    case EnvLayout::Cross:
    case EnvLayout::Faces: {
      if (!validate_layout(layout, width, height, nullptr)) return false;
      double a, b;
      const int index = cube_face_of(layout, d, &a, &b);
      const int size = layout == EnvLayout::Cross ? width / 3 : width;
      const int cell_col = layout == EnvLayout::Cross ? index % 3 : 0;
      const int cell_row = layout == EnvLayout::Cross ? index / 3 : index;
      *col = (cell_col + 0.5 * (a + 1.0)) * size;
      *row = (cell_row + 0.5 * (b + 1.0)) * size;
      return true;
    }
  }
  return false;
}

void sample_bilinear(const EnvMap& env, const double dir[3], float rgb[3]) noexcept {
  rgb[0] = rgb[1] = rgb[2] = 0.0f;
  double col, row;
  if (env.rgb.size() != static_cast<std::size_t>(env.width) * env.height * 3 ||
      !direction_to_texel(env.layout, env.width, env.height, dir, &col, &row))
    return;
  // Bounds of the filter region: the whole image, or the face holding the point.
  int x_lo = 0, x_hi = env.width - 1, y_lo = 0, y_hi = env.height - 1;
  const bool wrap = env.layout == EnvLayout::LatLong;
  if (env.layout == EnvLayout::Cross || env.layout == EnvLayout::Faces) {
    const int size = env.layout == EnvLayout::Cross ? env.width / 3 : env.width;
    const int cell_col = std::clamp(static_cast<int>(col) / size, 0, env.width / size - 1);
    const int cell_row = std::clamp(static_cast<int>(row) / size, 0, env.height / size - 1);
    x_lo = cell_col * size;
    x_hi = x_lo + size - 1;
    y_lo = cell_row * size;
    y_hi = y_lo + size - 1;
  }
  const double x = col - 0.5, y = row - 0.5;
  const double x_floor = std::floor(x), y_floor = std::floor(y);
  const double fx = x - x_floor, fy = y - y_floor;
  const int x0 = static_cast<int>(x_floor), y0 = static_cast<int>(y_floor);
  auto column = [&](int c) {
    if (wrap) return ((c % env.width) + env.width) % env.width;
    return std::clamp(c, x_lo, x_hi);
  };
  const int cols[2] = {column(x0), column(x0 + 1)};
  const int rows[2] = {std::clamp(y0, y_lo, y_hi), std::clamp(y0 + 1, y_lo, y_hi)};
  const double weights[2][2] = {{(1 - fx) * (1 - fy), fx * (1 - fy)}, {(1 - fx) * fy, fx * fy}};
  double sum[3] = {0, 0, 0};
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const float* texel = &env.rgb[(static_cast<std::size_t>(rows[j]) * env.width + cols[i]) * 3];
      for (int c = 0; c < 3; ++c) sum[c] += weights[j][i] * texel[c];
    }
  }
  for (int c = 0; c < 3; ++c) rgb[c] = static_cast<float>(sum[c]);
}

}  // namespace prt::sh
