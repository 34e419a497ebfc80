// cli/emitter_cli.cpp — see emitter_cli.h.
#include "emitter_cli.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "command_registry.h"
#include "prt/emitters/emitter_responses.h"
#include "relight/emitter_relight.h"
#include "scene/material_assignment.h"

namespace prt::cli {
namespace {

std::vector<prt::EmitterColor> parse_colors(const EmitterRelightArguments& a) {
  std::vector<prt::EmitterColor> colors;
  for (const std::string& text : a.emitter) {
    try {
      const scene::MaterialColour value = scene::parse_material_colour("--emitter", text);
      prt::EmitterColor color;
      color.name = value.name;
      for (int c = 0; c < 3; ++c) color.rgb[c] = value.rgb[c];
      colors.push_back(color);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
  }
  return colors;
}

}  // namespace

void add_emitter_relight_options(CLI::App* cmd, EmitterRelightArguments* a) {
  cmd->add_option("--emitter", a->emitter,
                  "NAME=r,g,b or NAME=v: new emission of an emitter of a responses file "
                  "(repeatable; the others keep their stored emission)")
      ->allow_extra_args(false);
  cmd->add_option("--emitters", a->emitters,
                  "Add the emitters of a responses file (prt radiosity --per-emitter) computed "
                  "on the same vertices to the relit radiance");
  cmd->add_option("--max-edge", a->max_edge,
                  "Subdivide the scene first, as prt bake --max-edge L did");
}

void apply_emitter_options(const EmitterRelightArguments& a, relight::RelightRequest* request) {
  if (!a.emitter.empty() && a.emitters.empty())
    throw UsageError(
        "--emitter applies to emitter responses: give --emitters RESPONSES.prte "
        "(or relight a responses file alone)");
  if (a.max_edge && !(*a.max_edge > 0.0 && std::isfinite(*a.max_edge)))
    throw UsageError("--max-edge " + std::to_string(*a.max_edge) +
                     ": must be a finite positive length");
  request->max_edge = a.max_edge;
  request->emitters_path = a.emitters;
  request->emitter_colors = parse_colors(a);
}

void check_responses_file(const std::string& path) {
  if (prt::is_emitter_responses_file(path)) return;  // read (and checked) by the run
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".obj" || ext == ".gltf" || ext == ".glb")
    throw UsageError("expected SCENE FILE.prt ENVIRONMENT (or an emitter responses file alone)");
  const prt::Result<prt::EmitterResponses> read = prt::read_emitter_responses(path);
  throw CommandError(read.ok() ? path + ": not an emitter responses file"
                               : read.status().message());
}

bool relight_if_emitter_responses(const relight::RelightRequest& request,
                                  const EmitterRelightArguments& a, bool quiet) {
  if (!prt::is_emitter_responses_file(request.transfer_path)) return false;
  if (!a.emitters.empty())
    throw UsageError("--emitters adds responses to a coefficient file; " + request.transfer_path +
                     " is itself a responses file");
  if (a.max_edge)
    throw UsageError("--max-edge does not apply to a responses file (its mesh is stored)");
  const relight::RelightSummary s = relight::run_emitter_relight(request, parse_colors(a));
  if (quiet) return true;
  std::printf("relit %zu vertices from %s; recombination %.3f ms, rendering %.3f s.\n%s\nwrote:",
              s.vertex_count, s.window_note.c_str(), 1e3 * s.shade_seconds, s.render_seconds,
              relight::describe_view(request, s).c_str());
  for (const std::string& file : s.files_written) std::printf(" %s", file.c_str());
  std::printf("\n");
  return true;
}

}  // namespace prt::cli
