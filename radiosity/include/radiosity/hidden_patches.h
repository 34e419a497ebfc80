// radiosity/hidden_patches.h — the parts of patches that nothing can see: a floor that runs on
// under a block resting on it, a wall behind a cupboard standing against it. Light never reaches
// them, so their radiance is 0, and a patch that is partly hidden has an area average of about
// (visible fraction) × the radiance of its visible part. Averaged to vertices as they are, such
// patches darken every vertex around a contact line, and the renderer spreads that darkness
// over the visible floor beside the block (the D0 discontinuity of Lischinski, Tampieri &
// Greenberg, "Discontinuity meshing for accurate radiosity", IEEE CG&A 12(6), 1992, left
// unresolved by a mesh that does not follow it). vertex_radiance (patches.h) therefore weights each
// patch by its visible area and takes the radiance of its visible part; the solve itself keeps
// every patch (hidden ones absorb and emit nothing, so the energy account is unchanged).
//
// A point x of a patch is *enclosed* when every one of kEnclosureProbes fixed directions of the
// hemisphere in front of it (the normal, and rings of six at 30°, 55°, 75° and 86° from it) meets
// a back face — x lies inside closed geometry — and no emitting patch's centroid is in view of
// it (the front of an emitter met first along the segment): inside a room whose walls face
// outward every probe meets a back face too, yet its lamps light it. A point from which one probe
// escapes or meets a front face, or that sees an emitter, is visible.
//
// The visible fraction of a patch is taken at the points where its form factors sample the
// receiver's visibility, so that radiance / fraction is the radiance of the visible part as the
// solve estimated it: the quadrature points (1 or 3, FormFactorOptions::quadrature_points) for
// analytic form factors and for ray form factors whose emitters' rows are reciprocal (direct
// light, the larger part, is collected at those points); otherwise (rays, hemicube: the hit or
// rasterised area) the centroids of the 16 congruent triangles of the patch's 4 × 4 split.
// Emitting patches count as fully visible (their emission is exact wherever they are).
#pragma once

#include <vector>

#include <glm/glm.hpp>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"

namespace prt::radiosity {

constexpr int kEnclosureProbes = 25;

// Whether the point x of triangle `patch` (unit front normal n) is enclosed (see above);
// `patches` are the scene's (their emitters are looked for).
bool point_enclosed(const scene::RayCaster& caster, uint32_t patch, const glm::dvec3& x,
                    const glm::dvec3& n, const std::vector<Patch>& patches);

// The visible fraction of every patch (see above), in [0, 1]; rows in parallel (TBB),
// deterministic. `caster` must be built on the scene whose triangles are `patches`.
std::vector<double> visible_fractions(const std::vector<Patch>& patches,
                                      const scene::RayCaster& caster,
                                      const FormFactorOptions& options);

// Sets Patch::visible of every patch from visible_fractions.
void mark_hidden_parts(std::vector<Patch>* patches, const scene::RayCaster& caster,
                       const FormFactorOptions& options);

}  // namespace prt::radiosity
