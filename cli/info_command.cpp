// `prt info FILE.prt [--json | --csv]`: describe a coefficient file of any kind
// (prt/formats/coefficient_file.h), a glossy transfer file or its CPCA compression
// (cli/glossy_cli.h, cli/cpca_info.h), emitter responses (cli/emitter_cli.h), a form-factor
// cache (radiosity/form_factor_cache.h: patches, method and settings, revision, key, size; no
// --csv) or a link cache (radiosity/link_cache.h: patches, links, settings, revision, keys; no
// --csv). `prt info SCENE (.glb, .gltf, .obj) [--material NAME=MODEL:...]`: the scene's size and
// one line per primitive with its material (prt::brdf::describe; scene/material_override.h for the
// overrides, applied as prt bake applies them).
//   default  the header (kind, order or cube size, channels, precision, vertices, primitives,
//            fingerprint, sections) and the metadata JSON, as text;
//   --json   the same as one JSON object;
//   --csv    one row per vertex: index, x, y, z, nx, ny, nz, [ao], [bx, by, bz], then the
//            coefficients channel by channel: c<channel>_<k> for SH (k = l(l+1)+m), and for
//            Haar the dense wavelet coefficients w<channel>_<i> (i = face·N² + q, zero where
//            the file stores none).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "emitter_cli.h"
#include "glossy_cli.h"
#include "material_option.h"
#include "output_safety.h"
#include "prt/formats/coefficient_file.h"
#include "prt/formats/transfer_data.h"
#include "prt/haar/transform.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/link_cache.h"
#include "run_record.h"
#include "scene/scene_loader.h"
#include "sh/basis.h"

namespace prt::cli {
namespace {

struct InfoArguments {
  std::string file;
  bool json = false, csv = false;
  std::vector<std::string> materials;  // --material overrides (scenes only)
};

bool is_scene_path(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".glb" || ext == ".gltf" || ext == ".obj";
}

void print_scene(const InfoArguments& args) {
  if (args.json || args.csv) throw UsageError("--json and --csv apply to coefficient files only");
  scene::LoadOptions load;
  load.material_overrides = parse_material_options(args.materials);
  const scene::Scene scene = scene::load_scene(args.file, load);
  std::printf("%s: %zu vertices, %zu triangles, %zu primitives, %zu camera(s), tangents %s\n",
              args.file.c_str(), scene.vertex_count(), scene.triangles.size(),
              scene.primitives.size(), scene.cameras.size(),
              scene.tangents.empty() ? "generated" : "from the file");
  std::printf("materials:\n");
  for (const std::string& line : scene::describe_materials(scene))
    std::printf("  %s\n", line.c_str());
}

const char* precision_name(const prt::CoefficientFile& f) {
  if (!f.haar) return f.data.storage == prt::Precision::F16 ? "f16" : "f32";
  switch (f.haar->quantization) {
    case prt::HaarQuantization::Bits8:
      return "i8 (per-vertex step)";
    case prt::HaarQuantization::Bits16:
      return "i16 (per-vertex step)";
    default:
      return "f32";
  }
}

uint64_t coefficients_per_channel(const prt::CoefficientFile& f) {
  return f.haar ? 6ull * static_cast<uint64_t>(f.haar->size) * static_cast<uint64_t>(f.haar->size)
                : f.data.coefficients_per_channel();
}

nlohmann::json describe(const prt::CoefficientFile& f, const std::string& path) {
  const prt::TransferData& d = f.data;
  nlohmann::json j;
  j["file"] = path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) j["bytes"] = size;
  j["kind"] = prt::transfer_kind_name(d.kind);
  if (f.haar) {
    j["cube_size"] = f.haar->size;
    j["stored_entries"] = f.haar->entry_count();
    j["stored_bytes"] = f.haar->stored_bytes();
    j["dense_bytes"] = f.haar->dense_bytes();
  } else {
    j["order"] = d.order;
  }
  j["coefficients_per_channel"] = coefficients_per_channel(f);
  j["channels"] = d.channels;
  j["precision"] = precision_name(f);
  j["albedo_folded"] = d.albedo_folded;
  j["vertices"] = d.vertex_count;
  char fp[32];
  std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(d.fingerprint));
  j["fingerprint"] = fp;
  nlohmann::json sections = nlohmann::json::array({"positions", "normals", "coefficients"});
  if (!d.ao.empty()) sections.push_back("ao");
  if (!d.bent_normals.empty()) sections.push_back("bent_normals");
  if (!d.metadata_json.empty()) sections.push_back("metadata");
  j["sections"] = sections;
  nlohmann::json prims = nlohmann::json::array();
  for (const prt::PrimitiveRange& p : d.primitives)
    prims.push_back(
        {{"name", p.name}, {"first_vertex", p.first_vertex}, {"vertex_count", p.vertex_count}});
  j["primitives"] = prims;
  if (f.haar)
    j["haar_basis"] = prt::kHaarBasisConvention;
  else
    j["sh_basis"] = prt::sh::kBasisConvention;
  if (!d.metadata_json.empty()) {
    nlohmann::json meta = nlohmann::json::parse(d.metadata_json, nullptr, false);
    j["metadata"] = meta.is_discarded() ? nlohmann::json(d.metadata_json) : meta;
  }
  return j;
}

void print_text(const prt::CoefficientFile& f, const nlohmann::json& j) {
  const prt::TransferData& d = f.data;
  std::printf("file          %s", j["file"].get<std::string>().c_str());
  if (j.contains("bytes")) std::printf(" (%llu bytes)", j["bytes"].get<unsigned long long>());
  std::printf("\nkind          %s\n", prt::transfer_kind_name(d.kind));
  if (f.haar)
    std::printf("cube size     %d (%llu wavelet coefficients per channel, %llu stored entries)\n",
                f.haar->size, static_cast<unsigned long long>(coefficients_per_channel(f)),
                static_cast<unsigned long long>(f.haar->entry_count()));
  else
    std::printf("order         %u (%u coefficients per channel)\n", d.order,
                d.coefficients_per_channel());
  std::printf("channels      %u\n", d.channels);
  std::printf("precision     %s\n", precision_name(f));
  std::printf("albedo        %s\n",
              d.albedo_folded ? "folded in (T includes albedo/pi)" : "kept apart");
  std::printf("vertices      %llu\n", static_cast<unsigned long long>(d.vertex_count));
  std::printf("fingerprint   %s\n", j["fingerprint"].get<std::string>().c_str());
  std::printf("sections     ");
  for (const auto& s : j["sections"]) std::printf(" %s", s.get<std::string>().c_str());
  std::printf("\nprimitives    %zu\n", d.primitives.size());
  for (const prt::PrimitiveRange& p : d.primitives)
    std::printf("  %-30s vertices %llu .. %llu\n", p.name.c_str(),
                static_cast<unsigned long long>(p.first_vertex),
                static_cast<unsigned long long>(p.first_vertex + p.vertex_count));
  if (j.contains("metadata")) std::printf("metadata\n%s\n", j["metadata"].dump(2).c_str());
}

// The dense coefficients of vertices [first, first + count), channel-major per vertex: SH rows
// as stored, Haar rows expanded from the per-wavelet vertex lists (zero where none is stored).
std::vector<float> dense_rows(const prt::CoefficientFile& f, uint64_t first, uint64_t count) {
  const uint64_t K = coefficients_per_channel(f), C = f.data.channels;
  if (!f.haar) {
    const float* begin = &f.data.coefficients[first * C * K];
    return std::vector<float>(begin, begin + count * C * K);
  }
  std::vector<float> rows(count * C * K, 0.f);
  const prt::HaarTransfer& h = *f.haar;
  // Each wavelet's vertex list is ascending: a binary search finds the chunk's part of it.
  for (uint64_t i = 0; i < K; ++i) {
    const auto list_end = h.vertices.begin() + static_cast<std::ptrdiff_t>(h.offsets[i + 1]);
    auto it = std::lower_bound(h.vertices.begin() + static_cast<std::ptrdiff_t>(h.offsets[i]),
                               list_end, static_cast<uint32_t>(first));
    for (; it != list_end && *it < first + count; ++it) {
      const uint64_t e = static_cast<uint64_t>(it - h.vertices.begin()), v = *it;
      for (uint64_t c = 0; c < C; ++c)
        rows[((v - first) * C + c) * K + i] = h.dequantized_value(e, static_cast<int>(c));
    }
  }
  return rows;
}

void print_csv(const prt::CoefficientFile& f) {
  const prt::TransferData& d = f.data;
  const uint64_t K = coefficients_per_channel(f), C = d.channels;
  const bool ao = !d.ao.empty(), bent = !d.bent_normals.empty();
  const char prefix = f.haar ? 'w' : 'c';
  std::printf("index,x,y,z,nx,ny,nz");
  if (ao) std::printf(",ao");
  if (bent) std::printf(",bx,by,bz");
  for (uint64_t c = 0; c < C; ++c)
    for (uint64_t k = 0; k < K; ++k)
      std::printf(",%c%llu_%llu", prefix, static_cast<unsigned long long>(c),
                  static_cast<unsigned long long>(k));
  std::printf("\n");
  constexpr uint64_t kChunk = 1024;  // vertices expanded at a time (Haar: one pass per chunk)
  for (uint64_t first = 0; first < d.vertex_count; first += kChunk) {
    const uint64_t count = std::min<uint64_t>(kChunk, d.vertex_count - first);
    const std::vector<float> rows = dense_rows(f, first, count);
    for (uint64_t v = first; v < first + count; ++v) {
      std::printf("%llu", static_cast<unsigned long long>(v));
      for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.positions[3 * v + a]));
      for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.normals[3 * v + a]));
      if (ao) std::printf(",%.9g", static_cast<double>(d.ao[v]));
      if (bent)
        for (int a = 0; a < 3; ++a)
          std::printf(",%.9g", static_cast<double>(d.bent_normals[3 * v + a]));
      const float* t = &rows[(v - first) * C * K];
      for (uint64_t i = 0; i < C * K; ++i) std::printf(",%.9g", static_cast<double>(t[i]));
      std::printf("\n");
    }
  }
}

// The method and the settings it uses (as `prt radiosity` names them).
std::string describe_form_factor_method(const radiosity::FormFactorOptions& o) {
  switch (o.method) {
    case radiosity::FormFactorMethod::Analytic:
      return "analytic, quadrature " + std::to_string(o.quadrature_points);
    case radiosity::FormFactorMethod::Hemicube:
      return "hemicube, resolution " + std::to_string(o.hemicube_resolution);
    case radiosity::FormFactorMethod::Rays:
      break;
  }
  const bool reciprocal = o.emitter_rows == radiosity::EmitterRows::Reciprocal;
  return "rays, " + std::to_string(o.rays_per_patch) + " per patch, seed " +
         std::to_string(o.seed) + ", emitter rays " + std::to_string(o.emitter_rays_per_patch) +
         ", sampling " + (o.sampling == radiosity::RaySampling::Sobol ? "sobol" : "independent") +
         ", emitter rows " + (reciprocal ? "reciprocal" : "rays") +
         (reciprocal ? ", quadrature " + std::to_string(o.quadrature_points) : "");
}

// The header of a cache file: refuses --csv (a cache has no per-vertex rows) and turns the
// reader's one-line std::runtime_error into a CommandError (exit 1).
template <class Read>
auto read_cache_header(const InfoArguments& args, const char* kind, Read read) {
  if (args.csv)
    throw UsageError("--csv: " + args.file + " is a " + kind +
                     "; --csv prints the per-vertex rows of .prt, .prtg, .prtq and .prte files");
  try {
    return read(args.file);
  } catch (const std::runtime_error& e) {
    throw CommandError(e.what());
  }
}

// A 64-bit key as 16 hexadecimal digits.
std::string hex_key(uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

// A cache's algorithm revision against this prt's: "2 (current)", "1 (earlier than this prt's
// 2: prt radiosity recomputes the cache and saves over it)" or "3 (later than this prt's 2:
// refused)".
std::string describe_revision(uint32_t cached, uint32_t current) {
  const std::string now = "this prt's " + std::to_string(current);
  if (cached == current) return std::to_string(cached) + " (current)";
  if (cached < current)
    return std::to_string(cached) + " (earlier than " + now +
           ": prt radiosity recomputes the cache and saves over it)";
  return std::to_string(cached) + " (later than " + now + ": refused)";
}

// `prt info` of a form-factor cache (radiosity/form_factor_cache.h): patches, method and
// settings (versions 2 and 3), the algorithms' revision, key and size.
void print_form_factor_cache(const InfoArguments& args) {
  const radiosity::FormFactorCacheInfo info =
      read_cache_header(args, "form-factor cache", radiosity::read_form_factor_cache_info);
  const std::string key = hex_key(info.key);
  const std::string method =
      info.settings_recorded
          ? describe_form_factor_method(info.options)
          : "not recorded (" +
                std::string(info.version == 1 ? "a version-1 cache" : "saved without") + ")";
  nlohmann::json j;
  j["file"] = args.file;
  j["bytes"] = info.file_size;
  j["kind"] = "form-factor cache";
  j["version"] = info.version;
  j["revision"] = info.revision;
  j["current_revision"] = radiosity::kFormFactorRevision;
  j["patches"] = info.patches;
  j["matrix"] = std::to_string(info.patches) + "x" + std::to_string(info.patches) + " f32";
  j["key"] = key;
  j["method"] = info.settings_recorded ? nlohmann::json(method) : nlohmann::json(nullptr);
  if (args.json) {
    add_run_record_json(j, args.file);
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("file          %s (%llu bytes)\n", args.file.c_str(),
              static_cast<unsigned long long>(info.file_size));
  std::printf("kind          form-factor cache (saved by prt radiosity), version %u\n",
              info.version);
  std::printf("patches       %llu (a %s matrix, row i = sender i)\n",
              static_cast<unsigned long long>(info.patches),
              j["matrix"].get<std::string>().c_str());
  std::printf("method        %s\n", method.c_str());
  std::printf("revision      %s\n",
              describe_revision(info.revision, radiosity::kFormFactorRevision).c_str());
  std::printf("key           %s (patches' corners, the method's settings and the revision)\n",
              key.c_str());
}

// `prt info` of a link cache (radiosity/link_cache.h, the hierarchical solver's
// `--form-factor-cache`): patches, links, the settings that shaped them and the three keys.
void print_link_cache(const InfoArguments& args) {
  const radiosity::LinkCacheInfo info =
      read_cache_header(args, "link cache", radiosity::read_link_cache_info);
  nlohmann::json j;
  j["file"] = args.file;
  j["bytes"] = info.file_size;
  j["kind"] = "link cache";
  j["version"] = info.version;
  j["revision"] = info.revision;
  j["current_revision"] = radiosity::kLinkCacheRevision;
  j["patches"] = info.patches;
  j["links"] = info.links;
  j["transfer"] = info.fine ? "fine" : "coarse";
  j["link_epsilon"] = info.epsilon;
  j["visibility_rays"] = info.visibility_rays;
  j["seed"] = info.seed;
  j["keys"] = {{"geometry", hex_key(info.keys.geometry)},
               {"settings", hex_key(info.keys.settings)},
               {"lighting", hex_key(info.keys.lighting)}};
  if (args.json) {
    add_run_record_json(j, args.file);
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("file          %s (%llu bytes)\n", args.file.c_str(),
              static_cast<unsigned long long>(info.file_size));
  std::printf(
      "kind          link cache (saved by prt radiosity --solver hierarchical), version %u\n",
      info.version);
  std::printf("patches       %llu\n", static_cast<unsigned long long>(info.patches));
  std::printf("links         %llu\n", static_cast<unsigned long long>(info.links));
  std::printf("settings      %s transfer, link epsilon %g, %u visibility rays a link, seed %llu\n",
              info.fine ? "fine" : "coarse", info.epsilon, info.visibility_rays,
              static_cast<unsigned long long>(info.seed));
  std::printf("revision      %s\n",
              describe_revision(info.revision, radiosity::kLinkCacheRevision).c_str());
  std::printf("keys          geometry %s, settings %s, lighting %s\n",
              hex_key(info.keys.geometry).c_str(), hex_key(info.keys.settings).c_str(),
              hex_key(info.keys.lighting).c_str());
}

// A file of any kind but a scene, as its kind's printer describes it.
void describe_file(const InfoArguments& args) {
  if (radiosity::is_form_factor_cache(args.file)) {
    if (!args.materials.empty()) throw UsageError("--material applies to scenes only");
    return print_form_factor_cache(args);
  }
  if (radiosity::is_link_cache(args.file)) {
    if (!args.materials.empty()) throw UsageError("--material applies to scenes only");
    return print_link_cache(args);
  }
  if (!args.materials.empty()) throw UsageError("--material applies to scenes only");
  if (is_glossy_file(args.file)) return describe_glossy_file(args.file, args.json, args.csv);
  if (info_if_emitter_responses(args.file, args.json, args.csv)) return;
  prt::Result<prt::CoefficientFile> read = prt::read_coefficient_file(args.file);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::CoefficientFile& f = read.value();
  if (args.csv) {
    print_csv(f);
    return;
  }
  nlohmann::json j = describe(f, args.file);
  if (args.json) {
    add_run_record_json(j, args.file);
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    print_text(f, j);
  }
}

// The file, then (as text) its run's times and threads from FILE.run.json (run_record.h); --json
// has them under "run". A form-factor cache has no record of its own (its run's record is beside
// that run's main output), so nothing is said of one.
void run(const InfoArguments& args) {
  if (is_scene_path(args.file)) return print_scene(args);
  describe_file(args);
  if (!args.json && !args.csv && !radiosity::is_form_factor_cache(args.file))
    print_run_record(args.file);
}

Command register_info(CLI::App& app) {
  auto args = std::make_shared<InfoArguments>();
  CLI::App* cmd = app.add_subcommand(
      "info",
      "Describe a coefficient file (.prt: SH or Haar), a glossy transfer file (.prtg), its CPCA "
      "compression (.prtq), emitter responses (.prte), a form-factor cache, a link cache, or a "
      "scene's "
      "materials");
  cmd->add_option(
         "file", args->file,
         "Coefficient file (.prt, SH or Haar wavelets), glossy transfer file (.prtg), "
         "CPCA file (.prtq, prt compress: error, metric, the source bake's settings), "
         "emitter responses (.prte), form-factor cache or link cache (saved by prt radiosity: "
         "patches, method or links, settings), or a scene (.glb, .gltf, .obj)")
      ->required();
  add_material_option(*cmd, args->materials);
  CLI::Option* json = cmd->add_flag("--json", args->json, "Print the header and metadata as JSON");
  cmd->add_flag("--csv", args->csv,
                "Print one CSV row per vertex (.prt, .prtg, .prtq: matrices reconstructed, .prte)")
      ->excludes(json);
  const auto files = [args] {
    CommandFiles f;  // no files are written: only stdout must not be the input
    if (is_scene_path(args->file))
      f.add_scene(args->file);
    else
      f.add_input("coefficient file", args->file);
    return f;
  };
  return {cmd, {}, files, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(25, register_info);

}  // namespace prt::cli
