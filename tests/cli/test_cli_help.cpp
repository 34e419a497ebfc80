// tests/cli/test_cli_help.cpp — what --help lists is what the parser accepts, and every option a
// message suggests exists.
//   * Every subcommand's --help is read; each option it lists is given (with its default value,
//     the first of its choices, or a value of its type) on an otherwise failing command line
//     (inputs that do not exist), and must not be a parse error. main.cpp ends a parse error,
//     and only a parse error, with "(see prt SUBCOMMAND --help)".
//   * Every "--option" in a string literal of the sources (comments skipped) names an option:
//     in cli/NAME_command.cpp, of that subcommand (or of the one the literal names, "prt bake
//     --auto"); elsewhere, of some subcommand. (Command lines of other programs, rsvg-convert,
//     are skipped.)
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "cli_test_support.h"

using namespace prt::test::cli;

namespace {

struct HelpOption {
  std::string name;   // the long name, or the short one when there is none
  std::string value;  // "" for a flag
  bool required = false;
};

struct Help {
  std::vector<std::string> positionals;
  std::vector<HelpOption> options;
};

// A value the option's type accepts: its default, else its first choice, else by type.
std::string value_for(const std::string& type) {
  const std::size_t equals = type.find('=');
  if (equals != std::string::npos) return type.substr(equals + 1);
  const std::size_t brace = type.find(":{");
  if (brace != std::string::npos)
    return type.substr(brace + 2, type.find_first_of(",}", brace) - brace - 2);
  if (type.rfind("TEXT", 0) == 0) return "x";
  return "1";  // INT, UINT, FLOAT
}

Help parse_help(const std::string& text) {
  Help help;
  std::istringstream lines(text);
  std::string section;
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line[0] != ' ') {
      section = line;
      continue;
    }
    if (line.rfind("  ", 0) != 0 || line.size() < 3 || line[2] == ' ') continue;
    std::istringstream tokens(line.substr(0, line.find("  ", 2)));
    std::string names, type, flag;
    tokens >> names >> type >> flag;
    if (section.rfind("Positionals", 0) == 0) {
      help.positionals.push_back(names);
      continue;
    }
    if (section.rfind("Options", 0) != 0 || names[0] != '-') continue;
    HelpOption option;
    const std::size_t comma = names.find(',');
    option.name = comma == std::string::npos ? names : names.substr(comma + 1);
    const bool typed = !type.empty() && std::isupper(static_cast<unsigned char>(type[0])) &&
                       type.rfind("Excludes", 0) != 0;
    if (typed) option.value = value_for(type);
    option.required = flag == "REQUIRED" || type == "REQUIRED";
    help.options.push_back(option);
  }
  return help;
}

std::vector<std::string> subcommands() {
  const RunResult r = run(prt_cli() + " --help");
  REQUIRE(r.exit_code == 0);
  std::vector<std::string> names;
  std::istringstream lines(r.out);
  bool in_section = false;
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("Subcommands", 0) == 0)
      in_section = true;
    else if (in_section && line.rfind("  ", 0) == 0) {
      std::istringstream tokens(line);
      std::string name;
      tokens >> name;
      names.push_back(name);
    }
  }
  return names;
}

// String literals of a C++ source, comments skipped (enough for this code base's sources).
std::vector<std::string> string_literals(const std::string& code) {
  std::vector<std::string> literals;
  for (std::size_t i = 0; i < code.size(); ++i) {
    if (code.compare(i, 2, "//") == 0) {
      i = code.find('\n', i);
      if (i == std::string::npos) break;
    } else if (code.compare(i, 2, "/*") == 0) {
      i = code.find("*/", i);
      if (i == std::string::npos) break;
      ++i;
    } else if (code[i] == '\'') {
      i += code[i + 1] == '\\' ? 3 : 2;  // 'c' or '\c'
    } else if (code.compare(i, 3, "R\"(") == 0) {
      const std::size_t end = code.find(")\"", i + 3);
      literals.push_back(code.substr(i + 3, end - i - 3));
      i = end + 1;
    } else if (code[i] == '"') {
      std::string literal;
      for (++i; i < code.size() && code[i] != '"'; ++i) {
        if (code[i] == '\\') ++i;
        literal += code[i];
      }
      literals.push_back(literal);
    }
  }
  return literals;
}

std::map<std::string, std::set<std::string>> options_by_subcommand() {
  std::map<std::string, std::set<std::string>> all;
  for (const std::string& sub : subcommands()) {
    const RunResult r = run(prt_cli() + " " + sub + " --help");
    REQUIRE(r.exit_code == 0);
    for (const HelpOption& option : parse_help(r.out).options) all[sub].insert(option.name);
  }
  return all;
}

}  // namespace

TEST_CASE("cli help: every option a subcommand's --help lists is accepted by its parser") {
  const fs::path dir = scratch("help_options");
  const std::vector<std::string> subs = subcommands();
  CHECK(subs.size() == 11u);  // demo env make-sky make-scene bake merge compress info relight
                              // report radiosity
  int checked = 0;
  for (const std::string& sub : subs) {
    const RunResult help = run(prt_cli() + " " + sub + " --help");
    REQUIRE(help.exit_code == 0);
    const Help h = parse_help(help.out);
    CHECK_FALSE(h.options.empty());
    std::string base = prt_cli() + " " + sub;
    for (const std::string& positional : h.positionals)
      base.append(" ").append(dir.string()).append("/missing_").append(positional);
    // demo would run for real on the bundled data: point it at a data folder that is not there.
    if (sub == "demo") base += " --data " + dir.string() + "/missing_data";
    for (const HelpOption& option : h.options) {
      if (option.name == "--help" || (sub == "demo" && option.name == "--data")) continue;
      std::string command = base;
      for (const HelpOption& other : h.options)
        if (other.required && other.name != option.name)
          command += " " + other.name + " " + dir.string() + "/out.x";
      command += " " + option.name + (option.value.empty() ? "" : " '" + option.value + "'");
      INFO(command);
      const RunResult r = run(command);
      INFO(r.err);
      CHECK(r.exit_code <= 2);
      CHECK(r.err.find("--help)") == std::string::npos);  // not a parse error
      ++checked;
    }
  }
  CHECK(checked > 60);  // every subcommand's options were tried (about 70)
  CHECK(files_in(dir).empty());
}

// A subcommand that runs worker threads does large work, so it also takes --memory-limit
// (cli/option_rules.h): a new threaded command that leaves it out fails here.
TEST_CASE("cli help: every subcommand with --threads also takes --memory-limit") {
  int threaded = 0;
  for (const auto& [sub, names] : options_by_subcommand()) {
    if (names.count("--threads") == 0) continue;
    ++threaded;
    INFO(sub);
    CHECK(names.count("--memory-limit") == 1);
  }
  CHECK(threaded >= 3);  // bake, compress, radiosity
}

TEST_CASE("cli help: every option that a message suggests exists") {
  const std::map<std::string, std::set<std::string>> options = options_by_subcommand();
  std::set<std::string> any = {"--help", "--version"};
  for (const auto& [sub, names] : options) any.insert(names.begin(), names.end());
  const fs::path root = PRT_SOURCE_DIR;
  const std::regex option_pattern("--[a-z][a-z0-9-]*");
  const std::regex named_pattern("prt ([a-z-]+)((?: --?[a-z][a-z0-9-]*(?: [^ -][^ ]*)?)+)");
  int literals_checked = 0;
  for (const char* folder :
       {"cli", "relight/src", "scene/src", "bake/src", "report/src", "prt/src", "sh/src"}) {
    for (const auto& entry : fs::recursive_directory_iterator(root / folder)) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".h") continue;
      const std::string stem = entry.path().stem().string();
      const std::string file_sub =
          std::string(folder) == "cli" && stem.size() > 8 &&
                  stem.substr(stem.size() - 8) == "_command"
              ? std::regex_replace(stem.substr(0, stem.size() - 8), std::regex("_"), "-")
              : "";
      for (const std::string& literal : string_literals(slurp(entry.path()))) {
        if (literal.find("rsvg-convert") != std::string::npos) continue;  // another program's
        // Options after "prt NAME" belong to NAME.
        std::string rest = literal;
        for (std::smatch m; std::regex_search(rest, m, named_pattern); rest = m.suffix()) {
          const std::string named = m[1];
          const std::string tail = m[2];
          for (std::sregex_iterator it(tail.begin(), tail.end(), option_pattern), end; it != end;
               ++it) {
            INFO(entry.path().string() << ": \"" << literal << "\"");
            REQUIRE(options.count(named) == 1);
            CHECK(options.at(named).count(it->str()) == 1);
            ++literals_checked;
          }
        }
        for (std::sregex_iterator it(rest.begin(), rest.end(), option_pattern), end; it != end;
             ++it) {
          INFO(entry.path().string() << ": \"" << literal << "\"");
          if (!file_sub.empty() && options.count(file_sub))
            CHECK(options.at(file_sub).count(it->str()) == 1);
          else
            CHECK(any.count(it->str()) == 1);
          ++literals_checked;
        }
      }
    }
  }
  CHECK(literals_checked > 100);  // the scan saw the messages (about 200 mentions)
}
