// cli/option_rules.h — "option X applies only with Y", one rule for every command: an option
// given on the command line that the run would ignore is refused by name (UsageError, exit 2),
// never silently dropped (README "Bad input"). Presence-only rules (X needs option Y) use
// CLI11's ->needs() / ->excludes() where the options are declared; these helpers cover rules
// that depend on a value (`--form-factors rays`) or on the kind of an input file.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>

namespace CLI {
class App;
}

namespace prt::cli {

// Throws UsageError "OPTION applies only to WHEN" for the first of `options` given on `cmd`'s
// command line when `applies` is false.
void refuse_unless(const CLI::App& cmd, bool applies, std::initializer_list<const char*> options,
                   const std::string& when);

// A finite exposure in EV within [-64, 64] (the range prt relight accepts); `text` is the value
// as typed, for the message "--exposure TEXT: must be a number of EV in [-64, 64]".
void check_exposure(double ev, const std::string& text);

// `--memory-limit SIZE`, the one declaration of every command that bakes, solves or compresses:
// the memory its large buffers may take (prt/core/memory_budget.h; "8G", "512M", "1.5GB", bytes).
// A value parse_memory_size refuses is a UsageError (exit 2, one line). `*bytes` keeps 0 when
// the option is not given; memory_limit_or_default turns that into the default.
void add_memory_limit_option(CLI::App& cmd, uint64_t* bytes);
// `given`, or prt::MemoryBudget::default_limit() when it is 0: what goes in the options'
// memory_limit.
uint64_t memory_limit_or_default(uint64_t given);

}  // namespace prt::cli
