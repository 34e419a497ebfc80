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

#include "sh/constants.h"

namespace prt::sh {
namespace {

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

// ---------------------------------------------------------------------------------------------
// rotate_coefficients: the zxzxz path, R(M) = Z(α)·X₋·Z(β)·X₊·Z(γ) per band.
//
// Euler angles. M = Rz(α)·Ry(β)·Rz(γ) expands to
//   [ ca·cb·cg − sa·sg,  −ca·cb·sg − sa·cg,  ca·sb ]
//   [ sa·cb·cg + ca·sg,  −sa·cb·sg + ca·cg,  sa·sb ]
//   [ −sb·cg,            sb·sg,              cb    ]
// so cb = m22, sb = √(m02² + m12²) (β ∈ [0, π]) and (ca, sa) = (m02, m12)/sb. Reading γ from
// (−m20, m21)/sb would lose accuracy near the poles (error ε/sb in α and γ separately, and they
// do not cancel), so γ comes from the well-conditioned sum or difference instead:
//   m00 + m11 = (1 + cb)·cos(α+γ),  m10 − m01 = (1 + cb)·sin(α+γ)   (used when cb ≥ 0),
//   m11 − m00 = (1 − cb)·cos(α−γ),  −(m10 + m01) = (1 − cb)·sin(α−γ) (used when cb < 0),
// whose norms are ≥ 1; then γ = (α+γ) − α or α − (α−γ) by complex division. An error ε/sb in α
// then changes the rebuilt M by only O(ε) (it multiplies sb in column 2 and row 2, and moves
// α+γ or α−γ not at all). At sb = 0 exactly, α = 0 and γ carries the whole z turn.
//
// Y-rotation. Rx(−90°)·Rz(β)·Rx(+90°) turns by β about Rx(−90°)·ẑ = ŷ, i.e. it is Ry(β); since
// R(A)·R(B) = R(A·B), R(Ry(β)) = X₋·Z(β)·X₊ with X± = R(Rx(±90°)) and X₋ = X₊ᵀ.
//
// Z-rotation. g(φ) = f(φ − θ) gives, for m > 0, out_m = c·in_m − s·in_−m and
// out_−m = c·in_−m + s·in_m with c = cos mθ, s = sin mθ (no Condon–Shortley phase).
//
// Parity blocks. Rx commutes with the reflection x → −x, under which Y_lm is even iff
// (m ≥ 0 and m even) or (m < 0 and m odd); and Rx(+90°) carries z → −z onto y → −y, under which
// Y_lm has parity (−1)^(l+m) and sign(m ≥ 0 ? +1 : −1) respectively. So X₊ only connects input
// m and output m' of the same x-parity with (l+m even) ⇔ (m' ≥ 0). Split band l into four
// groups, each ordered by |m|:
//   0: m = 0, 2, 4, …    1: m = −1, −3, …    2: m = 1, 3, …    3: m = −2, −4, …
// (sizes ⌊l/2⌋+1, ⌈l/2⌉, ⌈l/2⌉, ⌊l/2⌋). X₊ maps group s onto group d(s) by a dense square
// block: d = (0, 1, 3, 2) for even l, (1, 0, 2, 3) for odd l; about a quarter of X₊'s entries
// are non-zero. X₋ = X₊ᵀ maps d(s) back onto s by the transposed block. Z pairs group 0's
// m = 2j with group 3's m = −2j, and group 2's m = 2j+1 with group 1's m = −(2j+1).
namespace {

constexpr int group_size(int l, int g) {
  return g == 0 ? l / 2 + 1 : g == 3 ? l / 2 : (l + 1) / 2;
}
constexpr int group_member(int g, int r) {
  return g == 0 ? 2 * r : g == 1 ? -(2 * r + 1) : g == 2 ? 2 * r + 1 : -(2 * r + 2);
}
constexpr int x_target_group(int l, int g) {
  constexpr int kEven[4] = {0, 1, 3, 2}, kOdd[4] = {1, 0, 2, 3};
  return l % 2 == 0 ? kEven[g] : kOdd[g];
}

// Band l's blocks at xblock_offset(l): for each source group g, Bᵀ_g then B_g (row-major,
// group_size(l, g)² each), with B_g[r][c] = X₊[member(d(g), r)][member(g, c)].
constexpr int xblock_doubles(int l) {
  int n = 0;
  for (int g = 0; g < 4; ++g) n += 2 * group_size(l, g) * group_size(l, g);
  return n;
}
constexpr int xblock_offset(int l) {
  int offset = 0;
  for (int j = 2; j < l; ++j) offset += xblock_doubles(j);
  return offset;
}

struct XBlocks {
  double values[xblock_offset(kFastRotateOrder)];
  XBlocks() {
    const Rotation x(kFastRotateOrder, {1, 0, 0, 0, 0, -1, 0, 1, 0});  // Rx(+90°)
    for (int l = 2; l < kFastRotateOrder; ++l) {
      const double* band = x.band_matrix(l);
      const int s = 2 * l + 1;
      double* p = values + xblock_offset(l);
      for (int g = 0; g < 4; ++g) {
        const int n = group_size(l, g), d = x_target_group(l, g);
        for (int r = 0; r < n; ++r) {
          for (int c = 0; c < n; ++c) {
            const double v = band[(group_member(d, r) + l) * s + (group_member(g, c) + l)];
            p[c * n + r] = v;          // Bᵀ
            p[n * n + r * n + c] = v;  // B
          }
        }
        p += 2 * n * n;
      }
    }
  }
};

const XBlocks& x_blocks() {
  static const XBlocks instance;
  return instance;
}

// cos kθ and sin kθ for k = 1..N−1, from (c, s) = (cos θ, sin θ) by angle addition.
template <int N>
struct ZTurn {
  double c[N > 1 ? N : 2];
  double s[N > 1 ? N : 2];
  ZTurn(double c1, double s1) {
    double ck = c1, sk = s1;
    for (int k = 1; k < N; ++k) {
      c[k] = ck;
      s[k] = sk;
      const double cn = ck * c1 - sk * s1;
      sk = sk * c1 + ck * s1;
      ck = cn;
    }
  }
};

struct EulerZyz {
  double ca, sa, cb, sb, cg, sg;
};

inline EulerZyz decompose_zyz(const std::array<double, 9>& m) {
  EulerZyz e;
  e.cb = m[8];
  const bool upper = e.cb >= 0.0;
  const double t = m[2] * m[2] + m[5] * m[5];        // sb²
  const double d = upper ? 1.0 + e.cb : 1.0 - e.cb;  // |(p, q)| below, in [1, 2]
  double inv_d;
  if (t > 1e-200) {
    // One square root and one division, independent of each other (no latency chain):
    // q = 1/(t·d), then 1/sb = sb·d·q and 1/d = t·q.
    e.sb = std::sqrt(t);
    const double q = 1.0 / (t * d);
    const double inv_sb = e.sb * d * q;
    inv_d = t * q;
    e.ca = m[2] * inv_sb;
    e.sa = m[5] * inv_sb;
  } else {
    // At a pole (sb < 1e-100): α = 0 and γ takes the whole z turn; the neglected sb changes M
    // by less than 1e-100.
    e.sb = std::sqrt(t);
    inv_d = 1.0 / d;
    e.ca = 1.0;
    e.sa = 0.0;
  }
  if (upper) {  // σ = α + γ; γ = σ − α
    const double cs = (m[0] + m[4]) * inv_d, ss = (m[3] - m[1]) * inv_d;
    e.cg = cs * e.ca + ss * e.sa;
    e.sg = ss * e.ca - cs * e.sa;
  } else {  // δ = α − γ; γ = α − δ
    const double cd = (m[4] - m[0]) * inv_d, sd = -(m[3] + m[1]) * inv_d;
    e.cg = e.ca * cd + e.sa * sd;
    e.sg = e.sa * cd - e.ca * sd;
  }
  return e;
}

// y = Σ_c v[c]·(row c of t) for a dense N×N row-major t, i.e. y = tᵀ·v (column sweeps, which
// vectorise without horizontal sums).
template <int N>
inline void multiply_transposed(const double* t, const double* v, double* y) {
  for (int r = 0; r < N; ++r) y[r] = t[r] * v[0];
  for (int c = 1; c < N; ++c) {
    for (int r = 0; r < N; ++r) y[r] += t[c * N + r] * v[c];
  }
}

// Applies Z(θ) to band L held in groups g0..g3.
template <int L, int N>
inline void turn_groups(const ZTurn<N>& z, double* g0, double* g1, double* g2, double* g3) {
  for (int j = 1; 2 * j <= L; ++j) {  // (m, −m) = (2j, −2j): g0[j], g3[j−1]
    const double p = g0[j], q = g3[j - 1];
    g0[j] = z.c[2 * j] * p - z.s[2 * j] * q;
    g3[j - 1] = z.c[2 * j] * q + z.s[2 * j] * p;
  }
  for (int j = 0; 2 * j + 1 <= L; ++j) {  // (2j+1, −(2j+1)): g2[j], g1[j]
    const double p = g2[j], q = g1[j];
    g2[j] = z.c[2 * j + 1] * p - z.s[2 * j + 1] * q;
    g1[j] = z.c[2 * j + 1] * q + z.s[2 * j + 1] * p;
  }
}

template <int L, int N, typename T>
inline void rotate_band_zxzxz(const T* in, T* out, const ZTurn<N>& za, const ZTurn<N>& zb,
                              const ZTurn<N>& zg, const double* blocks) {
  constexpr int n0 = group_size(L, 0), n1 = group_size(L, 1), n2 = group_size(L, 2),
                n3 = group_size(L, 3);
  constexpr int d0 = x_target_group(L, 0), d1 = x_target_group(L, 1), d2 = x_target_group(L, 2),
                d3 = x_target_group(L, 3);
  const double* b0 = blocks + xblock_offset(L);  // Bᵀ_0, B_0, Bᵀ_1, …
  const double* b1 = b0 + 2 * n0 * n0;
  const double* b2 = b1 + 2 * n1 * n1;
  const double* b3 = b2 + 2 * n2 * n2;
  const T* x = in + L * L + L;  // x[m], m = −L..L
  double u[4][L / 2 + 1], w[4][L / 2 + 1];
  for (int r = 0; r < n0; ++r) u[0][r] = double(x[group_member(0, r)]);
  for (int r = 0; r < n1; ++r) u[1][r] = double(x[group_member(1, r)]);
  for (int r = 0; r < n2; ++r) u[2][r] = double(x[group_member(2, r)]);
  for (int r = 0; r < n3; ++r) u[3][r] = double(x[group_member(3, r)]);
  turn_groups<L>(zg, u[0], u[1], u[2], u[3]);  // Z(γ)
  multiply_transposed<n0>(b0, u[0], w[d0]);    // X₊: w[d(g)] = B_g·u[g]
  multiply_transposed<n1>(b1, u[1], w[d1]);
  multiply_transposed<n2>(b2, u[2], w[d2]);
  multiply_transposed<n3>(b3, u[3], w[d3]);
  turn_groups<L>(zb, w[0], w[1], w[2], w[3]);          // Z(β)
  multiply_transposed<n0>(b0 + n0 * n0, w[d0], u[0]);  // X₋: u[g] = B_gᵀ·w[d(g)]
  multiply_transposed<n1>(b1 + n1 * n1, w[d1], u[1]);
  multiply_transposed<n2>(b2 + n2 * n2, w[d2], u[2]);
  multiply_transposed<n3>(b3 + n3 * n3, w[d3], u[3]);
  turn_groups<L>(za, u[0], u[1], u[2], u[3]);  // Z(α)
  T* y = out + L * L + L;
  for (int r = 0; r < n0; ++r) y[group_member(0, r)] = T(u[0][r]);
  for (int r = 0; r < n1; ++r) y[group_member(1, r)] = T(u[1][r]);
  for (int r = 0; r < n2; ++r) y[group_member(2, r)] = T(u[2][r]);
  for (int r = 0; r < n3; ++r) y[group_member(3, r)] = T(u[3][r]);
}

template <int N, typename T, int... L>
inline void rotate_bands_zxzxz(const T* in, T* out, const ZTurn<N>& za, const ZTurn<N>& zb,
                               const ZTurn<N>& zg, const double* blocks,
                               std::integer_sequence<int, L...>) {
  (rotate_band_zxzxz<L + 2, N>(in, out, za, zb, zg, blocks), ...);
}

// Band 1 is M with axes reordered to (y, z, x).
template <typename T>
inline void rotate_band1(const std::array<double, 9>& m, const T* in, T* out) {
  const double r[9] = {m[4], m[5], m[3], m[7], m[8], m[6], m[1], m[2], m[0]};
  const double v[3] = {double(in[1]), double(in[2]), double(in[3])};
  for (int i = 0; i < 3; ++i) {
    out[1 + i] = T(r[i * 3] * v[0] + r[i * 3 + 1] * v[1] + r[i * 3 + 2] * v[2]);
  }
}

// Orders up to this are one straight-line function each (everything inlined); higher orders
// call one such function per band (keeps the code size down: ~40 kB instead of ~1 MB).
constexpr int kStraightLineOrder = 6;

template <int N, typename T>
#if defined(__GNUC__)
__attribute__((flatten))
#endif
void rotate_fixed_order(const std::array<double, 9>& m, const T* in, T* out) {
  out[0] = in[0];
  if constexpr (N >= 2) rotate_band1(m, in, out);
  if constexpr (N >= 3) {
    const EulerZyz e = decompose_zyz(m);
    const ZTurn<N> za(e.ca, e.sa), zb(e.cb, e.sb), zg(e.cg, e.sg);
    rotate_bands_zxzxz<N>(in, out, za, zb, zg, x_blocks().values,
                          std::make_integer_sequence<int, N - 2>());
  }
}

using FullTurn = ZTurn<kFastRotateOrder>;

template <int L, typename T>
#if defined(__GNUC__)
__attribute__((flatten))
#endif
void rotate_one_band(const T* in, T* out, const FullTurn& za, const FullTurn& zb,
                     const FullTurn& zg, const double* blocks) {
  rotate_band_zxzxz<L>(in, out, za, zb, zg, blocks);
}

template <typename T>
using BandRotator = void (*)(const T*, T*, const FullTurn&, const FullTurn&, const FullTurn&,
                             const double*);

template <typename T, int... I>
constexpr std::array<BandRotator<T>, sizeof...(I)> make_band_rotators(
    std::integer_sequence<int, I...>) {
  return {&rotate_one_band<I + 2, T>...};
}

template <typename T>
void rotate_by_bands(int order, const std::array<double, 9>& m, const T* in, T* out) {
  static constexpr auto kBands =
      make_band_rotators<T>(std::make_integer_sequence<int, kFastRotateOrder - 2>());
  out[0] = in[0];
  rotate_band1(m, in, out);
  const EulerZyz e = decompose_zyz(m);
  const FullTurn za(e.ca, e.sa), zb(e.cb, e.sb), zg(e.cg, e.sg);
  const double* blocks = x_blocks().values;
  for (int l = 2; l < order; ++l) kBands[l - 2](in, out, za, zb, zg, blocks);
}

template <typename T>
using FixedRotator = void (*)(const std::array<double, 9>&, const T*, T*);

template <typename T, int... I>
constexpr std::array<FixedRotator<T>, sizeof...(I)> make_fixed_rotators(
    std::integer_sequence<int, I...>) {
  return {&rotate_fixed_order<I + 1, T>...};
}

template <typename T>
void rotate_coefficients_impl(int order, const std::array<double, 9>& m, const T* in, T* out) {
  static constexpr auto kRotators =
      make_fixed_rotators<T>(std::make_integer_sequence<int, kStraightLineOrder>());
  order = std::clamp(order, 1, kMaxRotationOrder);
  if (order <= kStraightLineOrder) {
    kRotators[order - 1](m, in, out);
  } else if (order <= kFastRotateOrder) {
    rotate_by_bands(order, m, in, out);
  } else {
    Rotation(order, m).apply(in, out);
  }
}

}  // namespace

void rotate_coefficients(int order, const std::array<double, 9>& m, const double* in,
                         double* out) noexcept {
  rotate_coefficients_impl(order, m, in, out);
}

void rotate_coefficients(int order, const std::array<double, 9>& m, const float* in,
                         float* out) noexcept {
  rotate_coefficients_impl(order, m, in, out);
}

}  // namespace prt::sh
