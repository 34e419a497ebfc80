// The `prt` executable: subcommands env, bake, info, relight, report, demo.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"

namespace prt::cli {
namespace {
std::vector<std::pair<int, CommandRegistration>>& registry() {
  static std::vector<std::pair<int, CommandRegistration>> commands;
  return commands;
}
}  // namespace

bool register_command(int order, CommandRegistration registration) {
  registry().emplace_back(order, std::move(registration));
  return true;
}
}  // namespace prt::cli

int main(int argc, char** argv) {
  CLI::App app{"prt — precomputed radiance transfer: bake, relight, report"};
  app.require_subcommand(1);
  auto& commands = prt::cli::registry();
  std::stable_sort(commands.begin(), commands.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (auto& [order, registration] : commands) registration(app);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::string name = "prt";
    for (const CLI::App* sub : app.get_subcommands()) name += " " + sub->get_name();
    std::fprintf(stderr, "%s: %s\n", name.c_str(), e.what());
    return 1;
  }
  return 0;
}
