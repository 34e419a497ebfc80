// bake/adaptive/order_selection.h — choosing the SH order of a bake from the lighting's band energy
// and the transfer's, so that the predicted error of the exit radiance meets a tolerance.
//
// Convention: sh/basis.h (real orthonormal SH, no Condon–Shortley phase, k = l(l+1)+m, scene
// frame glTF +Y up). Lighting: channel-major RGB SH coefficients of distant radiance,
// L[c·n² + k]. Transfer: grey per-vertex vectors S (albedo applied per channel), B = ρ_c S·L_c.
//
// Truncating at order n drops bands l ≥ n. By orthonormality the exit radiance of vertex v is
// B_v,c = ρ_c Σ_l Σ_m S_v,lm L_c,lm, so the truncation error is
//   e_v,c(n) = ρ_c Σ_{l ≥ n} Σ_m S_v,lm L_c,lm,
// and band by band Cauchy–Schwarz gives |e_v,c(n)| ≤ ρ_c Σ_{l ≥ n} ‖S_v,l‖·‖L_c,l‖ with
// ‖x_l‖ = (Σ_m x_lm²)^½ (the band energies' square roots; cf. Ramamoorthi & Hanrahan 2001 on
// band-limited irradiance, Sloan et al. 2002 §7 on choosing n). From a pilot bake of P vertices
// at order n_p we get, for every n < n_p,
//   predicted(n) = [Σ_v,c e_v,c(n)²]^½ / [Σ_v,c B_v,c²]^½  (bands n .. n_p−1, exact sums), and
//   bound(n)     = the same with |e| replaced by its Cauchy–Schwarz bound,
// plus tail = a Cauchy–Schwarz bound of bands ≥ n_p, where the pilot does not see the transfer:
// it takes the smallest transfer band norm of the pilot's upper half of bands (adjacent bands in
// pairs, the larger of each pair) as a stand-in for every higher band (transfer band norms of
// clamped-cosine × visibility decrease with l, and the pilot's noise inflates its last bands)
// times the lighting's band norms
// beyond n_p (zero when the lighting given stops at n_p). The chosen order is the smallest n
// ≤ max_order with predicted(n) + tail ≤ target; when there is none, the smallest with
// predicted(n) + tail ≤ limit (the caller then leaves less of its tolerance to sampling); when
// there is none either (a sun: energy in every band), the Haar basis is recommended.
// References: [1], [2] of docs/REFERENCES.md.
#pragma once

#include <vector>

#include <glm/glm.hpp>

namespace prt::bake {

// E(l) = Σ_m c_lm² for l = 0 .. order−1.
std::vector<double> band_energies(const double* coefficients, int order);

struct OrderChoice {
  int order = 1;
  bool met = false;                 // some order ≤ max_order meets the target or the limit
  bool beyond_target = false;       // met the limit only
  bool haar_recommended = false;    // !met (bake_transfer_auto clears it when its bake at
                                    // max_order meets the tolerance as a whole)
  double predicted_error = 0;       // predicted(order) + tail
  double cauchy_schwarz_bound = 0;  // bound(order) + tail
  double tail_bound = 0;
  std::vector<double> predicted_by_order;  // [n−1] for n = 1 .. pilot_order
  std::vector<double> bound_by_order;
  std::vector<double> lighting_band_energy;  // per band, summed over channels
  std::vector<double> transfer_band_energy;  // per band, mean over pilot vertices
};

// pilot: P × pilot_order² grey transfer vectors, vertex-major; albedo: P values (rgb).
// lighting: 3 × lighting_order² coefficients. max_order ≤ pilot_order. limit ≤ target: none.
OrderChoice choose_order(const std::vector<double>& pilot, const std::vector<glm::vec3>& albedo,
                         int pilot_order, const std::vector<double>& lighting, int lighting_order,
                         double target, int max_order, double limit = 0.0);

}  // namespace prt::bake
