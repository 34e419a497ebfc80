// Shared by the approximations' sources (bake/subsurface_approx/subsurface_approximations.h).
#pragma once

#include "bake/subsurface_approx/subsurface_approximations.h"

namespace prt::bake::detail {

// The output's layout (3 channels, folded, Shadowed, S's vertices and order), every vertex
// Lambert: T_c = ρ_c·S (translucent vertices with ρ = R_total, opaque ones their own albedo).
prt::TransferData lambert_transfer(const SubsurfaceApproximationInputs& in);

// Per channel, each translucent vertex's T_c replaced by its row in `rows` (order² doubles per
// vertex and channel, vertex-major then channel).
void set_translucent_rows(const SubsurfaceApproximationInputs& in, const std::vector<double>& rows,
                          prt::TransferData& out);

prt::TransferData normal_blur_transfer(const SubsurfaceApproximationInputs& in);
prt::TransferData depth_map_transfer(const SubsurfaceApproximationInputs& in);

}  // namespace prt::bake::detail
