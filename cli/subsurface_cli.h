// cli/subsurface_cli.h — the subsurface options of `prt bake` (bake/subsurface/subsurface_baker.h),
// kept apart so the bake command changes by a few lines only.
//   prt bake SCENE -o OUT.prt --subsurface PRESET|custom|gltf [--transfer shadowed|interreflected]
//            [--sigma-a r,g,b --sigma-s r,g,b --eta E | --subsurface-color r,g,b
//             --mean-free-path r,g,b [--eta E]]
//            [--subsurface-scale MM_PER_UNIT] [--subsurface-epsilon E] [--subsurface-reference]
// --subsurface VALUE makes every primitive translucent; --subsurface MATERIAL=VALUE (repeatable,
// the NAME=VALUE rule of scene/material_assignment.h) only those, the others stay opaque.
// `gltf` takes each material's coefficients from its KHR_materials_volume /
// KHR_materials_diffuse_transmission (cli/subsurface_gltf.h); materials without them stay opaque
// unless another --subsurface names them (later values win where they overlap).
// `custom` takes the coefficients from --sigma-a/--sigma-s/--eta (mm⁻¹) or from
// --subsurface-color/--mean-free-path (mm). Refused by name (UsageError, exit 2): an unknown
// preset, σ ≤ 0 or NaN, η < 1, a colour outside (0, 1), the coefficient options without
// `custom`, both ways of giving them, --subsurface with --glossy, --basis haar or --auto.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "bake/subsurface/subsurface_baker.h"
#include "bake/transfer_baker.h"
#include "scene/scene.h"

namespace prt::cli {

struct SubsurfaceArguments {
  std::vector<std::string> subsurface;  // PRESET|custom|gltf, or MATERIAL=PRESET|custom|gltf
  std::string sigma_a, sigma_s, color, mean_free_path;
  std::optional<double> eta, scale, epsilon;
  bool reference = false;

  bool given() const { return !subsurface.empty(); }
};

void add_subsurface_options(CLI::App* command, SubsurfaceArguments* args);

// The command line's refusals, before any file is read (`other`: "--glossy", "--basis haar" or
// "--auto" when one of them is given, else empty).
void check_subsurface_usage(const SubsurfaceArguments& args, const CLI::App& cmd,
                            const std::string& other);

// The subsurface options the arguments give for `scene` (materials resolved against its
// primitives and glTF extensions). Throws UsageError, CommandError.
bake::SubsurfaceBakeOptions subsurface_bake_options(const scene::Scene& scene,
                                                    const SubsurfaceArguments& args);

// Bakes, writes `output` and reports; phases to the run record. Throws UsageError (a material
// name the scene does not have), CommandError, BakeError.
void run_subsurface_bake(const scene::Scene& scene, const std::string& output,
                         const bake::BakeOptions& options, const SubsurfaceArguments& args,
                         bool quiet);

}  // namespace prt::cli
