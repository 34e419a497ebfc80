// relight/environment_input.h — an environment map read the way every command reads one
// (prt env, relight, bake --auto --env, report, demo): decoded (relight/image_io.h), its texels
// screened and its resolution checked against the SH order it is projected to, by the one
// policy of sh/env_check.h (docs/CONVENTIONS.md, "Environment maps that are not clean").
//
// Refused (std::runtime_error, one line "PATH: problem"): what read_environment refuses; NaN or
// Inf over more than half the sphere; an order far beyond what the map resolves; with `strict`,
// any NaN, Inf or negative texel.
// Warned (one line each, "PATH: warning: ...", on stderr when print_warnings, and returned):
// aliasing (the order's top bands are finer than the map resolves), NaN/Inf texels over less
// than half the sphere (taken as black), negative channels (clamped to 0), a map that is black
// after screening (every image it lights is black).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sh/env_check.h"
#include "sh/env_map.h"

namespace prt::relight {

struct EnvironmentUse {
  int sh_order = 0;  // the SH order the map is projected to; 0: none (Haar wavelets, --auto)
  bool strict = false;
  bool print_warnings = true;
};

struct EnvironmentInput {
  sh::EnvMap env;  // screened: every texel finite and non-negative
  std::string layout_note;
  sh::EnvTexelReport texels;
  std::vector<std::string> warnings;  // the problems, without "PATH: warning: "
};

EnvironmentInput read_checked_environment(const std::string& path,
                                          std::optional<sh::EnvLayout> layout,
                                          const EnvironmentUse& use = {});

}  // namespace prt::relight
