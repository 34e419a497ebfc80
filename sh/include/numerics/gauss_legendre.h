// numerics/gauss_legendre.h — the n-point Gauss–Legendre quadrature rule, on [−1, 1] or on an
// interval [a, b].
//
// Contract: append_gauss_legendre(n, a, b, nodes, weights) APPENDS n nodes x_i and weights w_i
// (nothing is cleared, so panels of one composite rule go into the same vectors) such that
//     Σ_i w_i f(x_i) = ∫_a^b f(x) dx   for every polynomial f of degree ≤ 2n − 1
// (up to rounding: nodes and weights to a few units in the last place). Nodes lie strictly
// inside (a, b), in order from b towards a; weights are positive and sum to b − a. Any finite
// a ≠ b is accepted (a > b gives the rule of the reversed interval: negative weights summing to
// b − a); n ≤ 0 appends nothing. gauss_legendre(n, nodes, weights) REPLACES the vectors' contents
// with the rule on [−1, 1] (the same numbers as append_gauss_legendre(n, −1, 1, …)).
// Method: each root t_i of the Legendre polynomial P_n on [−1, 1] by its own Newton iteration
// from the asymptotic guess cos(π(i + ¾)/(n + ½)), P_n and P_n' by the three-term recurrence;
// weights 2/((1 − t_i²) P_n'(t_i)²); then the affine map to [a, b] (x = (a + b)/2 + (b − a)/2 · t,
// w scaled by (b − a)/2). The rule is symmetric to rounding (t_{n−1−i} = −t_i to an ulp), not
// by construction. Cost O(n²) per call; meant for rules of up to a few hundred nodes, built once
// and reused. Thread-safe, no state.
// References: [116] of docs/REFERENCES.md (Abramowitz & Stegun 25.4.29).
#pragma once

#include <vector>

namespace prt::numerics {

void append_gauss_legendre(int n, double a, double b, std::vector<double>* nodes,
                           std::vector<double>* weights);

void gauss_legendre(int n, std::vector<double>* nodes, std::vector<double>* weights);

}  // namespace prt::numerics
