// sh/src/rotation.cpp — Ivanic–Ruedenberg recurrence for real SH rotation matrices.
//
// For band l ≥ 2 (J. Phys. Chem. 1996, eqs. 8.1–8.5 and Table 2, with the 1998 corrections):
//   M^l_mn = u_mn U_mn + v_mn V_mn + w_mn W_mn,
//   u = √((l+m)(l−m)/D),  v = ½√((1+δ_m0)(l+|m|−1)(l+|m|)/D)(1−2δ_m0),
//   w = −½√((l−|m|−1)(l−|m|)/D)(1−δ_m0),  D = (l+n)(l−n) for |n| < l, 2l(2l−1) for |n| = l,
//   U = P(0, m, n),
//   V = P(1,1,n) + P(−1,−1,n)                               (m = 0)
//     = P(1,m−1,n)√(1+δ_m1) − P(−1,−m+1,n)(1−δ_m1)           (m > 0)
//     = P(1,m+1,n)(1−δ_{m,−1}) + P(−1,−m−1,n)√(1+δ_{m,−1})   (m < 0; sign-corrected)
//   W = P(1,m+1,n) + P(−1,−m−1,n)  (m > 0),  P(1,m−1,n) − P(−1,−m+1,n)  (m < 0),
//   P(i,a,n) = R_i0 M^{l−1}_{a,n}                              (|n| < l)
//            = R_i1 M^{l−1}_{a,l−1} − R_{i,−1} M^{l−1}_{a,−l+1} (n = l)
//            = R_i1 M^{l−1}_{a,−l+1} + R_{i,−1} M^{l−1}_{a,l−1} (n = −l),
// with R = M^1. Each row m is thus a weighted sum of at most five rows (i, a) of the previous
// band; the weights w·(factor) without the 1/√D part depend only on (l, m) and are tabulated.
//
// The constructor builds band 2 in closed form (write_band2) and the recurrence from band 3;
// build_with_recurrence() uses the recurrence from band 2 (the reference for the tests).
#include "sh/rotation.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

namespace sh {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The rows of band l − 1 that feed row m of band l: P(i, a, ·) with weight.
struct RowTerms {
  int count = 0;
  int i[5] = {};
  int a[5] = {};
  double weight[5] = {};

  void add(int ii, int aa, double w) {
    if (w == 0.0) return;
    i[count] = ii;
    a[count] = aa;
    weight[count] = w;
    ++count;
  }
};

RowTerms compute_row_terms(int l, int m) {
  RowTerms t;
  const int am = m < 0 ? -m : m;
  const double d0 = m == 0 ? 1.0 : 0.0;
  const double u = std::sqrt(double(l + m) * double(l - m));
  const double v = 0.5 * std::sqrt((1.0 + d0) * double(l + am - 1) * double(l + am)) * (1 - 2 * d0);
  const double w = -0.5 * std::sqrt(double(l - am - 1) * double(l - am)) * (1.0 - d0);
  t.add(0, m, u);
  if (m == 0) {
    t.add(1, 1, v);
    t.add(-1, -1, v);
  } else if (m > 0) {
    const double d1 = m == 1 ? 1.0 : 0.0;
    t.add(1, m - 1, v * std::sqrt(1.0 + d1));
    t.add(-1, -m + 1, -v * (1.0 - d1));
    t.add(1, m + 1, w);
    t.add(-1, -m - 1, w);
  } else {
    const double d1 = m == -1 ? 1.0 : 0.0;
    t.add(1, m + 1, v * (1.0 - d1));
    t.add(-1, -m - 1, v * std::sqrt(1.0 + d1));
    t.add(1, m - 1, w);
    t.add(-1, -m + 1, -w);
  }
  return t;
}

double compute_inverse_sqrt_denominator(int l, int n) {
  const double d = (n == l || n == -l) ? 2.0 * l * (2.0 * l - 1.0) : double(l + n) * double(l - n);
  return 1.0 / std::sqrt(d);
}

// Tables for bands below kTableOrder; higher bands compute the same values inline.
constexpr int kTableOrder = 32;

struct RotationTables {
  std::vector<RowTerms> terms;         // band l, row m at l² + l + m
  std::vector<double> inverse_sqrt_d;  // band l, column n at l² + l + n
  RotationTables() : terms(kTableOrder * kTableOrder), inverse_sqrt_d(kTableOrder * kTableOrder) {
    for (int l = 2; l < kTableOrder; ++l) {
      for (int m = -l; m <= l; ++m) {
        terms[l * l + l + m] = compute_row_terms(l, m);
        inverse_sqrt_d[l * l + l + m] = compute_inverse_sqrt_denominator(l, m);
      }
    }
  }
};

const RotationTables& rotation_tables() {
  static const RotationTables instance;
  return instance;
}

std::size_t band_offset(int l) {
  return std::size_t(l) * (4 * std::size_t(l) * l - 1) / 3;
}

// Σ a[j]·b[j] for j < n with two independent partial sums (even and odd j), which the
// compiler maps onto one 2-lane SIMD register where available.
inline double dot(const double* a, const double* b, int n) {
#if defined(__GNUC__)
  typedef double Pair __attribute__((vector_size(16)));
  Pair acc = {0.0, 0.0};
  int j = 0;
  for (; j + 1 < n; j += 2) {
    Pair x, y;
    std::memcpy(&x, a + j, sizeof x);
    std::memcpy(&y, b + j, sizeof y);
    acc += x * y;
  }
  double sum = acc[0] + acc[1];
#else
  double even = 0.0, odd = 0.0;
  int j = 0;
  for (; j + 1 < n; j += 2) {
    even += a[j] * b[j];
    odd += a[j + 1] * b[j + 1];
  }
  double sum = even + odd;
#endif
  for (; j < n; ++j) sum += a[j] * b[j];
  return sum;
}

// Builds band l (size s = 2l+1) into `out` from band l − 1 (`prev`, size s − 2) and band 1 `r`.
// L > 0 fixes l at compile time (the loops unroll); L = 0 is the general version.
template <int L>
void build_band(int l_runtime, const double* r, const double* prev, double* out,
                const RotationTables& tables) {
  const int l = L > 0 ? L : l_runtime;
  const int s = 2 * l + 1, ps = 2 * l - 1;
  // R_{i,j} for i, j ∈ {−1, 0, 1}.
  auto R = [r](int i, int j) { return r[(i + 1) * 3 + (j + 1)]; };
  const bool tabulated = l < kTableOrder;
  double inv_d_local[2 * kMaxRotationOrder + 1];
  const double* inv_d = tabulated ? &tables.inverse_sqrt_d[l * l] : inv_d_local;
  if (!tabulated) {
    for (int n = -l; n <= l; ++n) inv_d_local[n + l] = compute_inverse_sqrt_denominator(l, n);
  }
  for (int m = -l; m <= l; ++m) {
    RowTerms local;
    if (!tabulated) local = compute_row_terms(l, m);
    const RowTerms& t = tabulated ? tables.terms[l * l + l + m] : local;
    const int count = t.count;
    double* row = out + (m + l) * s;
    double first = 0.0, last = 0.0;  // columns n = −l and n = l
    double interior[2 * kMaxRotationOrder - 1];
    for (int n = 0; n < ps; ++n) interior[n] = 0.0;
    for (int j = 0; j < count; ++j) {
      const double* p = prev + (t.a[j] + l - 1) * ps;  // row a of band l − 1, n = −(l−1)..l−1
      const double w = t.weight[j];
      const double c = w * R(t.i[j], 0), c1 = w * R(t.i[j], 1), cm1 = w * R(t.i[j], -1);
      last += c1 * p[ps - 1] - cm1 * p[0];
      first += c1 * p[0] + cm1 * p[ps - 1];
      for (int n = 0; n < ps; ++n) interior[n] += c * p[n];
    }
    row[0] = first * inv_d[0];
    row[s - 1] = last * inv_d[s - 1];
    for (int n = 0; n < ps; ++n) row[n + 1] = interior[n] * inv_d[n + 1];
  }
}

using BandBuilder = void (*)(int, const double*, const double*, double*, const RotationTables&);

// {build_band<2>, …, build_band<kUnrolledBands + 1>}.
constexpr int kUnrolledBands = 8;
template <int... I>
constexpr std::array<BandBuilder, sizeof...(I)> make_band_builders(
    std::integer_sequence<int, I...>) {
  return {&build_band<I + 2>...};
}

void build_band_dispatch(int l, const double* r, const double* prev, double* out,
                         const RotationTables& tables) {
  static constexpr auto kBuilders =
      make_band_builders(std::make_integer_sequence<int, kUnrolledBands>());
  if (l - 2 < kUnrolledBands) {
    kBuilders[l - 2](l, r, prev, out, tables);
  } else {
    build_band<0>(l, r, prev, out, tables);
  }
}

// ---------------------------------------------------------------------------------------------
// Closed-form band 2 (the constructor; the recurrence takes over from band 3).

// Band 1: rows/columns (y, z, x) of M, i.e. scene axes 1, 2, 0.
inline void write_band1(const std::array<double, 9>& m, double* r) {
  static constexpr int kAxis[3] = {1, 2, 0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) r[i * 3 + j] = m[kAxis[i] * 3 + kAxis[j]];
  }
}

// Band 2 in closed form. Y2n(ω) is a quadratic form ωᵀQ_nω, so Y2n(Mᵀω) = (Mᵀω)ᵀQ_n(Mᵀω) is
// a product of the linear forms a·ω, b·ω, c·ω, where a, b, c are the columns x, y, z of M
// (u = Mᵀω has u_x = a·ω, u_y = b·ω, u_z = c·ω). Splitting a product (p·ω)(q·ω) into the
// basis: its xy, yz, xz coefficients p_x q_y + p_y q_x, … give Y2,−2, Y2,−1, Y2,1 (each
// 1.092548·xy, …); its diagonal part d = (p_x q_x, p_y q_y, p_z q_z) gives
// Y2,0 ∝ 2z² − x² − y² with weight (2d_z − d_x − d_y)/6 and Y2,2 ∝ x² − y² with weight
// (d_x − d_y)/2. Dividing by the normalisations (c1 = ½√(15/π), c0 = ¼√(5/π), c2 = c1/2;
// c1/c0 = 2√3) and simplifying with the orthonormality of M's rows and columns (a·b = 0,
// |a| = 1, Σ_j M_xj M_yj = 0, …) gives the entries below; row m, column n at (m+2)·5 + n+2.
inline void write_band2(const std::array<double, 9>& m, double* o) {
  constexpr double k3 = 1.7320508075688772935;  // √3
  constexpr double h3 = 0.8660254037844386468;  // √3/2
  const double ax = m[0], ay = m[3], az = m[6];
  const double bx = m[1], by = m[4], bz = m[7];
  const double cx = m[2], cy = m[5], cz = m[8];
  // n = −2: Y ∝ u_x·u_y, i.e. (p, q) = (a, b).
  o[0] = ax * by + ay * bx;
  o[5] = ay * bz + az * by;
  o[10] = k3 * (az * bz);
  o[15] = ax * bz + az * bx;
  o[20] = ax * bx - ay * by;
  // n = −1: u_y·u_z, (b, c).
  o[1] = bx * cy + by * cx;
  o[6] = by * cz + bz * cy;
  o[11] = k3 * (bz * cz);
  o[16] = bx * cz + bz * cx;
  o[21] = bx * cx - by * cy;
  // n = 0: 2u_z² − u_x² − u_y².
  o[2] = k3 * (cx * cy);
  o[7] = k3 * (cy * cz);
  o[12] = 1.5 * (cz * cz) - 0.5;
  o[17] = k3 * (cx * cz);
  o[22] = h3 * (cx * cx - cy * cy);
  // n = 1: u_x·u_z, (a, c).
  o[3] = ax * cy + ay * cx;
  o[8] = ay * cz + az * cy;
  o[13] = k3 * (az * cz);
  o[18] = ax * cz + az * cx;
  o[23] = ax * cx - ay * cy;
  // n = 2: u_x² − u_y².
  o[4] = ax * ay - bx * by;
  o[9] = ay * az - by * bz;
  o[14] = h3 * (az * az - bz * bz);
  o[19] = ax * az - bx * bz;
  o[24] = 0.5 * ((ax * ax - bx * bx) - (ay * ay - by * by));
}

void build_matrices(int order, const std::array<double, 9>& m, double* mats) {
  mats[0] = 1.0;
  if (order < 2) return;
  double* r = mats + band_offset(1);
  write_band1(m, r);
  if (order < 3) return;
  write_band2(m, mats + band_offset(2));
  const RotationTables& tables = rotation_tables();
  for (int l = 3; l < order; ++l) {
    build_band_dispatch(l, r, mats + band_offset(l - 1), mats + band_offset(l), tables);
  }
}

// out = B·in for one band; L > 0 fixes l at compile time.
template <int L, typename T>
void apply_band(int l_runtime, const double* b, const T* in, T* out) {
  const int s = 2 * (L > 0 ? L : l_runtime) + 1;
  double v[2 * kMaxRotationOrder + 2];
  for (int j = 0; j < s; ++j) v[j] = static_cast<double>(in[j]);
  for (int i = 0; i < s; ++i) out[i] = static_cast<T>(dot(b + i * s, v, s));
}

template <typename T>
using BandApplier = void (*)(int, const double*, const T*, T*);

// {apply_band<1, T>, …, apply_band<kUnrolledBands + 1, T>}.
template <typename T, int... I>
constexpr std::array<BandApplier<T>, sizeof...(I)> make_band_appliers(
    std::integer_sequence<int, I...>) {
  return {&apply_band<I + 1, T>...};
}

template <typename T>
void apply_bands(int order, const double* mats, const T* in, T* out) {
  static constexpr auto kAppliers =
      make_band_appliers<T>(std::make_integer_sequence<int, kUnrolledBands + 1>());
  if (order < 1) return;
  out[0] = in[0];
  for (int l = 1; l < order; ++l) {
    const double* b = mats + band_offset(l);
    const T* i = in + l * l;
    T* o = out + l * l;
    if (l <= kUnrolledBands + 1) {
      kAppliers[l - 1](l, b, i, o);
    } else {
      apply_band<0>(l, b, i, o);
    }
  }
}
}  // namespace

std::array<double, 9> rotation_from_yaw_pitch_roll(double yaw_deg, double pitch_deg,
                                                   double roll_deg) noexcept {
  const double d = kPi / 180.0;
  const double cy = std::cos(yaw_deg * d), sy = std::sin(yaw_deg * d);
  const double cp = std::cos(pitch_deg * d), sp = std::sin(pitch_deg * d);
  const double cr = std::cos(roll_deg * d), sr = std::sin(roll_deg * d);
  // Ry(yaw) = [cy 0 sy; 0 1 0; −sy 0 cy], Rx(pitch) = [1 0 0; 0 cp −sp; 0 sp cp],
  // Rz(roll) = [cr −sr 0; sr cr 0; 0 0 1]; M = Ry·Rx·Rz.
  // Rx·Rz = [cr, −sr, 0; cp·sr, cp·cr, −sp; sp·sr, sp·cr, cp].
  const double a[9] = {cr, -sr, 0.0, cp * sr, cp * cr, -sp, sp * sr, sp * cr, cp};
  return {cy * a[0] + sy * a[6],  cy * a[1] + sy * a[7],  cy * a[2] + sy * a[8], a[3], a[4], a[5],
          -sy * a[0] + cy * a[6], -sy * a[1] + cy * a[7], -sy * a[2] + cy * a[8]};
}

double* Rotation::allocate(int order) noexcept {
  order_ = std::clamp(order, 1, kMaxRotationOrder);
  if (order_ <= kInlineRotationOrder) return inline_matrices_;
  try {
    matrices_.resize(band_offset(order_));
  } catch (...) {  // out of memory: an empty rotation (order 0) instead of an exception
    order_ = 0;
    return nullptr;
  }
  return matrices_.data();
}

Rotation::Rotation(int order, const std::array<double, 9>& m) noexcept {
  double* mats = allocate(order);
  if (mats != nullptr) build_matrices(order_, m, mats);
}

Rotation::Rotation(int order, const std::array<double, 9>& m, RecurrenceTag) noexcept {
  double* mats = allocate(order);
  if (mats == nullptr) return;
  mats[0] = 1.0;
  if (order_ < 2) return;
  double* r = mats + band_offset(1);
  write_band1(m, r);
  const RotationTables& tables = rotation_tables();
  for (int l = 2; l < order_; ++l) {
    build_band_dispatch(l, r, mats + band_offset(l - 1), mats + band_offset(l), tables);
  }
}

Rotation Rotation::build_with_recurrence(int order, const std::array<double, 9>& m) noexcept {
  return Rotation(order, m, RecurrenceTag{});
}

const double* Rotation::band_matrix(int l) const noexcept {
  if (l < 0 || l >= order_) return nullptr;
  return data() + band_offset(l);
}

void Rotation::apply(const double* in, double* out) const noexcept {
  apply_bands(order_, data(), in, out);
}

void Rotation::apply(const float* in, float* out) const noexcept {
  apply_bands(order_, data(), in, out);
}

}  // namespace sh
