// cli/command_registry.h — how subcommands of the `prt` executable plug in.
//
// Each subcommand lives in its own cli/<name>_command.cpp and registers itself with
//   PRT_REGISTER_COMMAND(order, function)
// where function(CLI::App& app) adds a subcommand and its callback. Callbacks report
// failure by throwing; main prints "prt <subcommand>: <message>" on one line and exits with
// status 2 for a UsageError (the command line is wrong: a bad option value, options that do not
// apply together, an output that names an input) and 1 for anything else (CommandError or any
// std::exception: a bad input file, an unwritable output, a run-time failure).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

namespace CLI {
class App;
}

namespace prt::cli {

struct CommandError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// The command line itself is wrong (exit status 2).
struct UsageError : CommandError {
  using CommandError::CommandError;
};

using CommandRegistration = std::function<void(CLI::App&)>;

// Adds a registration; `order` sorts subcommands in --help.
bool register_command(int order, CommandRegistration registration);

}  // namespace prt::cli

#define PRT_CONCAT_INNER(a, b) a##b
#define PRT_CONCAT(a, b) PRT_CONCAT_INNER(a, b)
#define PRT_REGISTER_COMMAND(order, fn) \
  static const bool PRT_CONCAT(prt_command_registered_, __LINE__) = ::prt::cli::register_command(order, fn)
