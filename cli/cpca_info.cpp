// cli/cpca_info.cpp — see cpca_info.h.
#include "cpca_info.h"

#include <cstdio>
#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "prt/brdf/material.h"
#include "prt/formats/cpca_file.h"
#include "run_record.h"

namespace prt::cli {
namespace {

unsigned long long file_bytes(const std::string& path) {
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  return ec ? 0ull : static_cast<unsigned long long>(bytes);
}

nlohmann::json parse_object(const std::string& text) {
  if (text.empty()) return nullptr;
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  return j.is_discarded() ? nlohmann::json(text) : j;
}

// "prt bake --glossy of glossy.glb: glossy shadowed, order 5, 256 samples per vertex, seed 1,
// f32": the settings a bake's metadata records (those present).
std::string describe_bake(const nlohmann::json& bake) {
  if (!bake.is_object()) return "not recorded";
  auto text = [&](const char* key) {
    return bake.contains(key) && bake[key].is_string() ? bake[key].get<std::string>() : "";
  };
  // ", <before><value><after>" for a number the metadata holds, else nothing.
  auto number = [&](const char* key, const std::string& before, const std::string& after) {
    return bake.contains(key) && bake[key].is_number() ? ", " + before + bake[key].dump() + after
                                                       : std::string();
  };
  std::string line = text("generator").empty() ? "a bake" : text("generator");
  if (!text("scene").empty()) line += " of " + text("scene");
  line += ":";
  if (!text("transfer").empty()) line += " " + text("transfer");
  line += number("order", "order ", "");
  line += number("samples_per_vertex", "", " samples per vertex");
  line += number("bounces", "bounces ", "");
  line += number("seed", "seed ", "");
  if (!text("precision").empty()) line += ", " + text("precision");
  return line;
}

std::string describe_compression(const nlohmann::json& record) {
  if (!record.is_object())
    return "not recorded (a version-1 file: prt compress did not store its settings yet)";
  auto number = [&](const char* key) {
    return record.contains(key) && record[key].is_number() ? record[key].get<double>() : -1.0;
  };
  const std::string metric = record.value("metric", std::string("?"));
  char text[400];
  std::snprintf(text, sizeof text,
                "relative RMS error %.4g in the %s metric (what it minimised), %.4g in the plain "
                "matrix metric; --clusters %.0f --vectors %.0f",
                number("metric_relative_rms_error"), metric.c_str(),
                number("matrix_relative_rms_error"), number("clusters"), number("vectors"));
  std::string line = text;
  if (number("target_error") > 0) {
    std::snprintf(text, sizeof text, " (chosen by --target-error %g, --max-vectors %.0f)",
                  number("target_error"), number("max_vectors"));
    line += text;
  }
  std::snprintf(text, sizeof text, ", %.0f iterations, seed %.0f", number("iterations"),
                number("seed"));
  return line + text;
}

// One row per vertex (see cpca_info.h).
void print_csv(const prt::CpcaFile& f) {
  const prt::CpcaTransfer& t = f.cpca;
  const std::size_t K = std::size_t(t.order) * t.order, C = t.channels;
  const bool geometry = f.has_source;
  std::printf(geometry ? "index,x,y,z,nx,ny,nz,tx,ty,tz,tw,material,cluster" : "index,cluster");
  for (std::size_t c = 0; c < C; ++c)
    for (std::size_t i = 0; i < K; ++i)
      for (std::size_t k = 0; k < K; ++k) std::printf(",m%zu_%zu_%zu", c, i, k);
  std::printf("\n");
  std::vector<double> m(t.dimension());
  const prt::GlossyTransferData& d = f.source;
  for (std::size_t v = 0; v < t.vertex_count; ++v) {
    std::printf("%zu", v);
    if (geometry) {
      for (int a = 0; a < 3; ++a) std::printf(",%.9g", double(d.positions[3 * v + a]));
      for (int a = 0; a < 3; ++a) std::printf(",%.9g", double(d.normals[3 * v + a]));
      for (int a = 0; a < 4; ++a) std::printf(",%.9g", double(d.tangents[4 * v + a]));
      std::printf(",%u", d.material_of_vertex[v]);
    }
    std::printf(",%u", t.cluster_of_vertex[v]);
    prt::cpca_reconstruct(t, v, m.data());
    for (double x : m) std::printf(",%.9g", x);
    std::printf("\n");
  }
}

}  // namespace

std::string make_cpca_record(const GlossyCompressRequest& r, const prt::GlossyTransferData& source,
                             const prt::CpcaTransfer& cpca, double matrix_error,
                             double metric_error) {
  nlohmann::json j;
  j["generator"] = "prt compress";
  j["metric"] = r.metric;
  j["matrix_relative_rms_error"] = matrix_error;
  j["metric_relative_rms_error"] = metric_error;
  j["clusters"] = cpca.cluster_count;
  j["vectors"] = cpca.vector_count;
  j["clusters_requested"] = r.clusters;
  j["vectors_requested"] = r.target_error > 0 ? nlohmann::json(nullptr) : nlohmann::json(r.vectors);
  j["target_error"] = r.target_error > 0 ? nlohmann::json(r.target_error) : nlohmann::json(nullptr);
  j["max_vectors"] = r.max_vectors;
  j["iterations"] = r.iterations;
  j["seed"] = r.seed;
  j["source_file"] = std::filesystem::path(r.input).filename().string();
  j["source_bytes"] = file_bytes(r.input);
  j["source_bake"] = parse_object(source.metadata_json);
  return j.dump();
}

void describe_cpca_file(const std::string& path, bool json, bool csv) {
  prt::Result<prt::CpcaFile> read = prt::read_cpca_file_with_source(path);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::CpcaFile& f = read.value();
  if (csv) return print_csv(f);
  const prt::CpcaTransfer& t = f.cpca;
  const nlohmann::json record = parse_object(f.record_json);
  nlohmann::json bake = record.is_object() && record.contains("source_bake")
                            ? record["source_bake"]
                            : parse_object(f.has_source ? f.source.metadata_json : "");
  nlohmann::json j;
  j["file"] = path;
  j["bytes"] = file_bytes(path);
  j["kind"] = "glossy CPCA";
  j["format_version"] = record.is_object() ? prt::kCpcaFileVersion : 1;
  j["order"] = t.order;
  j["channels"] = t.channels;
  j["vertices"] = t.vertex_count;
  j["clusters"] = t.cluster_count;
  j["vectors"] = t.vector_count;
  j["matrix_bytes"] = t.payload_bytes();
  j["matrix_bytes_uncompressed"] = 4 * t.vertex_count * t.dimension();
  char fp[32];
  std::snprintf(fp, sizeof fp, "%016llx", static_cast<unsigned long long>(t.fingerprint));
  j["fingerprint"] = fp;
  j["source_section"] = f.has_source;
  j["compression"] = record;
  j["source_bake"] = bake;
  if (f.has_source) {
    nlohmann::json mats = nlohmann::json::array();
    for (const brdf::Material& m : f.source.materials) mats.push_back(brdf::describe(m));
    j["materials"] = mats;
  }
  if (json) {
    add_run_record_json(j, path);
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  std::printf("file          %s (%llu bytes)\n", path.c_str(), file_bytes(path));
  std::printf("kind          glossy CPCA (clustered PCA of %ux%u transfer matrices)\n",
              t.order * t.order, t.order * t.order);
  std::printf("order         %u\nchannels      %u\nvertices      %llu\n", t.order, t.channels,
              static_cast<unsigned long long>(t.vertex_count));
  std::printf("clusters      %u\nvectors       %u\n", t.cluster_count, t.vector_count);
  std::printf("matrices      %llu bytes (uncompressed %llu)\n",
              static_cast<unsigned long long>(t.payload_bytes()),
              static_cast<unsigned long long>(4 * t.vertex_count * t.dimension()));
  std::printf("compression   %s\n", describe_compression(record).c_str());
  std::printf("source bake   %s", describe_bake(bake).c_str());
  if (record.is_object() && record.contains("source_file"))
    std::printf(" (%s)", record["source_file"].get<std::string>().c_str());
  std::printf("\nfingerprint   %s\n", fp);
  std::printf("source        %s\n", f.has_source ? "geometry, frames and materials included"
                                                 : "none (prt relight cannot read it)");
  if (f.has_source)
    for (const auto& m : j["materials"]) std::printf("  %s\n", m.get<std::string>().c_str());
}

}  // namespace prt::cli
