// Refusing options that do not apply (option_rules.h).
#include "option_rules.h"

#include <cmath>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "prt/core/memory_budget.h"

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

void add_memory_limit_option(CLI::App& cmd, uint64_t* bytes) {
  // Parsed when CLI11 sets the option; a bad size is the command line's fault (UsageError, which
  // CLI11 lets through to main), like every other value prt checks.
  cmd.add_option_function<std::string>(
      "--memory-limit",
      [bytes](const std::string& text) {
        try {
          *bytes = prt::parse_memory_size(text);
        } catch (const std::invalid_argument& e) {
          throw UsageError(std::string("--memory-limit: ") + e.what());
        }
      },
      "Memory the large buffers may take (8G, 512M, bytes; default 85% of the available "
      "memory): a run that needs more stops at once, with one line");
}

uint64_t memory_limit_or_default(uint64_t given) {
  return given != 0 ? given : prt::MemoryBudget::default_limit();
}

}  // namespace prt::cli
