# Generates the hard-coded order 1..6 polynomial fast path of sh/src/basis.cpp.
from fractions import Fraction
from mpmath import mp, mpf, sqrt, pi, factorial
mp.dps = 40

def legendre_coeffs(l):
    # P_l(z) coefficients (index = power), via Bonnet recurrence with exact fractions.
    p0, p1 = [Fraction(1)], [Fraction(0), Fraction(1)]
    if l == 0: return p0
    for n in range(1, l):
        # (n+1) P_{n+1} = (2n+1) z P_n - n P_{n-1}
        a = [Fraction(0)] + [c * (2 * n + 1) for c in p1]
        b = [c * n for c in p0] + [Fraction(0)] * (len(a) - len(p0))
        p0, p1 = p1, [(x - y) / (n + 1) for x, y in zip(a, b)]
    return p1

def deriv(c, m):
    for _ in range(m):
        c = [c[i] * i for i in range(1, len(c))] or [Fraction(0)]
    return c

def q_poly(l, m):
    c = deriv(legendre_coeffs(l), m)
    n = sqrt(mpf(2 * l + 1) / (4 * pi) * factorial(l - m) / factorial(l + m))
    if m > 0: n *= sqrt(2)
    return [n * mpf(x.numerator) / x.denominator for x in c]

def fmt(v):
    return 'T(%s)' % mp.nstr(v, 17, min_fixed=-100, max_fixed=100)

def horner(coeffs, l, m):
    # Q_lm has parity (l - m): z^{(l-m)%2} * poly(z^2).
    par = (l - m) % 2
    cs = [coeffs[i] for i in range(par, len(coeffs), 2)]
    expr = fmt(cs[-1])
    for c in reversed(cs[:-1]):
        expr = '%s * z2 + %s' % ('(' + expr + ')' if '+' in expr or '-' in expr[1:] else expr, fmt(c))
    if par:
        expr = 'z * (%s)' % expr if len(cs) > 1 else '%s * z' % fmt(cs[0])
    return expr

out = []
for order in range(1, 7):
    out.append('template <typename T>')
    out.append('inline void evaluate_order%d(T x, T y, T z, T* out) noexcept {' % order)
    if order == 1:
        out.append('  (void)x;\n  (void)y;\n  (void)z;')
    if order > 2: out.append('  const T z2 = z * z;')
    for m in range(1, order):
        if m == 1: out.append('  const T c1 = x, s1 = y;')
        else: out.append('  const T c%d = x * c%d - y * s%d, s%d = x * s%d + y * c%d;' % (m, m-1, m-1, m, m-1, m-1))
    for l in range(order):
        for m in range(0, l + 1):
            e = horner(q_poly(l, m), l, m)
            k = l * (l + 1)
            if m == 0:
                out.append('  out[%d] = %s;' % (k, e))
            else:
                out.append('  {\n    const T q = %s;\n    out[%d] = q * c%d;\n    out[%d] = q * s%d;\n  }' % (e, k + m, m, k - m, m))
    out.append('}\n')
print('\n'.join(out))
