// sh/src/projection.cpp — environment-map projection (method and conventions in sh/projection.h).
#include "sh/projection.h"

#include <algorithm>
#include <cmath>

#include "gauss_legendre.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_check.h"

namespace prt::sh {
namespace {

bool skipped(TexelClass kind) {
  return kind == TexelClass::NaN || kind == TexelClass::Inf;
}

void count(TexelClass kind, ProjectionStats* stats) {
  if (kind == TexelClass::NaN) ++stats->nan_texels;
  if (kind == TexelClass::Inf) ++stats->inf_texels;
  if (kind == TexelClass::Negative) ++stats->negative_texels;
}

bool valid_input(const EnvMap& env, int order) {
  if (order < 1 || order > kMaxOrder || env.width <= 0 || env.height <= 0) return false;
  if (env.rgb.size() != static_cast<std::size_t>(env.width) * env.height * 3) return false;
  return env.layout == EnvLayout::LatLong ||
         validate_layout(env.layout, env.width, env.height, nullptr);
}

// Band-l block of M_jk = ∫ Y_j(P d) Y_k(d) dω, P(x, y, z) = (z, x, y), row-major (2l+1)².
// Quadrature: Gauss–Legendre with l+1 nodes in t = cos θ' (exact to degree 2l+1) times 2l+1
// equispaced azimuths (exact for frequencies ≤ 2l) in the primed frame, where the product of two
// band-l functions is a polynomial of degree 2l: the rule is exact.
std::vector<double> band_change_matrix(int l) {
  const int size = 2 * l + 1;
  const int order = l + 1;
  std::vector<double> nodes, weights;
  detail::gauss_legendre(l + 1, &nodes, &weights);
  std::vector<double> matrix(static_cast<std::size_t>(size) * size, 0.0);
  std::vector<double> primed(static_cast<std::size_t>(order) * order);
  std::vector<double> plain(primed.size());
  const int offset = l * l;
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const double t = nodes[i];
    const double s = std::sqrt(std::max(0.0, 1.0 - t * t));
    for (int j = 0; j < size; ++j) {
      const double phi = 2.0 * kPi * j / size;
      // Primed point p' = (x', y', z'); the scene direction d has x = y', y = z', z = x'.
      const double xp = s * std::cos(phi), yp = s * std::sin(phi), zp = t;
      evaluate(order, xp, yp, zp, primed.data());
      evaluate(order, yp, zp, xp, plain.data());
      const double w = weights[i] * 2.0 * kPi / size;
      for (int a = 0; a < size; ++a) {
        const double wa = w * primed[offset + a];
        double* row = &matrix[static_cast<std::size_t>(a) * size];
        for (int b = 0; b < size; ++b) row[b] += wa * plain[offset + b];
      }
    }
  }
  return matrix;
}

// Lat-long separable projection (see the header).
std::vector<double> project_latlong_separable(const EnvMap& env, int order,
                                              ProjectionStats* stats) {
  const int width = env.width, height = env.height;
  const int n2 = coefficient_count(order);
  const int frequencies = order;  // m = 0 .. order−1
  // Column tables: cos(mφ'), sin(mφ') with φ' = π/2 − φ, φ = 2π((col+½)/W − ½).
  std::vector<double> cos_table(static_cast<std::size_t>(frequencies) * width);
  std::vector<double> sin_table(cos_table.size());
  for (int col = 0; col < width; ++col) {
    const double phi = 2.0 * kPi * ((col + 0.5) / width - 0.5);
    const double phi_primed = 0.5 * kPi - phi;
    for (int m = 0; m < frequencies; ++m) {
      cos_table[static_cast<std::size_t>(m) * width + col] = std::cos(m * phi_primed);
      sin_table[static_cast<std::size_t>(m) * width + col] = std::sin(m * phi_primed);
    }
  }
  std::vector<double> primed(3 * static_cast<std::size_t>(n2), 0.0);  // c' per channel
  std::vector<double> channels(3 * static_cast<std::size_t>(width));
  std::vector<double> fourier_cos(3 * static_cast<std::size_t>(frequencies));
  std::vector<double> fourier_sin(fourier_cos.size());
  std::vector<double> legendre(n2);
  for (int row = 0; row < height; ++row) {
    double* red = channels.data();
    double* green = red + width;
    double* blue = green + width;
    const float* texels = &env.rgb[static_cast<std::size_t>(row) * width * 3];
    int used = 0;
    for (int col = 0; col < width; ++col) {
      float texel[3];  // the texel policy of sh/env_check.h
      const TexelClass kind = screen_texel(texels + 3 * col, texel);
      if (stats) count(kind, stats);
      red[col] = texel[0];
      green[col] = texel[1];
      blue[col] = texel[2];
      if (!skipped(kind)) ++used;
    }
    const double omega = texel_solid_angle(EnvLayout::LatLong, width, height, 0, row);
    if (stats) stats->solid_angle_sum += omega * used;
    if (used == 0) continue;
    // Fourier sums over the row, three channels at once.
    for (int m = 0; m < frequencies; ++m) {
      const double* c = &cos_table[static_cast<std::size_t>(m) * width];
      const double* s = &sin_table[static_cast<std::size_t>(m) * width];
      double cr = 0, cg = 0, cb = 0, sr = 0, sg = 0, sb = 0;
      if (m == 0) {
        for (int col = 0; col < width; ++col) {
          cr += red[col];
          cg += green[col];
          cb += blue[col];
        }
      } else {
        for (int col = 0; col < width; ++col) {
          cr += red[col] * c[col];
          cg += green[col] * c[col];
          cb += blue[col] * c[col];
          sr += red[col] * s[col];
          sg += green[col] * s[col];
          sb += blue[col] * s[col];
        }
      }
      fourier_cos[m] = cr;
      fourier_cos[frequencies + m] = cg;
      fourier_cos[2 * frequencies + m] = cb;
      fourier_sin[m] = sr;
      fourier_sin[frequencies + m] = sg;
      fourier_sin[2 * frequencies + m] = sb;
    }
    // Λ_l|m|(cos θ) sin-weighted: the basis at azimuth φ' = 0 of the primed frame.
    const double theta = kPi * (row + 0.5) / height;
    evaluate(order, std::sin(theta), 0.0, std::cos(theta), legendre.data());
    for (int channel = 0; channel < 3; ++channel) {
      double* out = &primed[static_cast<std::size_t>(channel) * n2];
      const double* fc = &fourier_cos[static_cast<std::size_t>(channel) * frequencies];
      const double* fs = &fourier_sin[static_cast<std::size_t>(channel) * frequencies];
      for (int l = 0; l < order; ++l) {
        out[index(l, 0)] += omega * legendre[index(l, 0)] * fc[0];
        for (int m = 1; m <= l; ++m) {
          const double lambda = omega * legendre[index(l, m)];
          out[index(l, m)] += lambda * fc[m];
          out[index(l, -m)] += lambda * fs[m];
        }
      }
    }
  }
  // Back to the scene basis: c = Mᵀ c', band by band.
  std::vector<double> result(3 * static_cast<std::size_t>(n2), 0.0);
  for (int l = 0; l < order; ++l) {
    const int size = 2 * l + 1;
    const std::vector<double> matrix = band_change_matrix(l);
    for (int channel = 0; channel < 3; ++channel) {
      const double* in = &primed[static_cast<std::size_t>(channel) * n2 + l * l];
      double* out = &result[static_cast<std::size_t>(channel) * n2 + l * l];
      for (int j = 0; j < size; ++j)
        for (int k = 0; k < size; ++k)
          out[k] += matrix[static_cast<std::size_t>(j) * size + k] * in[j];
    }
  }
  return result;
}

}  // namespace

std::vector<double> project_direct(const EnvMap& env, int order, ProjectionStats* stats) {
  if (!valid_input(env, order)) return {};
  const int n2 = coefficient_count(order);
  const std::vector<double> solid_angles = texel_solid_angles(env.layout, env.width, env.height);
  std::vector<double> result(3 * static_cast<std::size_t>(n2), 0.0);
  std::vector<double> row_sum(result.size());
  std::vector<double> basis(n2);
  for (int row = 0; row < env.height; ++row) {
    std::fill(row_sum.begin(), row_sum.end(), 0.0);
    for (int col = 0; col < env.width; ++col) {
      const std::size_t texel = static_cast<std::size_t>(row) * env.width + col;
      const double omega = solid_angles[texel];
      double dir[3];
      if (!(omega > 0.0) || !texel_direction(env.layout, env.width, env.height, col, row, dir))
        continue;
      float rgb[3];  // the texel policy of sh/env_check.h
      const TexelClass kind = screen_texel(&env.rgb[texel * 3], rgb);
      if (stats) count(kind, stats);
      if (skipped(kind)) continue;
      if (stats) stats->solid_angle_sum += omega;
      evaluate(order, dir[0], dir[1], dir[2], basis.data());
      for (int channel = 0; channel < 3; ++channel) {
        const double weight = omega * rgb[channel];
        if (weight == 0.0) continue;
        double* out = &row_sum[static_cast<std::size_t>(channel) * n2];
        for (int k = 0; k < n2; ++k) out[k] += weight * basis[k];
      }
    }
    for (std::size_t i = 0; i < result.size(); ++i) result[i] += row_sum[i];
  }
  return result;
}

std::vector<double> project(const EnvMap& env, int order, ProjectionStats* stats) {
  if (!valid_input(env, order)) return {};
  if (env.layout == EnvLayout::LatLong && order <= kSeparableMaxOrder)
    return project_latlong_separable(env, order, stats);
  return project_direct(env, order, stats);
}

void reconstruct(const double* coefficients, int channels, int order, const double dir[3],
                 double* out) {
  for (int c = 0; c < channels; ++c) out[c] = 0.0;
  if (order < 1 || order > kMaxOrder) return;
  const double length = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
  if (!(length > 0.0) || !std::isfinite(length)) return;
  const int n2 = coefficient_count(order);
  std::vector<double> basis(n2);
  evaluate(order, dir[0] / length, dir[1] / length, dir[2] / length, basis.data());
  for (int c = 0; c < channels; ++c) {
    double sum = 0.0;
    const double* coefficient = coefficients + static_cast<std::size_t>(c) * n2;
    for (int k = 0; k < n2; ++k) sum += coefficient[k] * basis[k];
    out[c] = sum;
  }
}

}  // namespace prt::sh
