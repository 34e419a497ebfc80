// relight/src/environment_input.cpp — see relight/environment_input.h.
#include "relight/environment_input.h"

#include <cstdio>
#include <stdexcept>

#include "relight/image_io.h"

namespace prt::relight {
namespace {

std::string size_text(const sh::EnvMap& env) {
  return std::to_string(env.width) + "x" + std::to_string(env.height);
}

std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g%%", 100.0 * fraction);
  return text;
}

void check_order(const std::string& path, const sh::EnvMap& env, int order,
                 std::vector<std::string>* warnings) {
  if (order <= 0) return;
  const std::string band = std::to_string(sh::resolved_band(env));
  switch (sh::order_fit(env, order)) {
    case sh::OrderFit::FarTooSmall:
      throw std::runtime_error(path + ": " + size_text(env) + " is far too small for order " +
                               std::to_string(order) +
                               " (it resolves bands up to about l = " + band + ")");
    case sh::OrderFit::Aliasing:
      warnings->push_back(size_text(env) + " resolves bands up to about l = " + band + "; order " +
                          std::to_string(order) + " asks for l = " + std::to_string(order - 1) +
                          " (aliasing)");
      break;
    case sh::OrderFit::Fine:
      break;
  }
}

void check_texels(const std::string& path, const sh::EnvTexelReport& t, bool strict,
                  std::vector<std::string>* warnings) {
  const std::string counts = std::to_string(t.nan_texels) + " NaN, " +
                             std::to_string(t.inf_texels) + " Inf, " +
                             std::to_string(t.negative_texels) + " negative";
  if (strict && t.invalid_texels() + t.negative_texels > 0)
    throw std::runtime_error(path + ": " + std::to_string(t.invalid_texels() + t.negative_texels) +
                             " texels are NaN, Inf or negative (" + counts + "; --strict)");
  if (t.invalid_fraction() > sh::kMaxInvalidSolidAngleFraction)
    throw std::runtime_error(path + ": NaN or Inf over " + percent(t.invalid_fraction()) +
                             " of the sphere (" + std::to_string(t.invalid_texels()) +
                             " texels): not a usable radiance map");
  if (t.invalid_texels() > 0)
    warnings->push_back(std::to_string(t.invalid_texels()) + " texels are NaN or Inf (" +
                        percent(t.invalid_fraction()) + " of the sphere): taken as black");
  if (t.negative_texels > 0)
    warnings->push_back(std::to_string(t.negative_texels) +
                        " texels have a negative channel: clamped to 0");
  if (t.all_black)
    warnings->push_back(
        "the map is black (no texel has positive radiance): "
        "everything it lights is black");
}

}  // namespace

EnvironmentInput read_checked_environment(const std::string& path,
                                          std::optional<sh::EnvLayout> layout,
                                          const EnvironmentUse& use) {
  EnvironmentInput in;
  in.env = read_environment(path, layout, &in.layout_note);
  check_order(path, in.env, use.sh_order, &in.warnings);
  in.texels = sh::screen_env_map(&in.env);
  check_texels(path, in.texels, use.strict, &in.warnings);
  if (use.print_warnings)
    for (const std::string& warning : in.warnings)
      std::fprintf(stderr, "%s: warning: %s\n", path.c_str(), warning.c_str());
  return in;
}

}  // namespace prt::relight
