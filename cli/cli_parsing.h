// cli/cli_parsing.h — parsing of option values shared by the subcommands.
//
// Every error throws UsageError with one line "OPTION TEXT: problem" (command_registry.h).
// Angles are in degrees; --rotate's yaw, pitch, roll are those of
// prt::sh::rotation_from_yaw_pitch_roll (sh/rotation.h, glTF frame, +Y up).
#pragma once

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "sh/env_map.h"

namespace prt::cli {

// "a,b,c": the comma-separated parts of `text`, each a finite number (nothing else in a part).
// Throws "OPTION TEXT: 'part' is not a number".
std::vector<double> parse_number_list(const std::string& option, const std::string& text);

// --rotate "yaw,pitch,roll" in degrees: exactly three finite numbers.
std::array<double, 3> parse_yaw_pitch_roll(const std::string& text);

// --layout: "auto" (guess from the aspect ratio: nullopt) or a layout name of
// prt::sh::parse_layout.
std::optional<prt::sh::EnvLayout> parse_layout_option(const std::string& text);

}  // namespace prt::cli
