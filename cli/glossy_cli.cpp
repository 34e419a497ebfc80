// cli/glossy_cli.cpp — see glossy_cli.h.
#include "glossy_cli.h"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "bake/glossy_transfer_baker.h"
#include "command_registry.h"
#include "progress_reporter.h"
#include "prt/glossy_transfer_file.h"
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

void run_glossy_bake(const scene::Scene& scene, const GlossyBakeRequest& r) {
  check_glossy_request(r);
  bake::GlossyBakeOptions o;
  o.order = r.order;
  o.samples = r.samples;
  o.bounces = glossy_bounces(r);
  o.bounce_tolerance = r.tolerance;
  o.seed = r.seed;
  o.threads = r.threads;
  o.precision = r.precision == "f16" ? prt::Precision::F16 : prt::Precision::F32;
  ProgressReporter progress(r.quiet);
  const bake::GlossyBakeResult result = bake::bake_glossy_transfer(scene, o, &progress);
  const prt::Status written = prt::write_glossy_transfer_file(r.output, result.data);
  if (!written.ok()) throw CommandError(written.message());
  const bake::GlossyBakeStatistics& st = result.stats;
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
  return in.read(magic, 4) && prt::is_glossy_transfer_file(magic, 4);
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
  prt::Result<prt::GlossyTransferData> read = prt::read_glossy_transfer_file(path);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::GlossyTransferData& d = read.value();
  if (csv) return print_csv(d);
  const nlohmann::json j = describe(d, path);
  if (json)
    std::printf("%s\n", j.dump(2).c_str());
  else
    print_text(d, j);
}

}  // namespace prt::cli
