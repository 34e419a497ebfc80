// Dipole coefficients from a glTF material's translucency extensions (cli/subsurface_gltf.h).
#include "subsurface_gltf.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "command_registry.h"

namespace prt::cli {

subsurface::DipoleCoefficients gltf_dipole_coefficients(const std::string& file,
                                                        const scene::ScenePrimitive& primitive,
                                                        double mm_per_unit,
                                                        std::optional<double> eta) {
  const std::string where = file + ": material '" + primitive.material + "': ";
  const scene::GltfTranslucency& t = *primitive.translucency;
  std::ostringstream value;
  value << t.attenuation_distance;
  if (!t.volume || t.attenuation_distance == 0)
    throw CommandError(where +
                       "no KHR_materials_volume attenuationDistance to take the mean free path "
                       "from: give its coefficients with --subsurface " +
                       primitive.material + "=PRESET");
  if (!(t.attenuation_distance > 0) || !std::isfinite(t.attenuation_distance))
    throw CommandError(where + "KHR_materials_volume attenuationDistance " + value.str() +
                       ": must be finite and > 0");
  if (!eta && !(t.ior >= 1 && std::isfinite(t.ior))) {
    std::ostringstream ior;
    ior << t.ior;
    throw CommandError(where + "KHR_materials_ior ior " + ior.str() + ": must be finite and >= 1");
  }
  subsurface::Rgb color{}, mfp{};
  for (int c = 0; c < 3; ++c) {
    color[c] = std::clamp(static_cast<double>(primitive.albedo[c]), 0.001, 0.999);
    mfp[c] = t.attenuation_distance * mm_per_unit;
  }
  Result<subsurface::DipoleCoefficients> r =
      subsurface::coefficients_from_color(color, mfp, eta.value_or(t.ior));
  if (!r) throw CommandError(where + r.status().message());
  return *r;
}

}  // namespace prt::cli
