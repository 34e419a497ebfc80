// prt/haar/transfer.h — sparse, quantised per-vertex transfer in the Haar basis.
//
// Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003, Sec. 5: each vertex's transfer vector over the
// 6N² cube texels is wavelet-transformed, truncated to its significant terms and quantised;
// the transport matrix is stored "for each lighting coefficient, the list of vertices that
// have it", so relighting with a sparse lighting vector touches only the kept lists.
//
// Conventions:
//   * Dense input, one vertex: 6N²·channels floats, texel t = face·N² + row·N + col (the
//     CubeMap layout of prt/haar/cube_map.h), channels interleaved: dense[t·channels + c].
//     The value already includes everything but the lighting: texel solid angle ×
//     visibility × max(n·ω, 0) × albedo/π (or more generally the transfer of interreflection),
//     so exit radiance B_v,c = Σ_t T_v,t,c · L_t,c with L the cube map's radiance.
//     channels = 1 (grey transfer: the same T for R, G, B) or 3.
//   * Because the Haar transform is orthonormal, B_v,c = Σ_i T̂_v,i,c · L̂_i,c over wavelet
//     indices i = face·N² + q (prt/haar/transform.h).
//   * Truncation per vertex, by max over channels of |T̂| (transfer already carries solid
//     angle, so no area weight): keep terms with |T̂| ≥ relative_threshold · (the vertex's
//     largest |T̂|), then at most max_terms_per_vertex of them (the largest; equal magnitudes
//     go to the lower index). Exact zeros are never stored.
//   * Quantisation, per vertex: m = the vertex's largest kept |T̂| (over channels),
//     Q = 2^(bits−1) − 1 (127 or 32767), step = m/Q (stored as a float per vertex),
//     stored value round(T̂/step) ∈ [−Q, Q] (signed, symmetric), dequantised q·step.
//     Error bound per coefficient: |T̂ − q·step| ≤ m/(2Q) + m·2⁻²² (the second term covers the
//     float rounding of step and of the product); see haar_quantization_error_bound().
//     HaarQuantization::Float32 stores the kept values exactly (step = 1).
// Compiles as C++17.
// References: [4] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/haar/cube_map.h"

namespace prt {

enum class HaarQuantization : int { Float32 = 32, Bits16 = 16, Bits8 = 8 };

struct HaarTransferOptions {
  HaarQuantization quantization = HaarQuantization::Bits16;
  double relative_threshold = 0.0;   // 0 keeps every non-zero term
  int64_t max_terms_per_vertex = 0;  // 0: no limit
};

// Largest quantised magnitude Q (127, 32767; 0 for Float32).
int haar_quantization_levels(HaarQuantization quantization) noexcept;

// The per-coefficient error bound m/(2Q) + m·2⁻²² for a vertex whose largest kept |T̂| is m
// (0 for Float32).
double haar_quantization_error_bound(HaarQuantization quantization, double max_abs) noexcept;

// One vertex's kept wavelet-domain transfer, before quantisation.
struct SparseVertexTransfer {
  std::vector<uint32_t> index;  // wavelet indices, strictly ascending
  std::vector<float> values;    // channels values per index
  int64_t nonfinite_count = 0;  // NaN/±Inf input values, replaced by 0
};

// Transforms one vertex's dense transfer (6N²·channels floats, layout above) and truncates it
// per the options (quantisation happens in the builder). Errors: invalid size or channels.
Result<SparseVertexTransfer> compress_vertex_transfer(const float* dense, int size, int channels,
                                                      const HaarTransferOptions& options);

// Truncates coefficients that are already in the wavelet domain (6N²·channels floats,
// coeffs[i·channels + c]); the second half of compress_vertex_transfer.
SparseVertexTransfer truncate_vertex_coefficients(const float* coeffs, int size, int channels,
                                                  const HaarTransferOptions& options);

// The relighting structure: for each wavelet index, the vertices that have it.
struct HaarTransfer {
  int size = 0;
  int channels = 1;
  int64_t vertex_count = 0;
  HaarQuantization quantization = HaarQuantization::Bits16;
  // Entries of wavelet index i are [offsets[i], offsets[i+1]); 6N² + 1 offsets.
  std::vector<uint64_t> offsets;
  std::vector<uint32_t> vertices;  // per entry, ascending within each index's list
  // channels values per entry, in the array matching `quantization` (the others stay empty).
  std::vector<float> values_f32;
  std::vector<int16_t> values_i16;
  std::vector<int8_t> values_i8;
  std::vector<float> vertex_step;  // per vertex: dequantised value = stored · vertex_step[v]

  uint64_t entry_count() const { return vertices.size(); }
  // Bytes of the arrays above (offsets, vertices, values, steps).
  uint64_t stored_bytes() const;
  // Bytes of the dense float transfer it replaces: vertex_count · 6N² · channels · 4.
  uint64_t dense_bytes() const;
  // Dequantised value of entry e, channel c (for tests and tools; not the fast path).
  float dequantized_value(uint64_t entry, int channel) const;
};

// Builds a HaarTransfer from vertices added in order 0, 1, 2, … (quantising each as it
// arrives, so only the compact lists are held). Compress vertices in parallel with
// compress_vertex_transfer, then add them here in order.
class HaarTransferBuilder {
 public:
  HaarTransferBuilder(int size, int channels, HaarQuantization quantization);

  // Appends the next vertex. Errors: invalid builder, indices out of range or not ascending,
  // value count ≠ channels · index count.
  Status add_vertex(const SparseVertexTransfer& vertex);

  // The assembled structure; the builder is left empty.
  Result<HaarTransfer> finish();

 private:
  int size_ = 0;
  int channels_ = 1;
  HaarQuantization quantization_;
  int64_t vertex_count_ = 0;
  std::vector<std::vector<uint32_t>> list_vertices_;  // per wavelet index
  std::vector<std::vector<float>> list_f32_;
  std::vector<std::vector<int16_t>> list_i16_;
  std::vector<std::vector<int8_t>> list_i8_;
  std::vector<float> vertex_step_;
};

}  // namespace prt
