// `prt info FILE.prt [--json | --csv]`: describe a coefficient file.
//   default  the header (kind, order, channels, precision, vertices, primitives, fingerprint,
//            sections) and the metadata JSON, as text;
//   --json   the same as one JSON object;
//   --csv    one row per vertex: index, x, y, z, nx, ny, nz, [ao], [bx, by, bz], then the
//            coefficients channel by channel, named c<channel>_<k> (k = l(l+1)+m).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "prt/transfer_data.h"
#include "prt/transfer_file.h"
#include "sh/basis.h"

namespace prt::cli {
namespace {

struct InfoArguments {
  std::string file;
  bool json = false, csv = false;
};

nlohmann::json describe(const prt::TransferData& d, const std::string& path) {
  nlohmann::json j;
  j["file"] = path;
  std::error_code ec;
  const auto size = std::filesystem::file_size(path, ec);
  if (!ec) j["bytes"] = size;
  j["kind"] = prt::transfer_kind_name(d.kind);
  j["order"] = d.order;
  j["coefficients_per_channel"] = d.coefficients_per_channel();
  j["channels"] = d.channels;
  j["precision"] = d.storage == prt::Precision::F16 ? "f16" : "f32";
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
  j["sh_basis"] = prt::sh::kBasisConvention;
  if (!d.metadata_json.empty()) {
    nlohmann::json meta = nlohmann::json::parse(d.metadata_json, nullptr, false);
    j["metadata"] = meta.is_discarded() ? nlohmann::json(d.metadata_json) : meta;
  }
  return j;
}

void print_text(const prt::TransferData& d, const nlohmann::json& j) {
  std::printf("file          %s", j["file"].get<std::string>().c_str());
  if (j.contains("bytes")) std::printf(" (%llu bytes)", j["bytes"].get<unsigned long long>());
  std::printf("\nkind          %s\n", prt::transfer_kind_name(d.kind));
  std::printf("order         %u (%u coefficients per channel)\n", d.order,
              d.coefficients_per_channel());
  std::printf("channels      %u\n", d.channels);
  std::printf("precision     %s\n", d.storage == prt::Precision::F16 ? "f16" : "f32");
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

void print_csv(const prt::TransferData& d) {
  const uint32_t K = d.coefficients_per_channel(), C = d.channels;
  const bool ao = !d.ao.empty(), bent = !d.bent_normals.empty();
  std::printf("index,x,y,z,nx,ny,nz");
  if (ao) std::printf(",ao");
  if (bent) std::printf(",bx,by,bz");
  for (uint32_t c = 0; c < C; ++c)
    for (uint32_t k = 0; k < K; ++k) std::printf(",c%u_%u", c, k);
  std::printf("\n");
  for (uint64_t v = 0; v < d.vertex_count; ++v) {
    std::printf("%llu", static_cast<unsigned long long>(v));
    for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.positions[3 * v + a]));
    for (int a = 0; a < 3; ++a) std::printf(",%.9g", static_cast<double>(d.normals[3 * v + a]));
    if (ao) std::printf(",%.9g", static_cast<double>(d.ao[v]));
    if (bent)
      for (int a = 0; a < 3; ++a)
        std::printf(",%.9g", static_cast<double>(d.bent_normals[3 * v + a]));
    const float* t = &d.coefficients[v * C * K];
    for (uint32_t i = 0; i < C * K; ++i) std::printf(",%.9g", static_cast<double>(t[i]));
    std::printf("\n");
  }
}

void run(const InfoArguments& args) {
  if (args.json && args.csv) throw CommandError("--json and --csv are exclusive");
  prt::Result<prt::TransferData> read = prt::read_transfer_file(args.file);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::TransferData& d = read.value();
  if (args.csv) {
    print_csv(d);
    return;
  }
  const nlohmann::json j = describe(d, args.file);
  if (args.json)
    std::printf("%s\n", j.dump(2).c_str());
  else
    print_text(d, j);
}

void register_info(CLI::App& app) {
  auto args = std::make_shared<InfoArguments>();
  CLI::App* cmd = app.add_subcommand("info", "Describe a coefficient (.prt) file");
  cmd->add_option("file", args->file, "Coefficient file (.prt)")->required();
  cmd->add_flag("--json", args->json, "Print the header and metadata as JSON");
  cmd->add_flag("--csv", args->csv, "Print one CSV row per vertex");
  cmd->callback([args] { run(*args); });
}

}  // namespace

PRT_REGISTER_COMMAND(25, register_info);

}  // namespace prt::cli
