// The `prt` executable: subcommands env, bake, info, relight, report, demo, make-sky, make-scene.
//
// Exit status (README "Exit status"): 0 success (and --help, --version); 1 an input file is
// unreadable or invalid, an output cannot be written, or the run failed; 2 the command line is
// wrong: a parse error of CLI11 (unknown option, missing argument, a value of the wrong type),
// an option value out of range, options that do not apply together, or an output that names
// an input or another output (UsageError). Every failure prints one line on stderr:
// "prt SUBCOMMAND: problem". Every subcommand runs as command_registry.h says: its optional
// check, then CommandFiles::check() of the files it declares, then its work.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "run_record.h"

#ifndef PRT_VERSION
#define PRT_VERSION "unknown"
#endif

namespace prt::cli {
namespace {
std::vector<std::pair<int, CommandRegistration>>& registry() {
  static std::vector<std::pair<int, CommandRegistration>> commands;
  return commands;
}

// "prt" and the subcommand being run, if parsing got that far.
std::string command_name(const CLI::App& app) {
  std::string name = "prt";
  for (const CLI::App* sub : app.get_subcommands()) name += " " + sub->get_name();
  return name;
}

// One line: newlines of multi-line messages become "; ".
std::string one_line(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (std::size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at))
    text.replace(at, 1, "; ");
  return text;
}
}  // namespace

bool register_command(int order, CommandRegistration registration) {
  registry().emplace_back(order, std::move(registration));
  return true;
}

// Adds every registered subcommand to `app`; a registration that does not declare its files
// and its work is a programming error, refused before anything runs.
std::vector<Command> add_commands(CLI::App& app) {
  auto& commands = registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Command> added;
  for (auto& [order, registration] : commands) {
    Command command = registration(app);
    if (command.app == nullptr || !command.files || !command.run)
      throw std::logic_error("a subcommand was registered without its files or its work");
    added.push_back(std::move(command));
  }
  return added;
}

// "prt" and the arguments as given, for the run record.
std::string command_line(int argc, char** argv) {
  std::string line = "prt";
  for (int i = 1; i < argc; ++i) line += std::string(" ") + argv[i];
  return line;
}

// The chosen subcommand: its check, its files checked, then its work, then its run record
// (OUT.run.json, run_record.h) when it declares one.
void run_chosen(const std::vector<Command>& commands, const std::string& line) {
  for (const Command& command : commands) {
    if (command.app->count() == 0) continue;
    const auto start = std::chrono::steady_clock::now();
    if (command.check) command.check();
    const CommandFiles files = command.files();
    files.check();
    command.run();
    if (files.run_record_output().empty()) continue;
    const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
    write_run_record(files.run_record_output(), line, PRT_VERSION, seconds.count());
  }
}
}  // namespace prt::cli

int main(int argc, char** argv) {
  using prt::cli::command_name;
  using prt::cli::one_line;
  CLI::App app{"prt — precomputed radiance transfer: bake, relight, report"};
  app.set_version_flag("--version", std::string("prt ") + PRT_VERSION);
  app.require_subcommand(1);
  const std::vector<prt::cli::Command> commands = prt::cli::add_commands(app);

  try {
    app.parse(argc, argv);
    prt::cli::run_chosen(commands, prt::cli::command_line(argc, argv));
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    const std::string name = command_name(app);
    std::fprintf(stderr, "%s: %s (see %s --help)\n", name.c_str(), one_line(e.what()).c_str(),
                 name.c_str());
    return 2;
  } catch (const prt::cli::UsageError& e) {
    std::fprintf(stderr, "%s: %s\n", command_name(app).c_str(), one_line(e.what()).c_str());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", command_name(app).c_str(), one_line(e.what()).c_str());
    return 1;
  }
  return 0;
}
