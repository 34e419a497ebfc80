// cli/emitter_cli.h — the emitter options of `prt relight` (relight/emitter_relight.h), kept
// apart so the SH command changes by a few lines only:
//   prt relight RESPONSES.prte -o OUT [--emitter NAME=r,g,b ...] [--camera … --size … --csv …]
//   prt relight SCENE FILE.prt ENV -o OUT --max-edge L --emitters RESPONSES.prte
//               [--emitter NAME=r,g,b ...]      (environment + emitters in one image)
// An --emitter NAME=v sets a grey strength; emitters not named keep their stored emission.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "relight/relight_pipeline.h"

namespace prt::cli {

struct EmitterRelightArguments {
  std::vector<std::string> emitter;  // NAME=r,g,b or NAME=v
  std::string emitters;              // responses file added to an SH relight
  std::optional<double> max_edge;    // subdivide the scene as prt bake --max-edge did
};

void add_emitter_relight_options(CLI::App* command, EmitterRelightArguments* args);

// Fills request->max_edge, emitters_path and emitter_colors for an SH relight. Throws
// UsageError for --emitter without --emitters or a bad --max-edge / --emitter value.
void apply_emitter_options(const EmitterRelightArguments& args, relight::RelightRequest* request);

// `prt relight RESPONSES.prte -o OUT`: when request.transfer_path is a responses file, relights
// it with the --emitter colours, prints the summary (unless quiet) and returns true; otherwise
// returns false and does nothing.
bool relight_if_emitter_responses(const relight::RelightRequest& request,
                                  const EmitterRelightArguments& args, bool quiet);

}  // namespace prt::cli

namespace prt::cli {

// True when `path` ends in .prte (any case): a file meant to hold emitter responses, read as one
// (a missing, empty or corrupt one gets the reader's message naming it).
bool has_responses_extension(const std::string& path);

// `prt info FILE.prte [--json | --csv]`: when FILE is a responses file (by its magic, or by its
// .prte name: then a corrupt file is reported as such), describes it (text:
// vertices, triangles, fingerprint, each emitter's name and stored emission; --json the same as
// one object; --csv one row per vertex: index,x,y,z,nx,ny,nz, then NAME_r,NAME_g,NAME_b per
// emitter) and returns true; otherwise returns false. Throws CommandError for a corrupt file.
//
// `prt relight FILE -o OUT` with FILE alone: check_responses_file throws CommandError with the
// reader's message ("FILE: truncated: ...") when FILE is not a readable responses file, and
// UsageError "expected SCENE FILE.prt ENVIRONMENT ..." when FILE is a scene.
void check_responses_file(const std::string& path);
bool info_if_emitter_responses(const std::string& path, bool json, bool csv);

}  // namespace prt::cli
