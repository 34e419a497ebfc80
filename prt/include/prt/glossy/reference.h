// prt/glossy/reference.h — the slow reference paths of glossy shading, in double, for tests:
// the transferred and exit radiance of one vertex straight from the uncompressed matrices
// (prt/glossy/transfer.h) or from the CPCA form (prt/glossy/cpca_transfer.h), with the
// channel and order conventions of prt/glossy/kernel.h. Nothing here throws. C++17.
#pragma once

#include <cstddef>

#include "prt/core/status.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/transfer.h"
#include "prt/lighting/sh_lighting.h"

namespace prt {

// The slow references, in double, straight from the vertex-major floats:
// L' of vertex v (3·n² doubles, channel-major) and its exit radiance with b (b_channels·n²
// floats for this vertex). Errors: v out of range, inconsistent data, bad b_channels.
Status glossy_transfer_reference(const GlossyTransferData& data, const ShLighting& light,
                                 std::size_t v, double* out);
Status glossy_shade_reference(const GlossyTransferData& data, const ShLighting& light,
                              const float* b_of_v, int b_channels, std::size_t v,
                              double out_rgb[3]);
// The same from the CPCA form (the matrix reconstructed in double, then applied).
Status cpca_transfer_reference(const CpcaTransfer& cpca, const ShLighting& light, std::size_t v,
                               double* out);
Status cpca_shade_reference(const CpcaTransfer& cpca, const ShLighting& light, const float* b_of_v,
                            int b_channels, std::size_t v, double out_rgb[3]);

}  // namespace prt
