// `prt make-sky -o PATH [--width 512 --height 256 --sun-elevation 40 --sun-azimuth 45 ...]`
// Writes the project's analytic HDR sky (relight/sky_model.h) as a lat-long map (.hdr or .exr,
// by extension), atomically. data/sky.hdr is made with the defaults: see data/README.md.
#include <array>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "output_safety.h"
#include "relight/image_io.h"
#include "relight/sky_model.h"
#include "sh/constants.h"
#include "sh/projection.h"

namespace prt::cli {
namespace {

constexpr int kMaxHeight = 8192;  // 16384 x 8192: 1.5 GB of float RGB

struct MakeSkyArguments {
  std::string output;
  int width = 512, height = 256;
  relight::SkyParams params;
};

// Every parameter in range, refused by name.
void check_parameters(const MakeSkyArguments& args) {
  if (args.height < 1 || args.height > kMaxHeight || args.width != 2 * args.height)
    throw UsageError("--width " + std::to_string(args.width) + " --height " +
                     std::to_string(args.height) +
                     ": the sky is a lat-long map: width = 2 x height, height in 1.." +
                     std::to_string(kMaxHeight));
  const relight::SkyParams& p = args.params;
  const auto require = [](bool ok, const char* option, const char* range) {
    if (!ok) throw UsageError(std::string(option) + ": must be " + range);
  };
  require(std::isfinite(p.sun_elevation_deg) && std::fabs(p.sun_elevation_deg) <= 90,
          "--sun-elevation", "in [-90, 90] degrees");
  require(std::isfinite(p.sun_azimuth_deg), "--sun-azimuth", "a finite number of degrees");
  require(p.sun_radius_deg > 0 && p.sun_radius_deg <= 90, "--sun-radius", "in (0, 90] degrees");
  require(std::isfinite(p.sun_radiance) && p.sun_radiance >= 0, "--sun-radiance",
          "a finite radiance >= 0");
  require(std::isfinite(p.glow_radiance) && p.glow_radiance >= 0, "--glow-radiance",
          "a finite radiance >= 0");
  require(std::isfinite(p.glow_width_deg) && p.glow_width_deg >= 0, "--glow-width",
          "a finite number of degrees >= 0");
  require(p.supersampling >= 1 && p.supersampling <= 64, "--supersampling", "in 1..64");
}

void run(const MakeSkyArguments& args) {
  check_parameters(args);
  const relight::SkyParams& p = args.params;
  const prt::sh::EnvMap sky = relight::make_procedural_sky(args.width, args.height, p);
  relight::write_image(args.output, sky.width, sky.height, 3, sky.rgb.data());
  // Mean radiance = L_00·Y_00 (∫L dω = L_00/Y_00 and Y_00² = 1/4π).
  const std::vector<double> L = prt::sh::project(sky, 1);
  const std::array<double, 3> sun = relight::sun_direction(p);
  std::printf(
      "%s: %dx%d lat-long sky, sun at elevation %g deg, azimuth %g deg "
      "(direction %.4f %.4f %.4f), mean radiance %.4g %.4g %.4g\n",
      args.output.c_str(), sky.width, sky.height, p.sun_elevation_deg, p.sun_azimuth_deg, sun[0],
      sun[1], sun[2], L[0] * prt::sh::kY00, L[1] * prt::sh::kY00, L[2] * prt::sh::kY00);
}

Command register_make_sky(CLI::App& app) {
  auto args = std::make_shared<MakeSkyArguments>();
  CLI::App* cmd = app.add_subcommand("make-sky", "Write the analytic HDR sky (lat-long map)");
  cmd->add_option("-o,--output", args->output, "Output image (.hdr or .exr)")->required();
  cmd->add_option("--width", args->width, "Width in texels (2 x height)")->default_str("512");
  cmd->add_option("--height", args->height, "Height in texels")->default_str("256");
  relight::SkyParams& p = args->params;
  cmd->add_option("--sun-elevation", p.sun_elevation_deg, "Sun elevation above the horizon, deg")
      ->default_val(p.sun_elevation_deg);
  cmd->add_option("--sun-azimuth", p.sun_azimuth_deg,
                  "Sun azimuth atan2(z, x) in deg (0 = +X, -90 = -Z, 90 = +Z)")
      ->default_val(p.sun_azimuth_deg);
  cmd->add_option("--sun-radius", p.sun_radius_deg, "Angular radius of the sun disc, deg")
      ->default_val(p.sun_radius_deg);
  cmd->add_option("--sun-radiance", p.sun_radiance, "Radiance of the sun disc")
      ->default_val(p.sun_radiance);
  cmd->add_option("--glow-radiance", p.glow_radiance, "Peak radiance of the glow around the sun")
      ->default_val(p.glow_radiance);
  cmd->add_option("--glow-width", p.glow_width_deg, "Sigma of the glow, deg")
      ->default_val(p.glow_width_deg);
  cmd->add_option("--supersampling", p.supersampling, "Sub-samples per texel along each axis")
      ->default_val(p.supersampling);
  const auto files = [args] {
    CommandFiles f;
    f.add_output_file("-o", args->output, {".hdr", ".exr"}, "an HDR image");
    return f;
  };
  return {cmd, [args] { check_parameters(*args); }, files, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(11, register_make_sky);

}  // namespace prt::cli
