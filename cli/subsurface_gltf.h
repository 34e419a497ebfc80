// cli/subsurface_gltf.h — dipole coefficients from a glTF material's translucency extensions, for
// `prt bake --subsurface gltf` (docs/SUBSURFACE.md, "From glTF materials"):
//   diffuse colour R_total = the material's base colour (its albedo), clamped to [0.001, 0.999];
//   diffuse mean free path ℓ_d = KHR_materials_volume attenuationDistance × mm per scene unit,
//     the same in every channel;
//   η = `eta` when given (--eta), else KHR_materials_ior's ior (glTF's default 1.5 when absent);
// through prt::subsurface::coefficients_from_color. attenuationColor, thicknessFactor and the
// diffuse-transmission factor and colour mark the material translucent but do not enter the
// coefficients. Refused (CommandError, one line "FILE: material 'M': problem"): no
// attenuationDistance, one that is not finite and > 0, an ior < 1 or not finite.
#pragma once

#include <optional>
#include <string>

#include "prt/subsurface/dipole.h"
#include "scene/scene.h"

namespace prt::cli {

subsurface::DipoleCoefficients gltf_dipole_coefficients(const std::string& file,
                                                        const scene::ScenePrimitive& primitive,
                                                        double mm_per_unit,
                                                        std::optional<double> eta);

}  // namespace prt::cli
