// cli/view/glossy_payload.h — what `prt view` serves for a GLOSSY file (a .prtg of per-vertex
// transfer matrices, or a .prtq of their CPCA compression; prt/glossy/transfer.h,
// prt/glossy/cpca_transfer.h), so that the page shades every vertex toward the camera as
// prt::GlossyRelighter does: exit_c = b_c(ωo) · (M_c' · L_c), ωo the direction to the eye in the
// vertex's tangent frame (docs/VIEWER.md, "Glossy files"; docs/GLOSSY.md, "Shading").
//
// The manifest, mesh.bin and environment.bin are those of view_payload.h (kind "glossy" or
// "glossy-cpca", albedo folded: the BRDF holds it); the window and exposure are chosen as
// `prt relight` chooses them for a glossy file (on the vertices shaded toward the automatic
// camera's eye). The bulk, raw little-endian, streamed as is:
//   transfer.bin  .prtg: float16 RGBA texels, vertex v owns texels v·P … v·P+P−1,
//                 P = ⌈channels·n⁴/4⌉, the matrix entries in the file's order (c·n² + i)·n² + j,
//                 zero-padded, a whole number of vertices a row (as the SH transfer texture).
//                 .prtq: float32, cluster q's mean then its K principal vectors, each of
//                 D = channels·n⁴ values in the same order: ((q·(K+1) + k)·D + d), k = 0 the mean.
//   glossy.bin    float32 sections (offsets in the manifest's "glossy" object):
//                 "vertex"  RGBA texels, G a vertex (a whole number of vertices a row): the
//                           orthonormal frame rows t, b, n (Gram–Schmidt as the relighter does)
//                           in texels 0–2 (xyz; w of texel 0 the material index), then for CPCA
//                           the cluster id and the K weights, four a texel (id first).
//                 "brdf"    RGBA texels, n² a node, whole nodes a row: texel i of node k = (b_R,i, b_G,i, b_B,i, 0)
//                           of one sampled b(ωo); each material's nodes are listed in the
//                           manifest: "table" (isotropic: b(θo, 0) at θo = t/(T−1)·90°, linear
//                           in θo, then rotated about +z by φo — the library's table exactly;
//                           the horizon node extrapolated as the library does) or "matrix"
//                           (anisotropic: b_c,i(ωo) = Σ_e B_c,i,e y_e(ωo) over the view-side
//                           SH of order m_v with l + m even, node e = l(l+1)/2 + (m + l)/2;
//                           B recovered exactly from the library's b by a product rule).
// Throws std::runtime_error "PATH: problem" for an unreadable or mismatched input.
#pragma once

#include <string>

#include "view_payload.h"

namespace prt::cli::view {

// True when `path` begins with the magic of a glossy transfer file or a CPCA file.
bool is_glossy_view_file(const std::string& path);

ViewPayload build_glossy_view_payload(const ViewInputs& inputs);

}  // namespace prt::cli::view
