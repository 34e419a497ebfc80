// cli/command_registry.h — how subcommands of the `prt` executable plug in.
//
// Each subcommand lives in its own cli/<name>_command.cpp and registers itself with
//   PRT_REGISTER_COMMAND(order, function)
// where function(CLI::App& app) adds a subcommand and returns its Command: the files the run
// reads and writes (`files`, computed from the parsed arguments) and the work (`run`). A Command
// without both is refused when `prt` starts. main runs CommandFiles::check() on `files()`
// (output_safety.h: required inputs exist, no output is an input or another output, stdout is
// not an input, each declared output file can be written) before `run`, so no command can skip
// it; a command declares every file it writes there, and tests/cli/test_cli_outputs.cpp gives
// every registered subcommand's outputs one path to prove it. When `files()` declares a run
// record (CommandFiles::add_run_record), main writes OUT.run.json after `run` succeeds: the
// run's times, threads and host, which no output file holds (run_record.h).
//
// Callbacks report failure by throwing; main prints "prt <subcommand>: <message>" on one line
// and exits with status 2 for a UsageError (the command line is wrong: a bad option value,
// options that do not apply together, an output that names an input) and 1 for anything else
// (CommandError or any std::exception: a bad input file, an unwritable output, a run-time
// failure).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>

#include "output_safety.h"

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

// A subcommand as main runs it: `files()` is checked, then `run()`. `check` (optional) runs
// first: refusals of the command line that the file list depends on (a count of turntable
// frames, a mode) or that should come before a file is looked at.
struct Command {
  CLI::App* app = nullptr;
  std::function<void()> check;
  std::function<CommandFiles()> files;
  std::function<void()> run;
};

using CommandRegistration = std::function<Command(CLI::App&)>;

// Adds a registration; `order` sorts subcommands in --help.
bool register_command(int order, CommandRegistration registration);

}  // namespace prt::cli

#define PRT_CONCAT_INNER(a, b) a##b
#define PRT_CONCAT(a, b) PRT_CONCAT_INNER(a, b)
#define PRT_REGISTER_COMMAND(order, fn)                             \
  static const bool PRT_CONCAT(prt_command_registered_, __LINE__) = \
      ::prt::cli::register_command(order, fn)
