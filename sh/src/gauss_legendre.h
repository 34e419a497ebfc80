// sh/src/gauss_legendre.h — private: n-point Gauss–Legendre rule on [−1, 1].
//
// Nodes are the roots of the Legendre polynomial P_n, found by Newton's method from the
// asymptotic guess cos(π(i + ¾)/(n + ½)); weights are 2/((1 − x²)·P_n'(x)²). The rule integrates
// polynomials of degree ≤ 2n − 1 exactly. Used by the exact angular-map solid angles
// (env_map.cpp) and the basis-change matrices of the separable lat-long projection
// (projection.cpp).
#pragma once

#include <cmath>
#include <vector>

#include "sh/constants.h"

namespace prt::sh::detail {

inline void gauss_legendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->assign(n, 0.0);
  weights->assign(n, 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      // P_n(x) and P_{n−1}(x) by the three-term recurrence.
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double pn = n == 0 ? 1.0 : (n == 1 ? x : p1);
      const double pn_minus_1 = n == 1 ? 1.0 : p0;
      derivative = n * (x * pn - pn_minus_1) / (x * x - 1.0);
      const double step = pn / derivative;
      x -= step;
      if (std::abs(step) < 1e-16) break;
    }
    const double weight = 2.0 / ((1.0 - x * x) * derivative * derivative);
    (*nodes)[i] = x;
    (*nodes)[n - 1 - i] = -x;
    (*weights)[i] = weight;
    (*weights)[n - 1 - i] = weight;
  }
}

}  // namespace prt::sh::detail
