// cli/emitter_info.cpp — `prt info` for emitter-response files (emitter_cli.h).
#include <cctype>
#include <cstdio>
#include <filesystem>

#include <nlohmann/json.hpp>

#include "command_registry.h"
#include "emitter_cli.h"
#include "prt/emitters/emitter_responses.h"
#include "run_record.h"

namespace prt::cli {
namespace {

std::string hex64(uint64_t v) {
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
}

void print_csv(const prt::EmitterResponses& d) {
  std::printf("index,x,y,z,nx,ny,nz");
  for (const prt::EmitterInfo& e : d.emitters)
    std::printf(",%s_r,%s_g,%s_b", e.name.c_str(), e.name.c_str(), e.name.c_str());
  std::printf("\n");
  const std::size_t v_count = d.vertex_count();
  for (std::size_t v = 0; v < v_count; ++v) {
    std::printf("%zu", v);
    for (int c = 0; c < 3; ++c) std::printf(",%.9g", double(d.positions[3 * v + c]));
    for (int c = 0; c < 3; ++c) std::printf(",%.9g", double(d.normals[3 * v + c]));
    for (std::size_t e = 0; e < d.emitter_count(); ++e)
      for (int c = 0; c < 3; ++c)
        std::printf(",%.9g", double(d.responses[3 * (e * v_count + v) + c]));
    std::printf("\n");
  }
}

}  // namespace

bool has_responses_extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".prte";
}

bool info_if_emitter_responses(const std::string& path, bool json, bool csv) {
  if (!prt::is_emitter_responses_file(path) && !has_responses_extension(path)) return false;
  prt::Result<prt::EmitterResponses> read = prt::read_emitter_responses(path);
  if (!read.ok()) throw CommandError(read.status().message());
  const prt::EmitterResponses& d = *read;
  if (csv) {
    print_csv(d);
    return true;
  }
  nlohmann::json j;
  j["file"] = path;
  j["kind"] = "emitter responses";
  j["vertices"] = d.vertex_count();
  j["triangles"] = d.triangle_count();
  j["fingerprint"] = hex64(d.fingerprint);
  j["emitters"] = nlohmann::json::array();
  for (const prt::EmitterInfo& e : d.emitters)
    j["emitters"].push_back({{"name", e.name}, {"emission", e.emission}});
  if (json) {
    add_run_record_json(j, path);
    std::printf("%s\n", j.dump(2).c_str());
    return true;
  }
  std::printf("file          %s\nkind          emitter responses (radiosity, per emitter)\n",
              path.c_str());
  std::printf("vertices      %zu\ntriangles     %zu\nfingerprint   %s\nemitters      %zu\n",
              d.vertex_count(), d.triangle_count(), hex64(d.fingerprint).c_str(),
              d.emitter_count());
  for (const prt::EmitterInfo& e : d.emitters)
    std::printf("  %-30s emission %g, %g, %g\n", e.name.c_str(), double(e.emission[0]),
                double(e.emission[1]), double(e.emission[2]));
  return true;
}

}  // namespace prt::cli
