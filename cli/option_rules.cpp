// Refusing options that do not apply (option_rules.h).
#include "option_rules.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "command_registry.h"

namespace prt::cli {

void refuse_unless(const CLI::App& cmd, bool applies, std::initializer_list<const char*> options,
                   const std::string& when) {
  if (applies) return;
  for (const char* option : options)
    if (cmd.count(option) > 0) throw UsageError(std::string(option) + " applies only to " + when);
}

void check_exposure(double ev, const std::string& text) {
  if (!std::isfinite(ev) || std::fabs(ev) > 64.0)
    throw UsageError("--exposure " + text + ": must be a number of EV in [-64, 64]");
}

}  // namespace prt::cli
