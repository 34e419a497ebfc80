// sh/src/numerics/gauss_legendre.cpp — the Gauss–Legendre rule of numerics/gauss_legendre.h.
#include "numerics/gauss_legendre.h"

#include <cmath>

#include "numerics/constants.h"

namespace prt::numerics {

void append_gauss_legendre(int n, double a, double b, std::vector<double>* nodes,
                           std::vector<double>* weights) {
  const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
  for (int i = 0; i < n; ++i) {
    double x = std::cos(kPi * (i + 0.75) / (n + 0.5));
    double derivative = 1.0;
    for (int iteration = 0; iteration < 100; ++iteration) {
      double p0 = 1.0, p1 = x;  // P_0, P_1; then the three-term recurrence up to P_n
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      derivative = n * (x * p1 - p0) / (x * x - 1.0);
      const double step = p1 / derivative;
      x -= step;
      if (std::fabs(step) < 1e-16) break;
    }
    nodes->push_back(mid + half * x);
    weights->push_back(half * 2.0 / ((1.0 - x * x) * derivative * derivative));
  }
}

void gauss_legendre(int n, std::vector<double>* nodes, std::vector<double>* weights) {
  nodes->clear();
  weights->clear();
  append_gauss_legendre(n, -1.0, 1.0, nodes, weights);
}

}  // namespace prt::numerics
