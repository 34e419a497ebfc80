// prt/emitters/glossy_emitter_radiance.h — a scene's emitters as seen by glossy vertices: per
// vertex and per emitting material, the SH coefficients of the radiance ARRIVING at the vertex in
// its local tangent frame (the frame of prt/glossy/transfer.h), when that emitter alone emits unit
// white radiance; and the exit radiance they give toward an eye point under any emitter colours.
//
// Radiance transport is linear in the emission, channel by channel, so under emissions c_e
// (linear RGB) the incident radiance at vertex v in its local frame is
//     L'_v,c,i = Σ_e c_e,c · G_e,v,c,i,          i < n², n = order,
// and the exit radiance toward ω_o (local) is Σ_i b_c,i(ω_o) · L'_v,c,i with b the vertex's
// BRDF projection (prt/glossy/brdf_projection.h), exactly as for the environment's L' = M·L.
// G is the upper-hemisphere projection ∫_{H+} y_i(ω_local) R_e(hit(ω)) dω of the radiance R_e a
// ray leaving the vertex meets (the emitter's own unit emission, and whatever the scene reflects
// of it); bake/glossy_emitter_gather.h computes it from a radiosity solution (.prte,
// prt/emitters/emitter_responses.h). G is RGB because reflected light takes the albedo's colour.
// The emitters' own surfaces add their emission: a vertex of emitter e seen from in front of its
// tangent plane adds c_e (uniform, one-sided emission, as in radiosity) to what it reflects.
// Units: G per unit emitted radiance (dimensionless); exit radiance in the units of the colours.
//
// Nothing here throws or starts threads; errors are one-line prt::Status messages. C++17.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/emitters/emitter_responses.h"
#include "prt/glossy/brdf_projection.h"
#include "prt/glossy/transfer.h"

namespace prt {

inline constexpr uint32_t kNotAnEmitter = 0xffffffffu;

struct GlossyEmitterRadiance {
  uint32_t order = 0;  // SH order n of G (the glossy file's)
  uint64_t vertex_count = 0;
  std::vector<EmitterInfo> emitters;  // E: names and stored emissions (the .prte's)
  // G_e,v,c,i at coefficients[((v · E + e) · 3 + c) · n² + i]: vertex-major, so one vertex's
  // emitters are contiguous.
  std::vector<float> coefficients;
  // Per vertex: the emitter whose surface it lies on (index into `emitters`), or kNotAnEmitter.
  std::vector<uint32_t> emitter_of_vertex;

  std::size_t emitter_count() const { return emitters.size(); }
  std::size_t coefficient_count() const { return std::size_t(order) * order; }
};

// Checks the sizes (order 1..kMaxBrdfProjectionOrder, E ≥ 1, coefficients = V·E·3·n²,
// emitter_of_vertex = V entries, each < E or kNotAnEmitter) and that every value is finite.
Status validate_glossy_emitter_radiance(const GlossyEmitterRadiance& data);

// L'_v,c,i = Σ_e colors_rgb[3e + c] · G_e,v,c,i for vertex v: 3·n² floats (channel-major) into
// out, accumulated in double. colors_rgb: 3·E values (emitter_colors()), finite and ≥ 0.
Status combine_glossy_emitters(const GlossyEmitterRadiance& data,
                               const std::vector<float>& colors_rgb, std::size_t v, float* out);

// The local frame of vertex v of `geometry` as GlossyRelighter builds it: Gram–Schmidt of the
// tangent against the normal, b = w·n × t; rows t, b, n (row-major) into rows[9], so rows·d is d
// in the local frame. Errors: v out of range, a degenerate or non-finite frame.
Status glossy_vertex_frame(const GlossyTransferData& geometry, std::size_t v, double rows[9]);

// Adds the emitters' exit radiance (reflected, plus the emission of emitter vertices) toward
// eye_xyz (scene frame) of vertices [first, first + count) to out_rgb[0 .. 3·count). `geometry`
// gives the positions, normals, tangents and material_of_vertex (its matrices are not read and may
// be empty), `projections` one BrdfProjection per material of geometry at order data.order
// (GlossyRelighter::projections()). The frame is glossy_vertex_frame's; a view from below the
// tangent plane (or at the vertex) adds nothing, as GlossyRelighter::shade.
Status shade_glossy_emitters(const GlossyEmitterRadiance& data,
                             const std::vector<float>& colors_rgb,
                             const GlossyTransferData& geometry,
                             const std::vector<BrdfProjection>& projections,
                             const double eye_xyz[3], std::size_t first, std::size_t count,
                             float* out_rgb);

}  // namespace prt
