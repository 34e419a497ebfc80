// sh/window.h — windowing (band attenuation) of SH expansions against ringing.
//
// Convention: the basis of sh/basis.h (order n = bands 0..n−1, k = l(l+1) + m). A window is a
// per-band multiplier h_l with h_0 = 1 and 0 ≤ h_l ≤ 1, applied with sh::convolve_zonal.
// References: P.-P. Sloan, "Stupid Spherical Harmonics (SH) Tricks", GDC 2008 (Hanning and
// Lanczos windows, and the Laplacian penalty); C. Lanczos, "Applied Analysis", 1956
// (σ-factors).
//
// Windows and their `strength` (a strength ≤ 0 or non-finite selects the default):
//   None       h_l = 1.
//   Hanning    h_l = ½(1 + cos(π l / w)) for l < w, 0 for l ≥ w; strength = width w in bands
//              (need not be an integer). Default w = order: the last band is attenuated
//              but kept.
//   Lanczos    h_l = sinc(π l / order)^s with sinc(x) = sin(x)/x (the σ-approximation);
//              strength = exponent s. Default s = 1.
//   Laplacian  h_l = 1 / (1 + λ l²(l+1)²), Sloan's minimiser of ∫|∇²f|² with penalty λ;
//              strength = λ. Default λ = 1/((n−1)² n²), which halves the last band (λ = 0
//              for order 1).
//   Auto       not a fixed window: window_band_factors returns all ones; use
//              choose_window_auto, which returns a concrete window and strength.
// References: [6] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

namespace prt::sh {

enum class Window { None, Hanning, Lanczos, Laplacian, Auto };

// "none", "hanning", "lanczos", "laplacian", "auto".
const char* window_name(Window w) noexcept;

// Parses a name of window_name (ASCII case-insensitive; "hann" is accepted for Hanning).
// Returns false, leaving *w untouched, on an unknown name.
bool parse_window(std::string_view name, Window* w) noexcept;

// The strength a strength ≤ 0 (or non-finite) stands for, as listed above.
double default_window_strength(Window w, int order) noexcept;

// Per-band factors h_0..h_{order−1} (empty for order < 1). Always h_0 = 1, 0 ≤ h_l ≤ 1.
std::vector<double> window_band_factors(Window w, int order, double strength);

struct WindowChoice {
  Window window;                 // None or Laplacian
  double strength;               // λ for Laplacian, 0 for None
  double min_irradiance_before;  // over the test directions and channels, unwindowed
  double min_irradiance_after;   // the same with the chosen window
};

// Picks the weakest window that keeps the reconstructed irradiance non-negative.
//
// Input: channel-major radiance coefficients, coefficients[c·order² + k], c < channels.
// Irradiance: E_c(ω) = Σ_l A_l h_l Σ_m L_c,lm Y_lm(ω), A_l the clamped-cosine factors of
// sh/zonal.h (so a constant radiance L gives E = πL).
// Test directions: a spherical Fibonacci lattice of N = clamp(64·order², 1024, 65536) points
// (z_i = 1 − (2i+1)/N, φ_i = i·π(3 − √5)) plus the six axis directions ±x, ±y, ±z.
// "Non-negative" means min over directions and channels of E ≥ −1e-12·max|E_unwindowed|.
// Sequence, weakest first: None, then Laplacian with λ_j = λ_1·2^j, j = 0, 1, …, where
// λ_1 = 1/(100·(n−1)²n²) (the last band keeps 99 %), up to λ ≥ 1e6 (band 1 keeps 2.5e-7).
// The first candidate that passes is returned. If none passes (e.g. the mean radiance is
// negative), the candidate with the largest minimum is returned, and min_irradiance_after
// stays negative: the caller should report it. Orders < 1, channels < 1 or non-finite input
// return None with minima 0 (or NaN for non-finite input).
// `progress` (optional) is called now and then with (test directions done, directions in all):
// at high orders the search takes seconds (order 200: about 13 CPU-seconds).
using WindowProgress = std::function<void(std::uint64_t done, std::uint64_t total)>;
WindowChoice choose_window_auto(const double* coefficients, int channels, int order,
                                const WindowProgress& progress = {});

}  // namespace prt::sh
