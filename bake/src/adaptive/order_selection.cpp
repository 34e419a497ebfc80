// bake/src/adaptive/order_selection.cpp — SH order from band energies (order_selection.h).
#include "bake/adaptive/order_selection.h"

#include <algorithm>
#include <cmath>

namespace prt::bake {

std::vector<double> band_energies(const double* coefficients, int order) {
  std::vector<double> e(static_cast<std::size_t>(std::max(order, 0)), 0.0);
  for (int l = 0; l < order; ++l)
    for (int k = l * l; k < (l + 1) * (l + 1); ++k) e[l] += coefficients[k] * coefficients[k];
  return e;
}

OrderChoice choose_order(const std::vector<double>& pilot, const std::vector<glm::vec3>& albedo,
                         int pilot_order, const std::vector<double>& lighting, int lighting_order,
                         double target, int max_order, double limit) {
  OrderChoice out;
  const int np = pilot_order, kp = np * np, kl = lighting_order * lighting_order;
  const std::size_t P = albedo.size();
  max_order = std::clamp(max_order, 1, np);
  const int usable = std::min(np, lighting_order);  // bands both sides know
  out.predicted_by_order.assign(np, 0.0);
  out.bound_by_order.assign(np, 0.0);
  out.transfer_band_energy.assign(np, 0.0);
  out.lighting_band_energy.assign(lighting_order, 0.0);
  std::vector<std::vector<double>> light_norm(3);
  std::vector<double> tail_light(3, 0.0);
  for (int c = 0; c < 3; ++c) {
    const std::vector<double> e = band_energies(&lighting[c * kl], lighting_order);
    light_norm[c].resize(lighting_order);
    for (int l = 0; l < lighting_order; ++l) {
      light_norm[c][l] = std::sqrt(e[l]);
      out.lighting_band_energy[l] += e[l];
      if (l >= np) tail_light[c] += light_norm[c][l];
    }
  }
  // Per vertex and channel: the band contributions b_l = ρ Σ_m S_lm L_lm and bounds ρ‖S_l‖‖L_l‖.
  std::vector<double> err2(np, 0.0), bound2(np, 0.0);
  double total2 = 0.0, tail2 = 0.0;
  std::vector<double> band(np), band_bound(np);
  for (std::size_t v = 0; v < P; ++v) {
    const double* s = &pilot[v * kp];
    const std::vector<double> es = band_energies(s, np);
    for (int l = 0; l < np; ++l) out.transfer_band_energy[l] += es[l] / static_cast<double>(P);
    // Stand-in for the bands ≥ np: the smallest energy of the pilot's upper half of bands,
    // taking adjacent bands in pairs (the larger of the two). The last band alone was wrong
    // both ways: an open pilot vertex's analytic clamped cosine has no odd bands l ≥ 3, so an
    // odd last band gave it no tail although its even bands beyond np are not zero; and the
    // pilot's Monte Carlo noise, which adds ~(2l + 1)/N to each band, is largest there. The
    // true energies decrease with l, so the envelope's minimum still covers the bands ≥ np.
    double tail_energy = np >= 2 ? std::max(es[np - 2], es[np - 1]) : es[0];
    for (int l = std::max(1, np / 2); l < np; ++l)
      tail_energy = std::min(tail_energy, std::max(es[l - 1], es[l]));
    for (int c = 0; c < 3; ++c) {
      const double rho = albedo[v][c];
      const double* lc = &lighting[c * kl];
      double full = 0.0;
      for (int l = 0; l < np; ++l) {
        double b = 0.0;
        if (l < usable)
          for (int k = l * l; k < (l + 1) * (l + 1); ++k) b += s[k] * lc[k];
        band[l] = rho * b;
        band_bound[l] = l < usable ? rho * std::sqrt(es[l]) * light_norm[c][l] : 0.0;
        full += band[l];
      }
      total2 += full * full;
      // Suffix sums: error of truncating at n = sum of bands n .. np−1.
      double suffix = 0.0, suffix_bound = 0.0;
      for (int n = np; n >= 1; --n) {
        err2[n - 1] += suffix * suffix;
        bound2[n - 1] += suffix_bound * suffix_bound;
        suffix += band[n - 1];
        suffix_bound += band_bound[n - 1];
      }
      const double tail = rho * std::sqrt(tail_energy) * tail_light[c];
      tail2 += tail * tail;
    }
  }
  const double norm = total2 > 0.0 ? std::sqrt(total2) : 1.0;
  out.tail_bound = std::sqrt(tail2) / norm;
  for (int n = 1; n <= np; ++n) {
    out.predicted_by_order[n - 1] = std::sqrt(err2[n - 1]) / norm;
    out.bound_by_order[n - 1] = std::sqrt(bound2[n - 1]) / norm;
  }
  out.order = max_order;
  for (const double bar : {target, std::max(target, limit)}) {
    for (int n = 1; n <= max_order && !out.met; ++n) {
      if (out.predicted_by_order[n - 1] + out.tail_bound <= bar) {
        out.order = n;
        out.met = true;
        out.beyond_target = bar > target;
      }
    }
  }
  out.haar_recommended = !out.met;
  out.predicted_error = out.predicted_by_order[out.order - 1] + out.tail_bound;
  out.cauchy_schwarz_bound = out.bound_by_order[out.order - 1] + out.tail_bound;
  return out;
}

}  // namespace prt::bake
