// report/src/stability_numerics.cpp — stability cases: SH evaluation at high order near and at
// the poles (double and float), and the orthogonality of high-order SH rotation matrices.
//
// Reference for evaluation: the normalised recurrence of P.-P. Sloan, "Efficient Spherical
// Harmonic Evaluation", JCGT 2(2), 2013, recomputed here in long double (x87: 64-bit mantissa,
// exponent range to 1e-4951, so sin^m θ never underflows at θ ≥ 1e-12, l ≤ 200), checked
// against the addition theorem Σ_m Y_lm² = (2l+1)/4π. Basis: sh/basis.h (no Condon–Shortley
// phase, k = l(l+1)+m). Rotation: sh/rotation.h (Ivanic & Ruedenberg 1996/1998).
#include <array>
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/rotation.h"
#include "report/stability_cases.h"

namespace prt::report::stability {
namespace {

using sh::kPi;
using sh::kPiLong;

// All order² values of Y_lm at (x, y, z), |(x, y, z)| = 1 assumed as the library does (z is
// cos θ, x + iy is sin θ·e^{iφ}), in long double.
std::vector<long double> evaluate_reference(int order, long double x, long double y,
                                            long double z) {
  std::vector<long double> out(static_cast<std::size_t>(order) * order, 0.0L);
  // Q_mm = √((2m+1)/(2m))·Q_{m−1,m−1}, Q_00 = 1/√(4π); Q_{m+1,m} = √(2m+3)·z·Q_mm;
  // Q_lm = a·(z·Q_{l−1,m} − b·Q_{l−2,m}), a = √((4l²−1)/(l²−m²)),
  // b = √(((l−1)²−m²)/(4(l−1)²−1)). Y_lm = √2·Q_l|m|·{Re, Im}((x+iy)^|m|), Y_l0 = Q_l0.
  long double qmm = 1.0L / std::sqrt(4.0L * kPiLong);
  std::complex<long double> power(1.0L, 0.0L);
  const std::complex<long double> xy(x, y);
  for (int m = 0; m < order; ++m) {
    if (m > 0) {
      qmm *= std::sqrt((2.0L * m + 1.0L) / (2.0L * m));
      power *= xy;
    }
    long double q_prev2 = 0, q_prev = qmm;
    for (int l = m; l < order; ++l) {
      long double q;
      if (l == m) {
        q = qmm;
      } else if (l == m + 1) {
        q = std::sqrt(2.0L * m + 3.0L) * z * qmm;
      } else {
        const long double ll = l, mm = m;
        const long double a = std::sqrt((4.0L * ll * ll - 1.0L) / (ll * ll - mm * mm));
        const long double b =
            std::sqrt(((ll - 1) * (ll - 1) - mm * mm) / (4.0L * (ll - 1) * (ll - 1) - 1.0L));
        q = a * (z * q_prev - b * q_prev2);
      }
      if (l > m) {
        q_prev2 = q_prev;
        q_prev = q;
      }
      if (m == 0) {
        out[sh::index(l, 0)] = q;
      } else {
        const long double s = std::sqrt(2.0L) * q;
        out[sh::index(l, m)] = s * power.real();
        out[sh::index(l, -m)] = s * power.imag();
      }
    }
  }
  return out;
}

// Relative error of band l: ‖Y_l − ref_l‖₂ / ‖ref_l‖₂ (non-finite values give +Inf).
template <class T>
double band_error(const T* values, const std::vector<long double>& ref, int l) {
  long double num = 0, den = 0;
  for (int m = -l; m <= l; ++m) {
    const long double v = values[sh::index(l, m)];
    if (!std::isfinite(v)) return INFINITY;
    const long double d = v - ref[sh::index(l, m)];
    num += d * d;
    den += ref[sh::index(l, m)] * ref[sh::index(l, m)];
  }
  return static_cast<double>(std::sqrt(num / den));
}

std::string format(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2e", v);
  return buf;
}

}  // namespace

CaseResult check_sh_evaluation_at_poles(const CaseOptions&) {
  return run_case(
      "numerics", "sh_eval_poles_l200",
      "double: band error <= 1e-10 for every l <= 200 at θ = 0, 1e-12 .. 1e-3 from both poles "
      "and a generic direction; float: error < 1e-3 to l >= 100 and finite to l > 150; where it "
      "stops being usable is reported",
      [](CaseResult& r) {
        constexpr int kOrder = 201;  // l = 0..200
        const double thetas[] = {0.0, 1e-12, 1e-9, 1e-6, 1e-3, 1.1};
        const double phi = 0.7;
        std::vector<double> worst_double(kOrder, 0.0), worst_float(kOrder, 0.0);
        double worst_addition = 0;
        bool double_finite = true, float_finite = true;
        int first_nonfinite = kOrder;  // first band where float gives NaN/Inf (kOrder: none)
        std::vector<double> yd(kOrder * kOrder);
        std::vector<float> yf(kOrder * kOrder);
        for (double pole : {1.0, -1.0}) {
          for (double theta : thetas) {
            const double t = pole > 0 ? theta : kPi - theta;
            double x = std::sin(t) * std::cos(phi), y = std::sin(t) * std::sin(phi),
                   z = std::cos(t);
            if (theta == 0) x = y = 0, z = pole;  // exactly at the pole
            sh::evaluate(kOrder, x, y, z, yd.data());
            const auto ref = evaluate_reference(kOrder, x, y, z);
            const float xf = static_cast<float>(x), yf1 = static_cast<float>(y),
                        zf = static_cast<float>(z);
            sh::evaluate(kOrder, xf, yf1, zf, yf.data());
            // Reference at the float-rounded input: the float path is judged on its arithmetic,
            // not on the rounding of its argument.
            const auto ref_f = evaluate_reference(kOrder, xf, yf1, zf);
            for (int l = 0; l < kOrder; ++l) {
              long double norm2 = 0;
              for (int m = -l; m <= l; ++m) norm2 += ref[sh::index(l, m)] * ref[sh::index(l, m)];
              // Addition theorem for a unit vector: Σ_m Y_lm² = (2l+1)/4π (checks the reference).
              const long double unit2 = static_cast<long double>(x) * x +
                                        static_cast<long double>(y) * y +
                                        static_cast<long double>(z) * z;
              const double add_err = static_cast<double>(std::fabs(
                  norm2 / ((2.0L * l + 1.0L) / (4.0L * kPiLong) * std::pow(unit2, l)) - 1.0L));
              worst_addition = std::max(worst_addition, add_err);
              worst_double[l] = std::max(worst_double[l], band_error(yd.data(), ref, l));
              worst_float[l] = std::max(worst_float[l], band_error(yf.data(), ref_f, l));
            }
            for (double v : yd) double_finite &= std::isfinite(v);
            for (int l = 0; l < kOrder; ++l)
              for (int m = -l; m <= l; ++m)
                if (!std::isfinite(yf[sh::index(l, m)])) {
                  float_finite = false;
                  first_nonfinite = std::min(first_nonfinite, l);
                }
          }
        }
        double max_double = 0;
        for (double e : worst_double) max_double = std::max(max_double, e);
        int float_usable_l = -1;
        while (float_usable_l + 1 < kOrder && worst_float[float_usable_l + 1] < 1e-3)
          ++float_usable_l;
        r.add("double_max_band_error", max_double);
        r.add("reference_addition_theorem_error", worst_addition);
        r.add("float_usable_up_to_l", float_usable_l);
        r.add("float_first_nonfinite_l", first_nonfinite);
        r.add("float_error_l10", worst_float[10]);
        r.add("float_error_l50", worst_float[50]);
        r.add("float_error_l100", std::isfinite(worst_float[100]) ? worst_float[100] : -1);
        r.table_header = {"l", "double band error", "float band error"};
        for (int l : {1, 10, 20, 50, 100, 150, 180, 190, 200})
          r.table_rows.push_back(
              {std::to_string(l), format(worst_double[l]),
               std::isfinite(worst_float[l]) ? format(worst_float[l]) : "non-finite"});
        // The reference itself satisfies the addition theorem to 1e-10 (measured 1.8e-12 at
        // l = 200: its recurrence error in long double).
        // Float is judged on being usable (error < 1e-3) to l >= 100 and finite to l >= 150; its
        // known overflow near the poles beyond that (sh/basis.h: "keep float to moderate
        // orders") is reported, not hidden.
        r.passed = double_finite && max_double <= 1e-10 && worst_addition < 1e-10 &&
                   float_usable_l >= 100 && first_nonfinite > 150;
        r.detail =
            "float stays below 1e-3 band error up to l = " + std::to_string(float_usable_l) +
            (float_finite ? "; float finite to l = 200"
                          : "; float gives NaN/Inf from l = " + std::to_string(first_nonfinite) +
                                " near the poles (intermediate overflow)") +
            "; worst double band error " + format(max_double);
      });
}

CaseResult check_rotation_orthogonality(const CaseOptions& options) {
  const int order = options.quick ? 61 : 101;
  return run_case(
      "numerics", "rotation_orthogonality",
      "max |R_l R_lᵀ − I| <= 1e-10 for l <= 30 and finite for every l up to " +
          std::to_string(order - 1) + "; growth per 20 bands reported",
      [order](CaseResult& r) {
        const sh::Rotation rotation(order, sh::rotation_from_yaw_pitch_roll(37.0, 23.0, 71.0));
        if (rotation.order() != order) throw std::runtime_error("rotation: allocation failed");
        std::vector<double> err(order, 0.0);
        bool finite = true;
        for (int l = 0; l < order; ++l) {
          const double* b = rotation.band_matrix(l);
          const int n = 2 * l + 1;
          double e = 0;
          for (int i = 0; i < n; ++i) {
            for (int j = 0; j < n; ++j) {
              double s = 0;  // (B Bᵀ)_ij
              for (int k = 0; k < n; ++k) s += b[i * n + k] * b[j * n + k];
              e = std::max(e, std::fabs(s - (i == j ? 1.0 : 0.0)));
            }
          }
          if (!std::isfinite(e)) finite = false, e = INFINITY;
          err[l] = e;
        }
        // Running maximum: the error of bands ≤ l.
        for (int l = 1; l < order; ++l) err[l] = std::max(err[l], err[l - 1]);
        r.table_header = {"l", "max |R Rᵀ − I| (bands ≤ l)", "growth over 20 bands"};
        for (int l = 20; l < order; l += 20)
          r.table_rows.push_back({std::to_string(l), format(err[l]),
                                  l >= 40 ? format(err[l] / std::max(err[l - 20], 1e-300)) : ""});
        r.add("error_l30", err[30]);
        r.add("error_l60", err[60]);
        if (order > 100) r.add("error_l100", err[100]);
        r.add("error_max", err[order - 1]);
        r.passed = finite && err[30] <= 1e-10;
        r.detail = "orthogonality error " + format(err[20]) + " at l = 20, " + format(err[40]) +
                   " at l = 40, " + format(err[order - 1]) + " at l = " + std::to_string(order - 1);
      });
}

}  // namespace prt::report::stability
