// sh/src/projection.cpp — environment-map projection (method and conventions in sh/projection.h).
#include "sh/projection.h"

#include <algorithm>
#include <cmath>

#include <cstdint>
#include <limits>
#include <vector>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_check.h"
#include "sh/polar_axis.h"

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

// ---- separable lat-long projection (see the header) ---------------------------------------

// Σ f_ch·x and Σ f_ch·y over n entries for the three channels f_0, f_1, f_2 (spaced `stride`
// apart): out = {Σ f_0 x, Σ f_1 x, Σ f_2 x, Σ f_0 y, Σ f_1 y, Σ f_2 y}. One pass, six independent
// chains, so each table entry is loaded once for the three channels.
void dot_three(const double* f, std::size_t stride, const double* x, const double* y, int n,
               double out[6]) {
  const double* f0 = f;
  const double* f1 = f + stride;
  const double* f2 = f + 2 * stride;
  double a0 = 0, a1 = 0, a2 = 0, b0 = 0, b1 = 0, b2 = 0;
  for (int i = 0; i < n; ++i) {
    a0 += f0[i] * x[i];
    a1 += f1[i] * x[i];
    a2 += f2[i] * x[i];
    b0 += f0[i] * y[i];
    b1 += f1[i] * y[i];
    b2 += f2[i] * y[i];
  }
  out[0] = a0, out[1] = a1, out[2] = a2, out[3] = b0, out[4] = b1, out[5] = b2;
}

// Stage 1: per row r and frequency m < order, the row's Fourier sums times the row's solid angle
//   F[r][m] = ω_r Σ_col f_col (cos mφ'_col, sin mφ'_col),  φ'_col = π/2 − φ_col,
// for the three channels: out[(r·order + m)·6 + {0,1,2}] cosine (r, g, b), {3,4,5} sine.
// With A_k = Σ_c f_c e^(−2πi k (c+½)/W), Σ_c f_c e^(i m φ'_c) = (−i)^m A_m (φ'_c = 3π/2 −
// 2π(c+½)/W), and A_(W−k) = −conj(A_k), A_(k+W) = −A_k: only k ≤ W/2 are summed; the exponentials
// come from a table of cos(πj/W), sin(πj/W), j < 2W (the angle k(2c+1)π/W reduced exactly).
class FourierStage {
 public:
  FourierStage(const EnvMap& env, int order)
      : env_(env),
        order_(order),
        width_(env.width),
        computed_(std::min(order, env.width / 2 + 1)),
        cos_(2 * static_cast<std::size_t>(width_)),
        sin_(cos_.size()) {
    for (int j = 0; j < 2 * width_; ++j) {
      cos_[j] = std::cos(kPi * j / width_);
      sin_[j] = std::sin(kPi * j / width_);
    }
  }

  int computed_frequencies() const { return computed_; }

  // Rows [first, first + count) into out (layout above); counts skipped texels into stats.
  void run(int first, int count, ProjectionStats* stats, double* out) {
    const int w = width_;
    rows_.resize(static_cast<std::size_t>(count) * 3 * w);  // every entry written by load_row
    omega_.resize(count);
    for (int i = 0; i < count; ++i)
      omega_[i] = load_row(first + i, &rows_[3 * i * std::size_t(w)], stats);
    re_.assign(static_cast<std::size_t>(count) * computed_ * 3, 0.0);  // rows without texels: 0
    im_.assign(re_.size(), 0.0);
    row_cos_.resize(w);
    row_sin_.resize(w);
    const int period = 2 * w;
    for (int k = 0; k < computed_; ++k) {
      // e^(−2πi k (c+½)/W) = cos(πj/W) − i sin(πj/W), j = k(2c+1) mod 2W, stepping by 2k.
      const int step = (2 * k) % period;
      int j = k % period;
      for (int c = 0; c < w; ++c) {
        row_cos_[c] = cos_[j];
        row_sin_[c] = sin_[j];
        j += step;
        if (j >= period) j -= period;
      }
      for (int i = 0; i < count; ++i) {
        if (omega_[i] == 0.0) continue;
        double sums[6];
        dot_three(&rows_[3 * std::size_t(i) * w], w, row_cos_.data(), row_sin_.data(), w, sums);
        for (int ch = 0; ch < 3; ++ch) {
          re_[(std::size_t(i) * computed_ + k) * 3 + ch] = sums[ch];
          im_[(std::size_t(i) * computed_ + k) * 3 + ch] = -sums[3 + ch];
        }
      }
    }
    for (int i = 0; i < count; ++i)
      write_row(i, out + static_cast<std::size_t>(first + i) * order_ * 6);
  }

 private:
  // Copies a row's valid texels to doubles (channel-major), zero for skipped ones; returns the
  // row's texel solid angle, or 0 when the row has no valid texel.
  double load_row(int row, double* channels, ProjectionStats* stats) const {
    const int w = width_;
    const float* texels = &env_.rgb[static_cast<std::size_t>(row) * w * 3];
    int used = 0;
    for (int col = 0; col < w; ++col) {
      float texel[3];  // the texel policy of sh/env_check.h
      const TexelClass kind = screen_texel(texels + 3 * col, texel);
      if (stats) count(kind, stats);
      for (int ch = 0; ch < 3; ++ch) channels[std::size_t(ch) * w + col] = texel[ch];
      if (!skipped(kind)) ++used;
    }
    const double omega = texel_solid_angle(EnvLayout::LatLong, w, env_.height, 0, row);
    if (stats) stats->solid_angle_sum += omega * used;
    return used > 0 ? omega : 0.0;
  }

  // F_m = ω (−i)^m A_m for m < order, from the computed A_k.
  void write_row(int i, double* out) const {
    const int w = width_;
    for (int m = 0; m < order_; ++m) {
      // A_m from A_k, k = m mod 2W folded into [0, W/2] by A_(k+W) = −A_k, A_(W−k) = −conj(A_k).
      int k = m % (2 * w);
      double sign = 1.0, conj = 1.0;
      if (k >= w) {
        k -= w;
        sign = -sign;
      }
      if (k > w / 2) {
        k = w - k;
        sign = -sign;
        conj = -1.0;
      }
      double* f = out + static_cast<std::size_t>(m) * 6;
      for (int ch = 0; ch < 3; ++ch) {
        const double re = sign * re_[(std::size_t(i) * computed_ + k) * 3 + ch];
        const double im = sign * conj * im_[(std::size_t(i) * computed_ + k) * 3 + ch];
        double c = re, s = im;  // (−i)^m (re + i im)
        switch (m % 4) {
          case 1:
            c = im, s = -re;
            break;
          case 2:
            c = -re, s = -im;
            break;
          case 3:
            c = -im, s = re;
            break;
          default:
            break;
        }
        f[ch] = omega_[i] * c;
        f[3 + ch] = omega_[i] * s;
      }
    }
  }

  const EnvMap& env_;
  const int order_, width_, computed_;
  std::vector<double> cos_, sin_, rows_, omega_, re_, im_, row_cos_, row_sin_;
};

// Stage 2: the +y-polar coefficients c'_lm = Σ_r Λ_lm(θ_r) F[r][|m|] (cosine part for m ≥ 0,
// sine part for m < 0), with Λ_lm(θ) = Q_lm(cos θ)·sin^m θ in the notation of sh/src/basis.cpp
// (the same seeds Q_mm and recurrence coefficients, so Λ equals sh::evaluate's value at φ' = 0).
// Rows r and H−1−r (θ and π−θ) have the same solid angle and Q_lm(−z) = (−1)^(l−m) Q_lm(z), so
// each pair is summed once with E = F_r + F_(H−1−r) for even l − m and O = F_r − F_(H−1−r) for
// odd. Frequency by frequency: the column Q_lm, l = m..order−1, is run for all row pairs at once
// into a per-frequency accumulator, so the working set stays small at any order. sin^m θ is
// folded into E and O; when it falls below the smallest normal double the pair's column is
// dropped (|Λ_lm| < 1e-94 then, as sh::evaluate, since |Q_lm| < 1e214).
class LegendreStage {
 public:
  LegendreStage(int height, int order) : height_(height), order_(order), pairs_((height + 1) / 2) {
    z_.resize(pairs_);
    sin_theta_.resize(pairs_);
    power_.assign(pairs_, 1.0);
    for (int p = 0; p < pairs_; ++p) {
      const double theta = kPi * (p + 0.5) / height;
      z_[p] = std::cos(theta);
      sin_theta_[p] = std::sin(theta);
    }
    a_.resize(order);
    ab_.resize(order);
    acc_.resize(static_cast<std::size_t>(order) * 6);
    even_odd_.resize(static_cast<std::size_t>(pairs_) * 12);
  }

  // Adds frequency m's coefficients c'_l,±m (l = m..order−1) into primed (channel-major, order²
  // per channel), from the Fourier sums F (stage 1 layout).
  void run(int m, double seed, const double* fourier, double* primed) {
    const int n2 = order_ * order_;
    if (m > 0)
      for (int p = 0; p < pairs_; ++p) {
        power_[p] *= sin_theta_[p];
        if (power_[p] < std::numeric_limits<double>::min()) power_[p] = 0.0;
      }
    for (int l = m + 2; l < order_; ++l) {
      const double ll = double(l) * l, mm = double(m) * m, l1 = double(l - 1) * (l - 1);
      a_[l] = std::sqrt((4.0 * ll - 1.0) / (ll - mm));
      ab_[l] = a_[l] * std::sqrt((l1 - mm) / (4.0 * l1 - 1.0));
    }
    const double first = std::sqrt(2.0 * m + 3.0);
    std::fill(acc_.begin(), acc_.end(), 0.0);
    for (int p = 0; p < pairs_; ++p) {
      if (power_[p] == 0.0) continue;
      double* e = &even_odd_[static_cast<std::size_t>(p) * 12];
      const double* north = fourier + (static_cast<std::size_t>(p) * order_ + m) * 6;
      const int south_row = height_ - 1 - p;
      const double* south = fourier + (static_cast<std::size_t>(south_row) * order_ + m) * 6;
      for (int i = 0; i < 6; ++i) {
        if (south_row == p) {  // the equator row of an odd height: Q_lm(0) = 0 for odd l − m
          e[i] = power_[p] * north[i];
          e[6 + i] = 0.0;
        } else {
          e[i] = power_[p] * (north[i] + south[i]);
          e[6 + i] = power_[p] * (north[i] - south[i]);
        }
      }
      const double z = z_[p];
      double q2 = seed, q1 = first * z * seed;
      accumulate(m, q2, e);
      if (m + 1 < order_) accumulate(m + 1, q1, e + 6);
      for (int l = m + 2; l < order_; ++l) {
        const double q = a_[l] * z * q1 - ab_[l] * q2;
        accumulate(l, q, e + ((l - m) % 2 == 0 ? 0 : 6));
        q2 = q1;
        q1 = q;
      }
    }
    for (int l = m; l < order_; ++l)
      for (int ch = 0; ch < 3; ++ch) {
        double* out = primed + static_cast<std::size_t>(ch) * n2;
        out[index(l, m)] += acc_[static_cast<std::size_t>(l) * 6 + ch];
        if (m > 0) out[index(l, -m)] += acc_[static_cast<std::size_t>(l) * 6 + 3 + ch];
      }
  }

 private:
  void accumulate(int l, double q, const double* e) {
    double* a = &acc_[static_cast<std::size_t>(l) * 6];
    for (int i = 0; i < 6; ++i) a[i] += q * e[i];
  }

  const int height_, order_, pairs_;
  std::vector<double> z_, sin_theta_, power_, a_, ab_, acc_, even_odd_;
};

std::vector<double> project_latlong_separable(const EnvMap& env, int order, ProjectionStats* stats,
                                              const ProjectionProgress& progress) {
  const int width = env.width, height = env.height;
  const int n2 = coefficient_count(order);
  FourierStage fourier_stage(env, order);
  // Progress units: about one multiply-add each.
  const std::uint64_t row_cost = std::uint64_t(width) * fourier_stage.computed_frequencies() * 6;
  const std::uint64_t pair_cost = std::uint64_t((height + 1) / 2) * 8;
  std::uint64_t legendre_total = 0;
  for (int m = 0; m < order; ++m) legendre_total += pair_cost * (order - m);
  const std::uint64_t axis_band = 8;  // per (l+1)² entry of a band
  std::uint64_t axis_total = 0;
  for (int l = 0; l < order; ++l) axis_total += axis_band * (l + 1) * (l + 1);
  const std::uint64_t total = row_cost * height + legendre_total + axis_total;
  std::uint64_t done = 0;

  std::vector<double> fourier(static_cast<std::size_t>(height) * order * 6);
  constexpr int kRowBlock = 16;  // rows sharing one pass over the exponential tables
  for (int first = 0; first < height; first += kRowBlock) {
    const int count = std::min(kRowBlock, height - first);
    fourier_stage.run(first, count, stats, fourier.data());
    done += row_cost * count;
    if (progress) progress(done, total);
  }
  std::vector<double> primed(3 * static_cast<std::size_t>(n2), 0.0);
  LegendreStage legendre(height, order);
  double seed = 1.0 / std::sqrt(4.0 * kPi);  // Q_mm
  for (int m = 0; m < order; ++m) {
    if (m > 0) seed *= std::sqrt((2.0 * m + 1.0) / (2.0 * m));
    legendre.run(m, m > 0 ? seed * std::sqrt(2.0) : seed, fourier.data(), primed.data());
    done += pair_cost * (order - m);
    if (progress && (m % 8 == 7 || m + 1 == order)) progress(done, total);
  }
  std::vector<double> result(primed.size());
  polar_y_to_z(order, 3, primed.data(), result.data(), [&](int l) {
    done += axis_band * (l + 1) * (l + 1);
    if (progress && (l % 8 == 7 || l + 1 == order)) progress(done, total);
  });
  return result;
}

}  // namespace

std::vector<double> project_direct(const EnvMap& env, int order, ProjectionStats* stats,
                                   const ProjectionProgress& progress) {
  if (!valid_input(env, order)) return {};
  const int n2 = coefficient_count(order);
  const std::vector<double> solid_angles = texel_solid_angles(env.layout, env.width, env.height);
  std::vector<double> result(3 * static_cast<std::size_t>(n2), 0.0);
  std::vector<double> row_sum(result.size());
  std::vector<double> basis(n2);
  // Progress in texels on the sphere (rows of angular maps and crosses hold different numbers).
  std::uint64_t total = 0, done = 0;
  for (double omega : solid_angles) total += omega > 0.0;
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
    for (int col = 0; col < env.width; ++col)
      done += solid_angles[static_cast<std::size_t>(row) * env.width + col] > 0.0;
    if (progress && total > 0) progress(done, total);
  }
  return result;
}

std::vector<double> project(const EnvMap& env, int order, ProjectionStats* stats,
                            const ProjectionProgress& progress) {
  if (!valid_input(env, order)) return {};
  if (env.layout == EnvLayout::LatLong)
    return project_latlong_separable(env, order, stats, progress);
  return project_direct(env, order, stats, progress);
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
