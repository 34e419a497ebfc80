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
  cmd.add_option_function<std::string>(
         "--memory-limit",
         [bytes](const std::string& text) { *bytes = prt::parse_memory_size(text); },
         "Memory the large buffers may take (8G, 512M, bytes; default 85% of the available "
         "memory): a run that needs more stops at once, with one line")
      ->check([](const std::string& text) -> std::string {
        try {
          prt::parse_memory_size(text);
          return "";
        } catch (const std::invalid_argument& e) {
          return e.what();
        }
      });
}

uint64_t memory_limit_or_default(uint64_t given) {
  return given != 0 ? given : prt::MemoryBudget::default_limit();
}

}  // namespace prt::cli
