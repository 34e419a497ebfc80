// radiosity/form_factor_update.h — bringing a form-factor matrix up to date after some patches
// moved (same patches, same order, some with new corners: an object translated, rotated or
// deformed), recomputing only what the move can have changed.
//
// The moved patches are those whose corners differ; the moved region R is the union of two
// axis-aligned boxes, around their corners before and around them after, each padded by 1e-3
// of the scene's diagonal.
// Per method (docs/RADIOSITY.md, "Resuming"):
//   analytic: entry F_ij is recomputed when i or j moved, or when one of its visibility segments
//     (quadrature point x_k of i to y_k of j) meets R; every other entry has the same
//     point-to-polygon value and an unchanged segment, so it is already right. A row whose
//     stored sum is ≥ 1 − 1e-6 may have been scaled (sampled visibility summing above 1) and is
//     recomputed whole; a patched row that now sums above 1 is scaled as the full computation
//     would scale it.
//   rays: row i is recomputed when i moved or when R reaches the half-space in front of patch i
//     (a ray leaving i can then have met the object before or after); the others' rays cannot
//     reach R. Random streams are per row, so a recomputed row equals the full computation's.
//   hemicube: every row is recomputed (each entry combines the hemicubes of both its patches,
//     radiosity/hemicube.h, and the stored matrix no longer holds them apart).
// Either way the result equals compute_form_factors on the new patches bit for bit (rows and
// entries are computed by the same code; test_radiosity checks it).
#pragma once

#include <cstddef>
#include <vector>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

struct FormFactorUpdate {
  std::size_t moved_patches = 0;
  std::size_t rows_recomputed = 0;     // whole rows
  std::size_t entries_recomputed = 0;  // analytic: single entries outside those rows
};

// Updates `f` (computed with `options` for `before`) to the patches `after`; `caster` must be
// built on the scene of `after`. Throws std::invalid_argument when the patch counts differ or f
// does not match them.
FormFactorUpdate update_form_factors(const std::vector<Patch>& before,
                                     const std::vector<Patch>& after,
                                     const scene::RayCaster& caster,
                                     const FormFactorOptions& options, FormFactorMatrix* f);

}  // namespace prt::radiosity
