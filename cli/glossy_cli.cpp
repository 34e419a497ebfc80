// cli/glossy_cli.cpp — see glossy_cli.h.
#include "glossy_cli.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "bake/cpca/compressor.h"
#include "bake/cpca/matrix_source.h"
#include "bake/cpca/relit_metric.h"
#include "bake/glossy_transfer_baker.h"
#include "command_registry.h"
#include "cpca_info.h"
#include "option_rules.h"
#include "output_safety.h"
#include "progress_reporter.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "run_record.h"
#include "sh/basis.h"

namespace prt::cli {
namespace {

// The bounces the request means: --bounces when given, else −1 (until converged) for
// --transfer interreflected and 0 (shadowed) otherwise.
int glossy_bounces(const GlossyBakeRequest& r) {
  if (r.bounces_given) return r.bounces;
  return r.transfer == "interreflected" ? -1 : 0;
}

}  // namespace

void check_glossy_request(const GlossyBakeRequest& r) {
  if (r.order < 1 || r.order > bake::kMaxGlossyBakeOrder)
    throw UsageError("--order " + std::to_string(r.order) + ": must be in [1, " +
                     std::to_string(bake::kMaxGlossyBakeOrder) + "] with --glossy");
  if (!r.transfer.empty() && r.transfer != "shadowed" && r.transfer != "interreflected")
    throw UsageError("--transfer " + r.transfer +
                     ": expected shadowed or interreflected with --glossy");
  if (r.transfer == "shadowed" && r.bounces_given)
    throw UsageError("--bounces applies to glossy interreflection only (not --transfer shadowed)");
  if (r.bounces_given && r.bounces < -1)
    throw UsageError("--bounces " + std::to_string(r.bounces) +
                     ": must be >= 0, or -1 (until converged)");
  if (r.bounce_precision != "f32" && r.bounce_precision != "f16")
    throw UsageError("--bounce-precision " + r.bounce_precision + ": expected f32 or f16");
  if (r.bounce_precision == "f16" && glossy_bounces(r) == 0)
    throw UsageError("--bounce-precision applies to glossy interreflection only");
  if (glossy_bounces(r) >= 0 && r.tolerance_given)
    throw UsageError("--tolerance applies to a solve to convergence (--bounces -1) only");
}

void check_glossy_applicable(const CLI::App& cmd) {
  for (const char* option :
       {"--ao", "--bent-normals", "--auto", "--env", "--cube", "--haar-threshold", "--haar-terms",
        "--haar-bits", "--haar-supersample", "--basis"})
    if (cmd.count(option) > 0)
      throw UsageError(std::string(option) + " does not apply to --glossy");
}

bake::GlossyBakeOptions glossy_bake_options(const GlossyBakeRequest& r) {
  bake::GlossyBakeOptions o;
  o.order = r.order;
  o.samples = r.samples;
  o.bounces = glossy_bounces(r);
  o.bounce_tolerance = r.tolerance;
  o.seed = r.seed;
  o.threads = r.threads;
  o.memory_limit = r.memory_limit;
  o.precision = r.precision == "f16" ? prt::Precision::F16 : prt::Precision::F32;
  o.bounce_precision = r.bounce_precision == "f16" ? prt::Precision::F16 : prt::Precision::F32;
  return o;
}

void run_glossy_bake(const scene::Scene& scene, const GlossyBakeRequest& r) {
  check_glossy_request(r);
  const bake::GlossyBakeOptions o = glossy_bake_options(r);
  ProgressReporter progress(r.quiet);
  // Streamed: the matrices go to the file as they are finished (result.data holds none).
  const bake::GlossyBakeResult result =
      bake::bake_glossy_transfer_to_file(scene, o, r.output, &progress);
  const bake::GlossyBakeStatistics& st = result.stats;
  run_record().phase("rays", st.seconds_rays);
  if (result.data.interreflected) {
    run_record().phase("BRDF projections", st.seconds_projection);
    run_record().phase("bounces", st.seconds_bounces);
  }
  run_record().phase("bake", st.seconds_total);
  if (o.bounces < 0 && !st.converged)
    std::fprintf(stderr, "prt bake: %s: warning: glossy bounces stopped after %d (change %.3g)\n",
                 r.scene.c_str(), st.bounces,
                 st.bounce_change.empty() ? 0.0 : st.bounce_change.back());
  if (r.quiet) return;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(r.output, ec);
  std::printf(
      "baked glossy %s transfer of %s: %llu vertices, %llu triangles, order %d (%dx%d matrices, "
      "%u channel%s), %d samples per vertex; %llu rays in %.2f s (%.2f Mrays/s)",
      result.data.interreflected ? "interreflected" : "shadowed", r.scene.c_str(),
      static_cast<unsigned long long>(st.vertices), static_cast<unsigned long long>(st.triangles),
      o.order, o.order * o.order, o.order * o.order, result.data.channels,
      result.data.channels == 1 ? "" : "s", st.samples_per_vertex,
      static_cast<unsigned long long>(st.rays), st.seconds_rays, st.mrays_per_second());
  if (result.data.interreflected)
    std::printf("; %d bounces (%.2f s, BRDF projections %.2f s)", st.bounces, st.seconds_bounces,
                st.seconds_projection);
  std::printf("; %zu material%s; total %.2f s; wrote %s (%llu bytes, %s)\n",
              result.data.materials.size(), result.data.materials.size() == 1 ? "" : "s",
              st.seconds_total, r.output.c_str(), static_cast<unsigned long long>(ec ? 0 : bytes),
              r.precision.c_str());
}

bool is_glossy_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) &&
         (prt::is_glossy_transfer_file(magic, 4) || prt::is_cpca_transfer_file(magic, 4));
}

void check_compress_request(const GlossyCompressRequest& r) {
  if (r.clusters < 1 || r.clusters > 65535)
    throw UsageError("--clusters " + std::to_string(r.clusters) + ": must be in [1, 65535]");
  if (r.vectors < 0 || r.vectors > 4096)
    throw UsageError("--vectors " + std::to_string(r.vectors) + ": must be in [0, 4096]");
  if (r.max_vectors < 1 || r.max_vectors > 4096)
    throw UsageError("--max-vectors " + std::to_string(r.max_vectors) + ": must be in [1, 4096]");
  if (r.target_error_given && !(r.target_error > 0 && r.target_error < 1)) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", r.target_error);
    throw UsageError("--target-error " + std::string(text) +
                     ": must be a relative error in (0, 1)");
  }
  if (r.max_vectors_given && !r.target_error_given)
    throw UsageError("--max-vectors applies with --target-error only");
  if (r.iterations < 1 || r.iterations > 100)
    throw UsageError("--iterations " + std::to_string(r.iterations) + ": must be in [1, 100]");
  if (r.threads < 0) throw UsageError("--threads " + std::to_string(r.threads) + ": must be >= 0");
}

CommandFiles compress_files(const GlossyCompressRequest& r) {
  CommandFiles files;
  files.add_input("glossy transfer file", r.input);
  files.add_output_file("-o", r.output, {".prtq"}, "a CPCA file");
  files.add_run_record(r.output);
  return files;
}

namespace {

unsigned long long file_bytes(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return ec ? 0ull : static_cast<unsigned long long>(bytes);
}

// More principal vectors than a vertex's matrices have entries (D) cannot lower the error, only
// grow the file: refused by name when asked for, the default --max-vectors capped at D.
uint32_t check_vectors_fit(const GlossyCompressRequest& r, const prt::GlossyTransferData& data) {
  const uint64_t d = uint64_t(data.channels) * data.order * data.order * data.order * data.order;
  const std::string why = " for " + r.input + " (order " + std::to_string(data.order) + ", " +
                          std::to_string(data.channels) + " channel(s): each vertex's matrices " +
                          "have " + std::to_string(d) + " entries)";
  if (!r.target_error_given && uint64_t(r.vectors) > d)
    throw UsageError("--vectors " + std::to_string(r.vectors) + ": at most " + std::to_string(d) +
                     why);
  if (r.max_vectors_given && uint64_t(r.max_vectors) > d)
    throw UsageError("--max-vectors " + std::to_string(r.max_vectors) + ": at most " +
                     std::to_string(d) + why);
  return static_cast<uint32_t>(std::min<uint64_t>(uint64_t(r.max_vectors), d));
}

}  // namespace

void run_glossy_compress(const GlossyCompressRequest& r) {
  check_compress_request(r);
  const auto start = std::chrono::steady_clock::now();
  prt::CpcaOptions o;
  o.clusters = static_cast<uint32_t>(r.clusters);
  o.vectors = static_cast<uint32_t>(r.vectors);
  o.target_relative_rms = r.target_error_given ? r.target_error : 0.0;
  o.iterations = static_cast<uint32_t>(r.iterations);
  o.seed = r.seed;
  o.threads = static_cast<unsigned>(resolved_threads(r.threads));
  o.memory_limit = memory_limit_or_default(r.memory_limit);
  run_record().threads = static_cast<int>(o.threads);
  // The matrices are mapped from the file (or expanded, for binary16, where the limit allows),
  // not loaded: a file larger than memory compresses out of core (bake/cpca/matrix_source.h).
  prt::MemoryBudget budget(o.memory_limit, r.input);
  prt::Result<std::unique_ptr<prt::GlossyMatrixSource>> opened =
      prt::GlossyMatrixSource::open(r.input, budget);
  if (!opened.ok()) throw CommandError(opened.status().message());
  const prt::GlossyMatrixSource& source = **opened;
  const prt::GlossyTransferData& data = source.data();
  const float* matrices = source.matrices();
  const uint64_t matrix_floats = data.vertex_count * data.channels * data.matrix_floats();
  o.max_vectors = check_vectors_fit(r, data);
  if (r.metric == "relit") {
    prt::Result<std::vector<double>> metric = prt::cpca_relit_metric(data);
    if (!metric.ok()) throw CommandError(r.input + ": " + metric.status().message());
    o.row_metric = std::move(metric).value();
  }
  prt::Result<prt::CpcaTransfer> cpca =
      prt::cpca_compress(data.order, data.channels, data.vertex_count, matrices, o);
  if (!cpca.ok()) throw CommandError(r.input + ": " + cpca.status().message());
  run_record().phase(
      "compression",
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  cpca->fingerprint = data.fingerprint;
  const double error = prt::cpca_relative_rms_error(*cpca, matrices);
  const double metric_error = prt::cpca_metric_relative_rms_error(*cpca, matrices, o.row_metric);
  const prt::Status written = prt::write_cpca_file(
      r.output, *cpca, data, make_cpca_record(r, data, *cpca, error, metric_error));
  if (!written.ok()) throw CommandError(written.message());
  if (r.quiet) return;
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const unsigned long long in_bytes = file_bytes(r.input), out_bytes = file_bytes(r.output);
  const double v = double(std::max<uint64_t>(1, data.vertex_count));
  std::printf(
      "compressed %s: %llu vertices, order %u, %u channel%s; %u clusters x %u vectors; relative "
      "RMS matrix error %.4g, %s error %.4g; matrices %.1f bytes/vertex (%.2f%% of %.0f); wrote "
      "%s (%llu bytes, %.1f%% of %llu) in %.2f s\n",
      r.input.c_str(), static_cast<unsigned long long>(data.vertex_count), data.order,
      data.channels, data.channels == 1 ? "" : "s", cpca->cluster_count, cpca->vector_count, error,
      r.metric == "relit" ? "relit-metric" : "matrix", metric_error,
      double(cpca->payload_bytes()) / v,
      100.0 * double(cpca->payload_bytes()) / (4.0 * double(matrix_floats)),
      4.0 * double(matrix_floats) / v, r.output.c_str(), out_bytes,
      in_bytes ? 100.0 * double(out_bytes) / double(in_bytes) : 0.0, in_bytes, seconds);
}

namespace {

nlohmann::json describe(const prt::GlossyTransferData& d, const std::string& path) {
  nlohmann::json j;
  j["file"] = path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) j["bytes"] = size;
  j["kind"] = d.interreflected ? "glossy interreflected" : "glossy shadowed";
  j["order"] = d.order;
  j["matrix"] = std::to_string(d.coefficients()) + "x" + std::to_string(d.coefficients());
  j["channels"] = d.channels;
  j["precision"] = d.storage == prt::Precision::F16 ? "f16" : "f32";
  j["vertices"] = d.vertex_count;
  char fp[32];
  std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(d.fingerprint));
  j["fingerprint"] = fp;
  nlohmann::json mats = nlohmann::json::array();
  std::vector<uint64_t> users(d.materials.size(), 0);
  for (uint32_t m : d.material_of_vertex) ++users[m];
  for (std::size_t m = 0; m < d.materials.size(); ++m)
    mats.push_back({{"material", brdf::describe(d.materials[m])}, {"vertices", users[m]}});
  j["materials"] = mats;
  nlohmann::json prims = nlohmann::json::array();
  for (const prt::PrimitiveRange& p : d.primitives)
    prims.push_back(
        {{"name", p.name}, {"first_vertex", p.first_vertex}, {"vertex_count", p.vertex_count}});
  j["primitives"] = prims;
  j["sh_basis"] = prt::sh::kBasisConvention;
  j["rows"] = "local tangent frame (+z normal, +x tangent)";
  j["columns"] = "global scene frame";
  if (!d.metadata_json.empty()) {
    nlohmann::json meta = nlohmann::json::parse(d.metadata_json, nullptr, false);
    j["metadata"] = meta.is_discarded() ? nlohmann::json(d.metadata_json) : meta;
  }
  return j;
}

void print_text(const prt::GlossyTransferData& d, const nlohmann::json& j) {
  std::printf("file          %s", j["file"].get<std::string>().c_str());
  if (j.contains("bytes")) std::printf(" (%llu bytes)", j["bytes"].get<unsigned long long>());
  std::printf("\nkind          %s\n", j["kind"].get<std::string>().c_str());
  std::printf("order         %u (%ux%u transfer matrices: local rows, global columns)\n", d.order,
              d.coefficients(), d.coefficients());
  std::printf("channels      %u\n", d.channels);
  std::printf("precision     %s\n", j["precision"].get<std::string>().c_str());
  std::printf("vertices      %llu\n", static_cast<unsigned long long>(d.vertex_count));
  std::printf("fingerprint   %s\n", j["fingerprint"].get<std::string>().c_str());
  std::printf("materials     %zu\n", d.materials.size());
  for (const auto& m : j["materials"])
    std::printf("  %-44s %llu vertices\n", m["material"].get<std::string>().c_str(),
                m["vertices"].get<unsigned long long>());
  std::printf("primitives    %zu\n", d.primitives.size());
  for (const prt::PrimitiveRange& p : d.primitives)
    std::printf("  %-30s vertices %llu .. %llu\n", p.name.c_str(),
                static_cast<unsigned long long>(p.first_vertex),
                static_cast<unsigned long long>(p.first_vertex + p.vertex_count));
  if (j.contains("metadata")) std::printf("metadata\n%s\n", j["metadata"].dump(2).c_str());
}

// One row per vertex: geometry, frame, material, then m<c>_<i>_<j>.
void print_csv(const prt::GlossyTransferData& d) {
  const std::size_t K = d.coefficients(), C = d.channels;
  std::printf("index,x,y,z,nx,ny,nz,tx,ty,tz,tw,material");
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t i = 0; i < K; ++i)
      for (std::size_t k = 0; k < K; ++k) std::printf(",m%zu_%zu_%zu", c, i, k);
  std::printf("\n");
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    std::printf("%zu", v);
    for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.positions[3 * v + a]));
    for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.normals[3 * v + a]));
    for (int a = 0; a < 4; ++a) std::printf(",%.9g", static_cast<double>(d.tangents[4 * v + a]));
    std::printf(",%u", d.material_of_vertex[v]);
    const float* m = &d.matrices[v * C * K * K];
    for (std::size_t e = 0; e < C * K * K; ++e) std::printf(",%.9g", static_cast<double>(m[e]));
    std::printf("\n");
  }
}

}  // namespace

void describe_glossy_file(const std::string& path, bool json, bool csv) {
  {
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    if (in.read(magic, 4) && prt::is_cpca_transfer_file(magic, 4))
      return describe_cpca_file(path, json, csv);
  }
  prt::Result<prt::GlossyTransferData> read = prt::read_glossy_transfer_file(path);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::GlossyTransferData& d = read.value();
  if (csv) return print_csv(d);
  nlohmann::json j = describe(d, path);
  if (json) {
    add_run_record_json(j, path);
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    print_text(d, j);
  }
}

}  // namespace prt::cli
