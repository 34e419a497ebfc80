// cli/radiosity_shard.cpp — form-factor shards and their merge (radiosity_shard.h).
#include "radiosity_shard.h"

#include <algorithm>
#include <cstdio>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "option_rules.h"
#include "prt/formats/part_file.h"
#include "radiosity/form_factor_cache.h"
#include "run_record.h"
#include "shard_cli.h"

namespace prt::cli {
namespace {

std::string options_json(const radiosity::FormFactorOptions& o) {
  nlohmann::json j;
  j["method"] = static_cast<int>(o.method);
  j["quadrature_points"] = o.quadrature_points;
  j["rays_per_patch"] = o.rays_per_patch;
  j["emitter_rays_per_patch"] = o.emitter_rays_per_patch;
  j["seed"] = o.seed;
  j["sampling"] = static_cast<int>(o.sampling);
  j["emitter_rows"] = static_cast<int>(o.emitter_rows);
  j["hemicube_resolution"] = o.hemicube_resolution;
  j["revision"] = radiosity::kFormFactorRevision;
  return j.dump();
}

// The algorithms' revision the rows were computed with: 1 for parts written before it was
// recorded (their merge is then a stale cache, recomputed where it is used).
uint32_t revision_of(const std::string& text) {
  const nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  return j.is_object() && j.contains("revision") && j["revision"].is_number_unsigned()
             ? std::max<uint32_t>(1, j["revision"].get<uint32_t>())
             : 1;
}

radiosity::FormFactorOptions options_of(const std::string& text, const std::string& name) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    radiosity::FormFactorOptions o;
    o.method = static_cast<radiosity::FormFactorMethod>(j.at("method").get<int>());
    o.quadrature_points = j.at("quadrature_points").get<int>();
    o.rays_per_patch = j.at("rays_per_patch").get<int>();
    o.emitter_rays_per_patch = j.at("emitter_rays_per_patch").get<int>();
    o.seed = j.at("seed").get<uint64_t>();
    o.sampling = static_cast<radiosity::RaySampling>(j.at("sampling").get<int>());
    o.emitter_rows = static_cast<radiosity::EmitterRows>(j.at("emitter_rows").get<int>());
    o.hemicube_resolution = j.at("hemicube_resolution").get<int>();
    return o;
  } catch (const nlohmann::json::exception& e) {
    throw CommandError(name + ": settings section: " + e.what());
  }
}

}  // namespace

void check_radiosity_shard(const CLI::App& cmd) {
  refuse_unless(cmd, false,
                {"--vertex-colors",
                 "--csv",
                 "--per-emitter",
                 "--form-factor-cache",
                 "--move",
                 "--adaptive",
                 "--max-patches",
                 "--adaptive-passes",
                 "--adaptive-levels",
                 "--solver",
                 "--link-epsilon",
                 "--link-rays",
                 "--link-passes",
                 "--tolerance",
                 "--max-iterations",
                 "--exposure",
                 "--size",
                 "--spp",
                 "--camera",
                 "--hemicube"},
                "a whole solve (--shard computes form-factor rows only)");
}

void run_radiosity_shard(const radiosity::SceneSolveRequest& request, bake::ShardSpec shard,
                         const std::string& output, bool quiet) {
  const radiosity::FormFactorShard rows =
      radiosity::compute_form_factor_shard(request, shard.index, shard.count);
  const prt::Status written = prt::write_part_file(
      output,
      bake::encode_form_factor_part(shard, rows.key, rows.patches, rows.first, rows.rows,
                                    options_json(rows.options), rows.options.seed, prt_version()));
  if (!written.ok()) throw CommandError(written.message());
  run_record().phase("form factors", rows.seconds);
  if (quiet) return;
  std::printf("form factors of shard %s of %s: rows %zu..%zu of %zu patches (%.2f s); wrote %s\n",
              shard_text(shard).c_str(), request.scene_path.c_str(), rows.first, rows.end,
              rows.patches, rows.seconds, output.c_str());
}

void merge_form_factor_parts(const std::vector<const bake::TransferPartFile*>& parts,
                             const std::string& output, bool quiet) {
  radiosity::FormFactorMatrix f;
  f.size = parts[0]->part.vertices;
  f.f.reserve(f.size * f.size);
  for (const bake::TransferPartFile* p : parts)
    f.f.insert(f.f.end(), p->form_factor_rows.begin(), p->form_factor_rows.end());
  if (f.f.size() != f.size * f.size)
    throw CommandError(parts[0]->name + ": the parts do not make a square matrix");
  const radiosity::FormFactorOptions options = options_of(parts[0]->settings, parts[0]->name);
  radiosity::save_form_factors(output, f, parts[0]->key, &options, revision_of(parts[0]->settings));
  if (!quiet)
    std::printf("merged %zu parts: form factors of %zu patches; wrote %s\n", parts.size(), f.size,
                output.c_str());
}

}  // namespace prt::cli
