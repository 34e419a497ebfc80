// sh/src/polar_axis.cpp — Wigner d(π/2) by recurrence and the change of polar axis y ↔ z (method
// and conventions in sh/polar_axis.h).
#include "sh/polar_axis.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <functional>
#include <vector>

#include "sh/basis.h"

namespace prt::sh {
namespace {

constexpr double kInvSqrt2 = 0.70710678118654752440;

// Storage: `upper_` holds, for band l, row-major (l+1)×(l+1) U[m][m'] = d_m m'(π/2) for
// m ≤ m' (the upper triangle); the lower triangle follows from d_m'm = (−1)^(m'−m) d_mm'.

// In-place z-rotation by α = quarter_turns·π/2 of band l's coefficients v[m + l], m = −l..l.
void rotate_z_quarter_turns(int l, int quarter_turns, double* v) {
  for (int m = 1; m <= l; ++m) {
    const int phase = ((m * quarter_turns) % 4 + 4) % 4;  // mα mod 2π in quarter turns
    const double a = v[l + m], b = v[l - m];              // a_m (cosine), a_−m (sine)
    switch (phase) {
      case 0:
        break;
      case 1:  // cos = 0, sin = 1
        v[l + m] = -b;
        v[l - m] = a;
        break;
      case 2:  // cos = −1, sin = 0
        v[l + m] = -a;
        v[l - m] = -b;
        break;
      default:  // cos = 0, sin = −1
        v[l + m] = b;
        v[l - m] = -a;
        break;
    }
  }
}

}  // namespace

WignerHalfPi::WignerHalfPi() : upper_(1, 1.0), top_row_(1, 1.0) {}

void WignerHalfPi::next() {
  const int l = band_ + 1;
  const int n = l + 1;
  // Top row d^l_l,m from band l−1's top row.
  std::vector<double>& top = next_top_row_;
  top.resize(n);
  top[0] = -std::sqrt((2.0 * l - 1.0) / (2.0 * l)) * top_row_[0];
  for (int m = 1; m <= l; ++m)
    top[m] = std::sqrt(l * (2.0 * l - 1.0) / (2.0 * (l + m) * (l + m - 1.0))) * top_row_[m - 1];
  // Recurrence coefficients of the downward sweep in m'.
  inv_a_.resize(n);
  b_.resize(n);
  double* inv_a = inv_a_.data();
  double* b = b_.data();
  for (int mp = 0; mp < l; ++mp) {
    inv_a[mp] = 1.0 / std::sqrt((l - mp) * (l + mp + 1.0));
    b[mp] = std::sqrt((l - mp - 1.0) * (l + mp + 2.0));
  }
  // Every entry of the upper triangle is written below. Growing geometrically keeps the number of
  // (page-faulting) reallocations logarithmic in the order.
  const std::size_t size = static_cast<std::size_t>(n) * n;
  if (upper_.capacity() < size) upper_.reserve(std::max(size, 2 * upper_.capacity()));
  upper_.resize(size);
  // Column m of the lower triangle, d_m'm for m' = l..m, is stored as row m of the upper one:
  // v_m' = U[m][m'] = d_m m' = (−1)^(m'−m) d_m'm, which obeys the recurrence with the signs
  // folded in: v_m' = −(2m v_(m'+1) + b_m' v_(m'+2))·inv_a_m', from v_l = (−1)^(l−m) d_lm.
  // Columns are independent: kColumns of them advance together (the recurrence is latency-bound).
  constexpr int kColumns = 4;
  for (int m0 = 0; m0 <= l; m0 += kColumns) {
    const int count = std::min(kColumns, l + 1 - m0);
    double* rows[kColumns];
    double next1[kColumns], next2[kColumns], two_m[kColumns];
    for (int j = 0; j < count; ++j) {
      const int m = m0 + j;
      rows[j] = &upper_[static_cast<std::size_t>(m) * n];
      next1[j] = ((l - m) % 2 == 0 ? 1.0 : -1.0) * top[m];
      next2[j] = 0.0;
      two_m[j] = 2.0 * m;
      rows[j][l] = next1[j];
    }
    int mp = l - 1;
    if (count == kColumns)
      for (; mp >= m0 + kColumns - 1; --mp)
        for (int j = 0; j < kColumns; ++j) {
          const double value = -(two_m[j] * next1[j] + b[mp] * next2[j]) * inv_a[mp];
          rows[j][mp] = value;
          next2[j] = next1[j];
          next1[j] = value;
        }
    for (int j = 0; j < count; ++j)  // the rest of each column, down to its diagonal
      for (int q = mp; q >= m0 + j; --q) {
        const double value = -(two_m[j] * next1[j] + b[q] * next2[j]) * inv_a[q];
        rows[j][q] = value;
        next2[j] = next1[j];
        next1[j] = value;
      }
  }
  top_row_.swap(top);
  band_ = l;
}

double WignerHalfPi::operator()(int m_primed, int m) const noexcept {
  const int l = band_;
  if (m_primed < -l || m_primed > l || m < -l || m > l) return 0.0;
  // d_−m',m = (−1)^(l+m) d_m'm, and d_m',−m = (−1)^(l+m') d_m'm.
  double sign = 1.0;
  if (m_primed < 0) {
    m_primed = -m_primed;
    if ((l + m) % 2 != 0) sign = -sign;
  }
  if (m < 0) {
    m = -m;
    if ((l + m_primed) % 2 != 0) sign = -sign;
  }
  const int n = l + 1;
  if (m <= m_primed) {  // stored as U[m][m'] = (−1)^(m'−m) d_m'm
    const double u = upper_[static_cast<std::size_t>(m) * n + m_primed];
    return ((m_primed - m) % 2 == 0 ? sign : -sign) * u;
  }
  return sign * upper_[static_cast<std::size_t>(m_primed) * n + m];
}

namespace {

// Gy(π/2)·in (transpose = false) or Gy(π/2)ᵀ·in for band l of `channels` vectors, in place on
// v[c·stride + m + l], m = −l..l. The nonzero entries (header; s = (−1)^l, κ_0 = 1/√2,
// κ_m>0 = 1):
//   cos block, m + m' + l even:  Gy(m', m)   =  2 s κ_m' κ_m d_m'm
//   sin block, m + m' + l odd:   Gy(−m', −m) = −2 s d_m'm
// On the cos pattern d_mm' = s d_m'm, on the sin pattern −s d_m'm, so Gyᵀ is s·Gy on the cos
// block and −s·Gy on the sin block. d_m'm is U[m'][m] above the diagonal and (−1)^(m'−m)·U[m][m']
// on and below it, i.e. s·U[m][m'] on the cos pattern and −s·U[m][m'] on the sin pattern; one
// pass over each row of U gathers the part above the diagonal and scatters the part below.
class YQuarterTurn {
 public:
  explicit YQuarterTurn(int channels) : channels_(channels) {}

  void apply(const WignerHalfPi& d, std::size_t stride, double* v, bool transpose) {
    const int l = d.band();
    const double s = (l % 2 == 0) ? 1.0 : -1.0;
    // Cosine block: x_m = κ_m a_m for m = 0..l.
    load(l, stride, v, 0, true);
    block(d, s, 0, l % 2 == 0);
    store(l, stride, v, 0, true, transpose ? 2.0 : 2.0 * s);
    // Sine block: y_m = a_−m for m = 1..l (entry m = 0 stays zero).
    load(l, stride, v, 1, false);
    block(d, -s, 1, l % 2 != 0);
    store(l, stride, v, 1, false, transpose ? 2.0 : -2.0 * s);
  }

 private:
  // x[m·channels + c] = (κ_m) a_±m for m ≥ first; x[0..] = 0 for m < first.
  void load(int l, std::size_t stride, const double* v, int first, bool cosine) {
    const int n = l + 1;
    x_.assign(static_cast<std::size_t>(n) * channels_, 0.0);
    acc_.assign(x_.size(), 0.0);
    for (int m = first; m <= l; ++m)
      for (int c = 0; c < channels_; ++c) {
        const double a = v[c * stride + (cosine ? l + m : l - m)];
        x_[static_cast<std::size_t>(m) * channels_ + c] = (cosine && m == 0) ? kInvSqrt2 * a : a;
      }
  }

  // acc[m'] = Σ_m (pattern) d_m'm x_m with d_m'm = U[m'][m] above the diagonal and
  // lower_sign·U[m][m'] on and below it; `diagonal`: whether m = m' is on the pattern.
  void block(const WignerHalfPi& d, double lower_sign, int first, bool diagonal) {
    const int l = d.band();
    const int n = l + 1;
    const int k = channels_;
    for (int r = first; r <= l; ++r) {
      const double* row = d.upper_row(r);
      const double* xr = &x_[static_cast<std::size_t>(r) * k];
      double* ar = &acc_[static_cast<std::size_t>(r) * k];
      if (diagonal)
        for (int c = 0; c < k; ++c) ar[c] += lower_sign * row[r] * xr[c];
      // Off the diagonal the pattern keeps m − r even when the diagonal is on it, odd otherwise.
      const int start = diagonal ? r + 2 : r + 1;
      for (int m = start; m < n; m += 2) {
        const double u = row[m];
        const double* xm = &x_[static_cast<std::size_t>(m) * k];
        double* am = &acc_[static_cast<std::size_t>(m) * k];
        for (int c = 0; c < k; ++c) {
          ar[c] += u * xm[c];               // above the diagonal: d_rm = U[r][m]
          am[c] += lower_sign * u * xr[c];  // below: d_mr = lower_sign·U[r][m]
        }
      }
    }
  }

  void store(int l, std::size_t stride, double* v, int first, bool cosine, double scale) {
    for (int m = first; m <= l; ++m)
      for (int c = 0; c < channels_; ++c) {
        const double value = scale * acc_[static_cast<std::size_t>(m) * channels_ + c];
        v[c * stride + (cosine ? l + m : l - m)] = (cosine && m == 0) ? kInvSqrt2 * value : value;
      }
  }

  int channels_;
  std::vector<double> x_, acc_;
};

// G(Pᵀ) = Gz(π/2)·Gy(π/2)·Gz(π) (inverse = false) or its transpose Gz(−π)·Gy(π/2)ᵀ·Gz(−π/2),
// band by band, for `channels` channel-major vectors of order² coefficients.
void change_axis(int order, int channels, const double* in, double* out, bool inverse,
                 const std::function<void(int)>& band_done) {
  if (order < 1 || order > kMaxOrder || channels < 1) return;
  const std::size_t stride = static_cast<std::size_t>(order) * order;
  for (std::size_t i = 0; i < stride * channels; ++i) out[i] = in[i];
  WignerHalfPi d;
  YQuarterTurn turn(channels);
  for (int l = 0; l < order; ++l) {
    if (l > 0) d.next();
    double* band = out + static_cast<std::size_t>(l) * l;  // m = −l at band[0]
    for (int c = 0; c < channels; ++c)
      rotate_z_quarter_turns(l, inverse ? -1 : 2, band + c * stride);
    turn.apply(d, stride, band, inverse);
    for (int c = 0; c < channels; ++c)
      rotate_z_quarter_turns(l, inverse ? -2 : 1, band + c * stride);
    if (band_done) band_done(l);
  }
}

}  // namespace

void polar_y_to_z(int order, int channels, const double* in, double* out,
                  const std::function<void(int band)>& band_done) {
  change_axis(order, channels, in, out, false, band_done);
}

void polar_z_to_y(int order, int channels, const double* in, double* out) {
  change_axis(order, channels, in, out, true, {});
}

}  // namespace prt::sh
