// Option-value parsing shared by the subcommands (cli_parsing.h).
#include "cli_parsing.h"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include "command_registry.h"

namespace prt::cli {

std::vector<double> parse_number_list(const std::string& option, const std::string& text) {
  std::vector<double> values;
  std::istringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) {
    try {
      std::size_t used = 0;
      const double v = std::stod(part, &used);
      if (used != part.size() || !std::isfinite(v)) throw std::invalid_argument(part);
      values.push_back(v);
    } catch (const std::exception&) {
      throw UsageError(option + " " + text + ": '" + part + "' is not a number");
    }
  }
  return values;
}

std::array<double, 3> parse_yaw_pitch_roll(const std::string& text) {
  const std::vector<double> v = parse_number_list("--rotate", text);
  if (v.size() != 3) throw UsageError("--rotate " + text + ": expected yaw,pitch,roll in degrees");
  return {v[0], v[1], v[2]};
}

std::optional<prt::sh::EnvLayout> parse_layout_option(const std::string& text) {
  if (text == "auto") return std::nullopt;
  prt::sh::EnvLayout layout;
  if (!prt::sh::parse_layout(text, &layout))
    throw UsageError("--layout " + text + ": expected auto|latlong|angular|cross|faces");
  return layout;
}

}  // namespace prt::cli
