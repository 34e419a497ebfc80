// bake/cpca/relit_metric.h — a metric for CPCA (bake/cpca/compressor.h, CpcaOptions::row_metric)
// under which the compressor's error tracks the RELIT error of the vertices' own BRDFs, not the
// matrix error.
//
// A vertex's exit radiance is e_c = Σ_i b_c,i(ω_o) Σ_j M_c,ij L_c,j (prt/glossy/transfer.h,
// prt/glossy/brdf_projection.h). An error δM changes it by δe_c = b_cᵀ δM_c L_c. Averaged over view
// directions uniform in solid angle on the upper hemisphere and over lightings whose SH
// coefficients are uncorrelated with one variance σ² (a white prior: nothing is assumed of the
// lighting's spectrum, since a sun or a studio lamp is as broad-band as SH can be),
//     E[δe_c²] = σ² tr(δM_cᵀ C_c δM_c),   C_c = E_ωo[b_c(ω_o) b_c(ω_o)ᵀ]   (n² × n²),
// exactly. So CpcaOptions::row_metric = C makes the compressor's squared error proportional to
// the expected squared relit error. For a glossy lobe C falls with the band (the lobe low-pass
// filters the transferred radiance), for a Lambert surface it vanishes beyond the clamped
// cosine's bands, and the correlations between rows (b's coefficients are not independent over
// the views) are kept. The compressor then stops spending vectors on what no view can see.
// Measurements: docs/GLOSSY_CPCA.md.
//
// C is averaged over the file's materials, each weighted by its vertex count, and, for grey
// transfer (channels = 1), over b's three colour channels; it is scaled so that its largest
// eigenvalue is 1 and `floor`² · I is added: rows the file's BRDFs hardly see are still kept
// roughly (for relighting with another material, prt relight --material), and the metric is
// positive definite. Nothing here throws; failures return prt::Status. Compiles as C++17.
#pragma once

#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/transfer.h"

namespace prt {

struct RelitMetricOptions {
  int view_theta = 16;  // views: a midpoint grid, uniform in cos θ_o ∈ (0, 1) ...
  int view_phi = 32;    // ... and in φ_o ∈ [0, 2π)
  double floor = 0.05;  // √ of the added multiple of I (0 < floor ≤ 1)
};

// The metric for CpcaOptions::row_metric: channels · n⁴ values, [(c·n² + i)·n² + k] = G_c,ik.
// Errors: no materials or vertices, a material index out of range, a BRDF the projection
// refuses (BrdfProjection::create's message), options out of range.
Result<std::vector<double>> cpca_relit_metric(const GlossyTransferData& data,
                                              const RelitMetricOptions& options = {});

}  // namespace prt
