// cli/material_option.h — the repeatable `--material NAME=MODEL[:KEY=VALUE,...]` option shared by
// the commands that load a scene (prt bake, prt info SCENE, prt report --glossy): its registration
// and its parsing (scene/material_override.h for the syntax). Parse errors throw UsageError with
// one line "--material TEXT: problem"; the overrides are applied by load_scene (LoadOptions).
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "scene/material_override.h"

namespace prt::cli {

void add_material_option(CLI::App& command, std::vector<std::string>& values);

std::vector<scene::MaterialOverride> parse_material_options(const std::vector<std::string>& values);

}  // namespace prt::cli
