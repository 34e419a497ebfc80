// prt/diffuse/relighter.h — the shading kernel: exit radiance of vertices under SH lighting.
//
// B_v,c = Σ_{k < K} T_v,c',k · L_c,k  for the output channels c = R, G, B, where c' = c for
// 3-channel transfer and c' = 0 for 1-channel (grey) transfer (which gives RGB under RGB
// lighting). The basis is sh/basis.h's; L is *radiance* (prt/lighting/sh_lighting.h); T is the
// file's transfer (prt/formats/transfer_data.h), so B is exit radiance in the units of L.
//
// Orders: K = min(order_file, order_light)² — lighting of a higher order is truncated to the
// file's bands, lighting of a lower order is zero-extended (the missing bands contribute 0).
//
// Layout: coefficients are kept as in the file (prt/formats/transfer_file.h): blocks of 16
// vertices, within a block channel-major, coefficient-major, then the 16 vertices; f32 or binary16.
//
// Arithmetic: each block accumulates in float over k in increasing order, one multiply and
// one add per term (never fused, on every path), so results are deterministic and identical
// between the AVX2/F16C path and the portable path, on any machine. The float error is at most
// about K·2^-24 relative to Σ_k |T_k L_k| (K = order² ≤ a few hundred terms): far below the
// 2^-11 of binary16 storage and of 8-bit output.
//
// Threads: every shading call is const and uses only the stack; call it from any number of
// threads on disjoint (or overlapping) output ranges. The library starts no threads: split the
// vertex range into chunks (multiples of 16 are best) in your own job system.
// Nothing here throws; failures return prt::Status. Compiles as C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "prt/core/kernel_path.h"
#include "prt/core/status.h"
#include "prt/formats/transfer_data.h"
#include "prt/lighting/sh_lighting.h"

namespace prt {

class Relighter {
 public:
  Relighter();  // empty: 0 vertices
  Relighter(Relighter&&) noexcept;
  Relighter& operator=(Relighter&&) noexcept;
  ~Relighter();

  // Copies the coefficients of `data` into the blocked layout, at data.storage precision
  // (binary16 storage rounds them; a value that overflows binary16 is an error).
  static Result<Relighter> create(const TransferData& data);
  // Same, at an explicit precision.
  static Result<Relighter> create(const TransferData& data, Precision storage);
  // Straight from the bytes of a coefficient file (fully validated; the blocked coefficients
  // are copied as they are, without conversion).
  static Result<Relighter> from_file_bytes(const void* bytes, std::size_t size,
                                           const std::string& name_for_errors);
  static Result<Relighter> from_file(const std::string& path);

  std::size_t vertex_count() const;
  int order() const;
  int channels() const;
  Precision storage() const;

  // Exit radiance of vertices [first_vertex, first_vertex + count): 3 floats per vertex (RGB)
  // into out_rgb[0 .. 3·count). Errors: range beyond vertex_count(), null out_rgb with
  // count > 0.
  Status shade(const ShLighting& light, std::size_t first_vertex, std::size_t count,
               float* out_rgb) const;

  // Same, choosing the implementation (for tests and benchmarks).
  Status shade_using(KernelPath path, const ShLighting& light, std::size_t first_vertex,
                     std::size_t count, float* out_rgb) const;

  // Display colours: radiance × 2^exposure_ev, clamped to [0, 1] (NaN → 0), sRGB-encoded
  // (IEC 61966-2-1: 12.92·x for x ≤ 0.0031308, else 1.055·x^(1/2.4) − 0.055), rounded to
  // nearest 8-bit value; alpha = 255. 4 bytes per vertex into out_rgba[0 .. 4·count).
  Status shade_rgba8(const ShLighting& light, std::size_t first_vertex, std::size_t count,
                     float exposure_ev, uint8_t* out_rgba) const;

  // Whether KernelPath::Auto picks the AVX2 path on this CPU.
  static bool avx2_path_available();

  struct Impl;  // implementation detail (declared here so the kernel can see it)

 private:
  std::unique_ptr<Impl> impl_;
};

// The slow reference: exit radiance of vertex v straight from the vertex-major floats of
// `data`, accumulated in double, same order rule as the kernel. Writes 3 doubles.
// Errors: v out of range, inconsistent `data`.
Status shade_reference(const TransferData& data, const ShLighting& light, std::size_t v,
                       double out_rgb[3]);

// sRGB encoding of one linear value in [0, 1] (clamped; NaN → 0) to 8 bits, as used by
// shade_rgba8.
uint8_t encode_srgb8(float linear);

}  // namespace prt
