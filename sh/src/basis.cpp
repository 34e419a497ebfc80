// sh/src/basis.cpp — real SH evaluation: normalised recurrence plus an order ≤ 6 fast path.
//
// Notation (see basis.h for the convention). For m ≥ 0 write
//   Y_l0  = Q_l0(z),
//   Y_lm  = Q_lm(z) · C_m,   Y_l,−m = Q_lm(z) · S_m,   with C_m + i S_m = (x + i y)^m,
// where Q_lm(z) = √2·N_lm · d^m P_l(z)/dz^m (the √2 only for m > 0) is a polynomial in z, and
// N_lm = √((2l+1)/4π · (l−m)!/(l+m)!). Since x + iy = sin θ·e^{iφ}, C_m = sin^m θ cos mφ and
// S_m = sin^m θ sin mφ, so nothing divides by sin θ and nothing calls atan2.
//
// Q_lm obeys the standard normalised recurrences (e.g. Sloan, "Efficient Spherical Harmonic
// Evaluation", JCGT 2(2), 2013; Holmes & Featherstone, J. Geodesy 76, 2002):
//   Q_00 = 1/√(4π),  Q_mm = Q_{m−1,m−1} · √((2m+1)/(2m))  (× √2 once, at m = 1),
//   Q_{m+1,m} = √(2m+3) · z · Q_mm,
//   Q_lm = a_lm · z · Q_{l−1,m} − a_lm·b_lm · Q_{l−2,m},
//   a_lm = √((4l²−1)/(l²−m²)),  b_lm = √(((l−1)²−m²)/(4(l−1)²−1)).
// |Q_lm| stays below 1e214 for every l < kMaxOrder (its maximum, at z = ±1, is
// √((l+m)!/(l−m)!)/(2^m m!) · √((2l+1)/4π)), so Q never overflows in double.
//
// Underflow, handled deliberately: the only factor that can underflow is (x + iy)^m near the
// poles. The loop keeps it as a mantissa times 2^(−kRescaleBits·e): whenever |C_m| and |S_m|
// both drop below 2^(−kRescaleBits) they are multiplied by 2^kRescaleBits and e is
// incremented, and the outputs of that m are scaled back once. A result is therefore only
// flushed to zero (or made subnormal) when its true magnitude is below the type's smallest
// normal number times |Q| — in double, below 1e-200 for every l ≤ 200.
#include "sh/basis.h"

#include <array>
#include <cmath>
#include <utility>
#include <vector>

#include "sh/constants.h"

namespace prt::sh {
namespace {

// ---- hard-coded polynomial fast path, orders 1..6 ---------------------------------------
// The constants are the coefficients of Q_lm(z) above, written in z² (Horner form) times
// z^((l−m) mod 2), computed exactly (rational Legendre coefficients times N_lm at 40 digits)
// and rounded to 17 significant digits. The tests check them against the recurrence.

template <typename T>
inline void band0(T /*z*/, T /*z2*/, const T* /*c*/, const T* /*s*/, T* out) noexcept {
  out[0] = T(kY00);
}

template <typename T>
inline void band1(T z, T /*z2*/, const T* c, const T* s, T* out) noexcept {
  out[2] = T(0.48860251190291992) * z;
  {
    const T q = T(0.48860251190291992);
    out[3] = q * c[1];
    out[1] = q * s[1];
  }
}

template <typename T>
inline void band2(T z, T z2, const T* c, const T* s, T* out) noexcept {
  out[6] = T(0.94617469575756002) * z2 + T(-0.31539156525252001);
  {
    const T q = T(1.0925484305920791) * z;
    out[7] = q * c[1];
    out[5] = q * s[1];
  }
  {
    const T q = T(0.54627421529603954);
    out[8] = q * c[2];
    out[4] = q * s[2];
  }
}

template <typename T>
inline void band3(T z, T z2, const T* c, const T* s, T* out) noexcept {
  out[12] = z * (T(1.865881662950577) * z2 + T(-1.1195289977703462));
  {
    const T q = T(2.2852289973223287) * z2 + T(-0.45704579946446574);
    out[13] = q * c[1];
    out[11] = q * s[1];
  }
  {
    const T q = T(1.445305721320277) * z;
    out[14] = q * c[2];
    out[10] = q * s[2];
  }
  {
    const T q = T(0.59004358992664351);
    out[15] = q * c[3];
    out[9] = q * s[3];
  }
}

template <typename T>
inline void band4(T z, T z2, const T* c, const T* s, T* out) noexcept {
  out[20] = (T(3.7024941420321506) * z2 + T(-3.1735664074561291)) * z2 + T(0.31735664074561291);
  {
    const T q = z * (T(4.6833258049010242) * z2 + T(-2.0071396306718675));
    out[21] = q * c[1];
    out[19] = q * s[1];
  }
  {
    const T q = T(3.3116114351514601) * z2 + T(-0.47308734787878001);
    out[22] = q * c[2];
    out[18] = q * s[2];
  }
  {
    const T q = T(1.7701307697799305) * z;
    out[23] = q * c[3];
    out[17] = q * s[3];
  }
  {
    const T q = T(0.62583573544917613);
    out[24] = q * c[4];
    out[16] = q * s[4];
  }
}

template <typename T>
inline void band5(T z, T z2, const T* c, const T* s, T* out) noexcept {
  out[30] =
      z * ((T(7.3678703145656866) * z2 + T(-8.1865225717396518)) * z2 + T(1.7542548368013539));
  {
    const T q = (T(9.5118796751096353) * z2 + T(-6.3412531167397569)) * z2 + T(0.45294665119569692);
    out[31] = q * c[1];
    out[29] = q * s[1];
  }
  {
    const T q = z * (T(7.1903051774599856) * z2 + T(-2.3967683924866619));
    out[32] = q * c[2];
    out[28] = q * s[2];
  }
  {
    const T q = T(4.4031446949172535) * z2 + T(-0.48923829943525039);
    out[33] = q * c[3];
    out[27] = q * s[3];
  }
  {
    const T q = T(2.0756623148810413) * z;
    out[34] = q * c[4];
    out[26] = q * s[4];
  }
  {
    const T q = T(0.6563820568401701);
    out[35] = q * c[5];
    out[25] = q * s[5];
  }
}

// Fills bands 0 … N−1 (N² outputs). Band l reads z, z² and C_m, S_m for m ≤ l, with
// C_m + i S_m = (x + i y)^m formed by repeated complex products.
template <int N, typename T>
inline void evaluate_fixed(T x, T y, T z, T* out) noexcept {
  const T z2 = z * z;
  T c[N + 1] = {T(1), x};
  T s[N + 1] = {T(0), y};
  for (int m = 2; m < N; ++m) {
    c[m] = x * c[m - 1] - y * s[m - 1];
    s[m] = x * s[m - 1] + y * c[m - 1];
  }
  band0(z, z2, c, s, out);
  if constexpr (N > 1) band1(z, z2, c, s, out);
  if constexpr (N > 2) band2(z, z2, c, s, out);
  if constexpr (N > 3) band3(z, z2, c, s, out);
  if constexpr (N > 4) band4(z, z2, c, s, out);
  if constexpr (N > 5) band5(z, z2, c, s, out);
}

// ---- general recurrence ------------------------------------------------------------------

// Bands below kTableOrder read a_lm and a_lm·b_lm from tables; above, they are computed inline.
constexpr int kTableOrder = 128;

template <typename T>
struct RecurrenceTables {
  std::vector<T> seed;   // Q_mm, m < kMaxOrder (includes the √2 for m > 0)
  std::vector<T> first;  // √(2m+3), m < kMaxOrder
  std::vector<T> a;      // a_lm at triangle(l) + m, l < kTableOrder, m ≤ l − 2
  std::vector<T> ab;     // a_lm · b_lm, same layout

  static int triangle(int l) { return l * (l + 1) / 2; }

  RecurrenceTables() : seed(kMaxOrder), first(kMaxOrder) {
    double q = 1.0 / std::sqrt(4.0 * kPi);
    for (int m = 0; m < kMaxOrder; ++m) {
      if (m > 0) q *= std::sqrt((2.0 * m + 1.0) / (2.0 * m));
      seed[m] = static_cast<T>(m > 0 ? q * std::sqrt(2.0) : q);
      first[m] = static_cast<T>(std::sqrt(2.0 * m + 3.0));
    }
    a.resize(triangle(kTableOrder));
    ab.resize(triangle(kTableOrder));
    for (int l = 2; l < kTableOrder; ++l) {
      for (int m = 0; m <= l - 2; ++m) {
        double al, abl;
        coefficients(l, m, &al, &abl);
        a[triangle(l) + m] = static_cast<T>(al);
        ab[triangle(l) + m] = static_cast<T>(abl);
      }
    }
  }

  static void coefficients(int l, int m, double* a_lm, double* ab_lm) {
    const double ll = double(l) * l, mm = double(m) * m, l1 = double(l - 1) * (l - 1);
    *a_lm = std::sqrt((4.0 * ll - 1.0) / (ll - mm));
    *ab_lm = *a_lm * std::sqrt((l1 - mm) / (4.0 * l1 - 1.0));
  }
};

template <typename T>
const RecurrenceTables<T>& tables() {
  static const RecurrenceTables<T> instance;  // thread-safe initialisation (C++11 statics)
  return instance;
}

template <typename T>
struct RescaleTraits;
template <>
struct RescaleTraits<double> {
  static constexpr int kBits = 512;
};
template <>
struct RescaleTraits<float> {
  static constexpr int kBits = 64;
};

// Writes band l's ±m entries from Q_lm = q; `scale` undoes the rescaling of (c, s).
template <typename T, bool kScaled>
inline void store(T* out, int l, int m, T q, T c, T s, T scale) {
  const int k = l * (l + 1);
  if (m == 0) {
    out[k] = q;
  } else if (kScaled) {
    out[k + m] = (q * c) * scale;
    out[k - m] = (q * s) * scale;
  } else {
    out[k + m] = q * c;
    out[k - m] = q * s;
  }
}

template <typename T, bool kScaled>
inline void run_column(int order, int m, T z, T c, T s, T scale, const RecurrenceTables<T>& t,
                       T* out) {
  T q2 = t.seed[m];
  store<T, kScaled>(out, m, m, q2, c, s, scale);
  if (m + 1 >= order) return;
  T q1 = t.first[m] * z * q2;
  store<T, kScaled>(out, m + 1, m, q1, c, s, scale);
  const int table_end = order < kTableOrder ? order : kTableOrder;
  int l = m + 2;
  for (; l < table_end; ++l) {
    const int i = RecurrenceTables<T>::triangle(l) + m;
    const T q = t.a[i] * z * q1 - t.ab[i] * q2;
    store<T, kScaled>(out, l, m, q, c, s, scale);
    q2 = q1;
    q1 = q;
  }
  for (; l < order; ++l) {
    double a, ab;
    RecurrenceTables<T>::coefficients(l, m, &a, &ab);
    const T q = static_cast<T>(a) * z * q1 - static_cast<T>(ab) * q2;
    store<T, kScaled>(out, l, m, q, c, s, scale);
    q2 = q1;
    q1 = q;
  }
}

// The same column recurrence with the order known at compile time (fully unrolled; about
// 40 % faster at order 10), for orders ≤ 16. It does the same arithmetic as
// run_column, in the same order, so the results are identical. It skips the rescaling: for
// l < 16, |Q_lm| < 1e4, so a product with an underflowed (x + iy)^m is below 1e-300 in double
// (1e-34 in float) anyway.
template <typename T, int N>
void evaluate_columns_fixed(T x, T y, T z, T* out, const RecurrenceTables<T>& t) {
  T c = 1, s = 0;
#pragma GCC unroll 32
  for (int m = 0; m < N; ++m) {
    if (m > 0) {
      const T cn = x * c - y * s;
      s = x * s + y * c;
      c = cn;
    }
    T q2 = t.seed[m];
    if (m == 0) {
      out[0] = q2;
    } else {
      out[m * (m + 1) + m] = q2 * c;
      out[m * (m + 1) - m] = q2 * s;
    }
    if (m + 1 < N) {
      T q1 = t.first[m] * z * q2;
      const int k1 = (m + 1) * (m + 2);
      if (m == 0) {
        out[k1] = q1;
      } else {
        out[k1 + m] = q1 * c;
        out[k1 - m] = q1 * s;
      }
#pragma GCC unroll 32
      for (int l = m + 2; l < N; ++l) {
        const int i = RecurrenceTables<T>::triangle(l) + m;
        const T q = t.a[i] * z * q1 - t.ab[i] * q2;
        const int k = l * (l + 1);
        if (m == 0) {
          out[k] = q;
        } else {
          out[k + m] = q * c;
          out[k - m] = q * s;
        }
        q2 = q1;
        q1 = q;
      }
    }
  }
}

constexpr int kFixedOrders = 16;

template <typename T>
using FixedEvaluator = void (*)(T, T, T, T*, const RecurrenceTables<T>&);

// {evaluate_columns_fixed<T, 1>, …, evaluate_columns_fixed<T, kFixedOrders>}.
template <typename T, int... I>
constexpr std::array<FixedEvaluator<T>, sizeof...(I)> make_fixed_table(
    std::integer_sequence<int, I...>) {
  return {&evaluate_columns_fixed<T, I + 1>...};
}

template <typename T>
void evaluate_recurrence_impl(int order, T x, T y, T z, T* out) {
  if (order < 1 || order > kMaxOrder) return;
  const RecurrenceTables<T>& t = tables<T>();
  if (order <= kFixedOrders) {
    static constexpr auto kFixed =
        make_fixed_table<T>(std::make_integer_sequence<int, kFixedOrders>());
    kFixed[order - 1](x, y, z, out, t);
    return;
  }
  constexpr int kBits = RescaleTraits<T>::kBits;
  const T tiny = std::ldexp(T(1), -kBits), big = std::ldexp(T(1), kBits);
  T c = 1, s = 0;  // (x + iy)^m · 2^(kBits·e)
  int e = 0;
  for (int m = 0; m < order; ++m) {
    if (m > 0) {
      const T cn = x * c - y * s;
      s = x * s + y * c;
      c = cn;
      if (std::fabs(c) < tiny && std::fabs(s) < tiny && (c != 0 || s != 0)) {
        c *= big;
        s *= big;
        ++e;
      }
    }
    if (e == 0) {
      run_column<T, false>(order, m, z, c, s, T(1), t, out);
    } else {
      // 2^(−kBits·e) is subnormal or 0 for e ≥ 2 in double; the results it degrades
      // are then below 2^(−2·kBits)·max|Q| (< 1e-90 in double, < 1e-33 in float).
      const T scale = std::ldexp(T(1), -kBits * e);
      run_column<T, true>(order, m, z, c, s, scale, t, out);
    }
  }
}

template <typename T>
void evaluate_impl(int order, T x, T y, T z, T* out) {
  switch (order) {
    case 1:
      evaluate_fixed<1>(x, y, z, out);
      return;
    case 2:
      evaluate_fixed<2>(x, y, z, out);
      return;
    case 3:
      evaluate_fixed<3>(x, y, z, out);
      return;
    case 4:
      evaluate_fixed<4>(x, y, z, out);
      return;
    case 5:
      evaluate_fixed<5>(x, y, z, out);
      return;
    case 6:
      evaluate_fixed<6>(x, y, z, out);
      return;
    default:
      evaluate_recurrence_impl(order, x, y, z, out);
      return;
  }
}

}  // namespace

void evaluate(int order, double x, double y, double z, double* out) noexcept {
  evaluate_impl(order, x, y, z, out);
}

void evaluate(int order, float x, float y, float z, float* out) noexcept {
  evaluate_impl(order, x, y, z, out);
}

void evaluate_recurrence(int order, double x, double y, double z, double* out) noexcept {
  evaluate_recurrence_impl(order, x, y, z, out);
}

void evaluate_recurrence(int order, float x, float y, float z, float* out) noexcept {
  evaluate_recurrence_impl(order, x, y, z, out);
}

}  // namespace prt::sh
