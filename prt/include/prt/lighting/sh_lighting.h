// prt/lighting/sh_lighting.h — the SH lighting an engine passes to the relighting kernel.
//
// Conventions: coefficients of *radiance* (not irradiance, not pre-convolved), in the basis of
// sh/basis.h (real, orthonormal, no Condon–Shortley phase, k = l(l+1)+m, scene frame +Y up);
// three channels R, G, B, stored channel-major: L[c·order² + k]. Exit radiance at a vertex is
// B_c = Σ_k T_c,k · L_c,k (prt/formats/transfer_data.h). Values are kept in double (projection,
// rotation and windowing happen in double) and mirrored in float for the kernel.
//
// Rotation: rotate(M) turns the lighting by the 3×3 rotation matrix M (row-major):
// g(ω) = f(Mᵀω), i.e. light that came from direction d now comes from M·d
// (sh/rotation.h; Ivanic & Ruedenberg 1996, with the 1998 errata).
// Windowing scales band l by sh::window_band_factors (Hanning, Lanczos σ, or Sloan's
// Laplacian penalty 1/(1+λ l²(l+1)²); Sloan, "Stupid SH tricks", 2008) to trade blur for
// ringing. Projection: sh::project (exact texel solid angles).
// Nothing here throws; failures return prt::Status. Compiles as C++17.
// References: [2], [5] of docs/REFERENCES.md.
#pragma once

#include <array>
#include <vector>

#include "prt/core/status.h"
#include "sh/env_map.h"
#include "sh/window.h"

namespace prt {

class ShLighting {
 public:
  static constexpr int kChannels = 3;
  static constexpr int kMaxOrder = 64;  // lighting orders 1 .. 64

  // Black lighting of order 1.
  ShLighting();

  // From 3·order² channel-major coefficients. Errors: order outside [1, kMaxOrder], null
  // pointer, a non-finite value.
  static Result<ShLighting> from_coefficients(int order, const float* rgb_channel_major);
  static Result<ShLighting> from_coefficients(int order, const double* rgb_channel_major);

  // Projects an environment map (linear radiance, 3 floats per texel, row 0 at the top) in one
  // of the sh/env_map.h layouts. Errors: bad order, a size that does not fit the layout,
  // null pixels, a projection that yields non-finite values (Inf/NaN pixels).
  static Result<ShLighting> from_pixels(sh::EnvLayout layout, int width, int height,
                                        const float* rgb, int order);
  static Result<ShLighting> from_env_map(const sh::EnvMap& map, int order);

  // Rotates by the row-major 3×3 matrix m (g(ω) = f(mᵀω)). Errors (lighting unchanged):
  // m not finite, or not orthonormal with determinant +1 to within 1e-5.
  Status rotate(const std::array<double, 9>& m);

  // Multiplies band l by sh::window_band_factors(window, order, strength)[l].
  // A strength <= 0 selects the window's default (sh/window.h). Window::Auto asks
  // sh::choose_window_auto for the weakest window that keeps irradiance non-negative (the
  // `strength` argument is then ignored). Errors: strength not finite.
  Status apply_window(sh::Window window, double strength);

  int order() const { return order_; }
  int coefficient_count() const { return order_ * order_; }

  // order² float coefficients of channel c (0 = R, 1 = G, 2 = B), what the kernel reads.
  const float* coefficients(int channel) const;
  // The same in double precision.
  const double* coefficients_double(int channel) const;

 private:
  void refresh_float_copy();
  int order_ = 1;
  std::vector<double> values_;  // 3·order², channel-major
  std::vector<float> values_f_;
};

}  // namespace prt
