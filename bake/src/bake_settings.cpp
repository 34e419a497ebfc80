// bake/src/bake_settings.cpp — the canonical settings of a bake (bake_settings.h): one table per
// options struct, every member in it, carried or not, checked against the struct at compile time.
#include "bake/bake_settings.h"

#include <tuple>

#include <nlohmann/json.hpp>

#include "aggregate_fields.h"
#include "bake/obscurance_falloff.h"

namespace prt::bake {
namespace {

template <class S, class M>
struct Carried {
  const char* key;
  M S::*member;
};
template <class S, class M>
struct NotCarried {
  const char* name;
  M S::*member;
  const char* why;
};
template <class S, class M>
constexpr Carried<S, M> carried(const char* key, M S::*member) {
  return {key, member};
}
template <class S, class M>
constexpr NotCarried<S, M> not_carried(const char* name, M S::*member, const char* why) {
  return {name, member, why};
}

constexpr const char* kRun = "a run setting (the output does not depend on it)";
constexpr const char* kSeed = "kept apart by part files (compared on its own)";

// Every member of BakeOptions, in declaration order.
constexpr auto kShTable = std::make_tuple(
    carried("transfer", &BakeOptions::kind), carried("order", &BakeOptions::order),
    carried("samples", &BakeOptions::samples), carried("bounces", &BakeOptions::bounces),
    carried("tolerance", &BakeOptions::bounce_tolerance),
    carried("max_solver_iterations", &BakeOptions::max_solver_iterations),
    not_carried("seed", &BakeOptions::seed, kSeed),
    not_carried("threads", &BakeOptions::threads, kRun),
    not_carried("memory_limit", &BakeOptions::memory_limit, kRun), carried("ao", &BakeOptions::ao),
    carried("bent_normals", &BakeOptions::bent_normals),
    carried("obscurance", &BakeOptions::obscurance), carried("precision", &BakeOptions::precision),
    carried("bounce_precision", &BakeOptions::bounce_precision),
    not_carried("adaptive", &BakeOptions::adaptive, "a sharded bake refuses it (check_shardable)"),
    not_carried("keep_albedo_apart", &BakeOptions::keep_albedo_apart,
                "a sharded bake refuses it (check_shardable)"),
    not_carried("dense_gather", &BakeOptions::dense_gather,
                "a sharded bake refuses it (check_shardable)"),
    not_carried("direct_override", &BakeOptions::direct_override,
                "a function (the subsurface bake's direct term): not data"));
static_assert(std::tuple_size_v<decltype(kShTable)> ==
                  detail::aggregate_member_count<BakeOptions>(),
              "BakeOptions changed: list the new member in kShTable (carried or not, and why)");
static_assert(detail::aggregate_member_count<ObscuranceOptions>() == 2,
              "ObscuranceOptions changed: update its encoding below");

constexpr auto kHaarTable = std::make_tuple(
    carried("transfer", &HaarBakeOptions::transport), carried("cube", &HaarBakeOptions::cube_size),
    carried("supersample", &HaarBakeOptions::supersample),
    carried("compression", &HaarBakeOptions::compression),
    carried("bounces", &HaarBakeOptions::bounces),
    carried("tolerance", &HaarBakeOptions::bounce_tolerance),
    carried("max_solver_iterations", &HaarBakeOptions::max_solver_iterations),
    not_carried("seed", &HaarBakeOptions::seed, kSeed),
    not_carried("threads", &HaarBakeOptions::threads, kRun),
    not_carried("memory_limit", &HaarBakeOptions::memory_limit, kRun));
static_assert(
    std::tuple_size_v<decltype(kHaarTable)> == detail::aggregate_member_count<HaarBakeOptions>(),
    "HaarBakeOptions changed: list the new member in kHaarTable (carried or not, and why)");
static_assert(detail::aggregate_member_count<prt::HaarTransferOptions>() == 3,
              "HaarTransferOptions changed: update its encoding below");

constexpr auto kGlossyTable = std::make_tuple(
    carried("order", &GlossyBakeOptions::order), carried("samples", &GlossyBakeOptions::samples),
    carried("bounces", &GlossyBakeOptions::bounces),
    carried("tolerance", &GlossyBakeOptions::bounce_tolerance),
    not_carried("seed", &GlossyBakeOptions::seed, kSeed),
    not_carried("threads", &GlossyBakeOptions::threads, kRun),
    not_carried("memory_limit", &GlossyBakeOptions::memory_limit, kRun),
    carried("projection", &GlossyBakeOptions::projection),
    carried("precision", &GlossyBakeOptions::precision),
    carried("bounce_cpca_clusters", &GlossyBakeOptions::bounce_cpca_clusters),
    carried("bounce_cpca_vectors", &GlossyBakeOptions::bounce_cpca_vectors),
    carried("exact_hits", &GlossyBakeOptions::exact_hits),
    carried("bounce_precision", &GlossyBakeOptions::bounce_precision));
static_assert(std::tuple_size_v<decltype(kGlossyTable)> ==
                  detail::aggregate_member_count<GlossyBakeOptions>(),
              "GlossyBakeOptions changed: list the new member in kGlossyTable (carried or not)");
static_assert(detail::aggregate_member_count<prt::BrdfProjectionOptions>() == 9,
              "BrdfProjectionOptions changed: update its encoding below");

// Every member of SubsurfaceBakeOptions (the options of bake/subsurface/subsurface_baker.h).
constexpr auto kSubsurfaceTable = std::make_tuple(
    carried("materials", &SubsurfaceBakeOptions::materials),
    not_carried("vertex_material", &SubsurfaceBakeOptions::vertex_material,
                "one value per vertex: shard 0's part stores it, every part hashes it"),
    carried("mm_per_unit", &SubsurfaceBakeOptions::mm_per_unit),
    carried("gather", &SubsurfaceBakeOptions::gather));
static_assert(std::tuple_size_v<decltype(kSubsurfaceTable)> ==
                  detail::aggregate_member_count<SubsurfaceBakeOptions>(),
              "SubsurfaceBakeOptions changed: list the new member in kSubsurfaceTable");
static_assert(detail::aggregate_member_count<SubsurfaceGatherOptions>() == 3,
              "SubsurfaceGatherOptions changed: update its encoding below");
static_assert(detail::aggregate_member_count<subsurface::DipoleCoefficients>() == 3,
              "DipoleCoefficients changed: update its encoding below");

// --- encodings of the members' types ---

nlohmann::json encode(int v) {
  return v;
}
nlohmann::json encode(bool v) {
  return v;
}
nlohmann::json encode(double v) {
  return v;
}
nlohmann::json encode(uint32_t v) {
  return v;
}
nlohmann::json encode(prt::TransferKind v) {
  return transfer_kind_name(v);
}
nlohmann::json encode(prt::Precision v) {
  return v == prt::Precision::F16 ? "f16" : "f32";
}
nlohmann::json encode(const ObscuranceOptions& v) {
  return {{"distance", v.distance}, {"falloff", obscurance_falloff_name(v.falloff)}};
}
nlohmann::json encode(const prt::HaarTransferOptions& v) {
  return {{"relative_threshold", v.relative_threshold},
          {"max_terms_per_vertex", v.max_terms_per_vertex},
          {"quantization_bits", static_cast<int>(v.quantization)}};
}
nlohmann::json encode(const prt::BrdfProjectionOptions& v) {
  return {{"method", static_cast<int>(v.method)},
          {"view_order", v.view_order},
          {"zonal_table", v.zonal_table},
          {"table_size", v.table_size},
          {"table_nodes", v.table_nodes},
          {"inner_theta", v.inner_theta},
          {"inner_phi", v.inner_phi},
          {"outer_theta", v.outer_theta},
          {"outer_phi", v.outer_phi}};
}

nlohmann::json encode(const std::vector<subsurface::DipoleCoefficients>& v) {
  nlohmann::json a = nlohmann::json::array();
  for (const subsurface::DipoleCoefficients& c : v)
    a.push_back({{"sigma_a", c.sigma_a}, {"sigma_s_prime", c.sigma_s_prime}, {"eta", c.eta}});
  return a;
}
nlohmann::json encode(const SubsurfaceGatherOptions& v) {
  return {{"epsilon", v.epsilon}, {"reference", v.reference}, {"energy_clamp", v.energy_clamp}};
}

void decode(const nlohmann::json& j, int& v) {
  v = j.get<int>();
}
void decode(const nlohmann::json& j, bool& v) {
  v = j.get<bool>();
}
void decode(const nlohmann::json& j, double& v) {
  v = j.get<double>();
}
void decode(const nlohmann::json& j, uint32_t& v) {
  v = j.get<uint32_t>();
}
void decode(const nlohmann::json& j, prt::TransferKind& v) {
  const std::string s = j.get<std::string>();
  if (s == "unshadowed")
    v = prt::TransferKind::Unshadowed;
  else if (s == "shadowed")
    v = prt::TransferKind::Shadowed;
  else if (s == "interreflected")
    v = prt::TransferKind::Interreflected;
  else
    throw BakeError("unknown transfer \"" + s + "\"");
}
void decode(const nlohmann::json& j, prt::Precision& v) {
  const std::string s = j.get<std::string>();
  if (s != "f16" && s != "f32") throw BakeError("unknown precision \"" + s + "\"");
  v = s == "f16" ? prt::Precision::F16 : prt::Precision::F32;
}
void decode(const nlohmann::json& j, ObscuranceOptions& v) {
  v.distance = j.at("distance").get<double>();
  const std::optional<ObscuranceFalloff> f =
      parse_obscurance_falloff(j.at("falloff").get<std::string>());
  if (!f) throw BakeError("unknown obscurance falloff");
  v.falloff = *f;
}
void decode(const nlohmann::json& j, prt::HaarTransferOptions& v) {
  v.relative_threshold = j.at("relative_threshold").get<double>();
  v.max_terms_per_vertex = j.at("max_terms_per_vertex").get<int64_t>();
  const int bits = j.at("quantization_bits").get<int>();
  if (bits != 32 && bits != 8 && bits != 16) throw BakeError("unknown Haar quantization");
  v.quantization = static_cast<prt::HaarQuantization>(bits);
}
void decode(const nlohmann::json& j, prt::BrdfProjectionOptions& v) {
  const int method = j.at("method").get<int>();
  if (method < 0 || method > static_cast<int>(prt::BrdfProjectionMethod::kMatrix))
    throw BakeError("unknown BRDF projection method");
  v.method = static_cast<prt::BrdfProjectionMethod>(method);
  v.view_order = j.at("view_order").get<int>();
  v.zonal_table = j.at("zonal_table").get<int>();
  v.table_size = j.at("table_size").get<int>();
  v.table_nodes = j.at("table_nodes").get<int>();
  v.inner_theta = j.at("inner_theta").get<int>();
  v.inner_phi = j.at("inner_phi").get<int>();
  v.outer_theta = j.at("outer_theta").get<int>();
  v.outer_phi = j.at("outer_phi").get<int>();
}

void decode(const nlohmann::json& j, std::vector<subsurface::DipoleCoefficients>& v) {
  v.clear();
  for (const nlohmann::json& m : j) {
    subsurface::DipoleCoefficients c;
    c.sigma_a = m.at("sigma_a").get<subsurface::Rgb>();
    c.sigma_s_prime = m.at("sigma_s_prime").get<subsurface::Rgb>();
    c.eta = m.at("eta").get<double>();
    v.push_back(c);
  }
}
void decode(const nlohmann::json& j, SubsurfaceGatherOptions& v) {
  v.epsilon = j.at("epsilon").get<double>();
  v.reference = j.at("reference").get<bool>();
  v.energy_clamp = j.at("energy_clamp").get<bool>();
}

template <class S, class M>
void write_entry(const S& o, const Carried<S, M>& e, nlohmann::json& j) {
  j[e.key] = encode(o.*e.member);
}
template <class S, class M>
void write_entry(const S&, const NotCarried<S, M>&, nlohmann::json&) {}
template <class S, class M>
void read_entry(S& o, const Carried<S, M>& e, const nlohmann::json& j) {
  decode(j.at(e.key), o.*e.member);
}
template <class S, class M>
void read_entry(S&, const NotCarried<S, M>&, const nlohmann::json&) {}

template <class S, class Table>
std::string write_settings(const S& o, const Table& table, const char* basis) {
  nlohmann::json j;
  j["basis"] = basis;
  std::apply([&](const auto&... e) { (write_entry(o, e, j), ...); }, table);
  return j.dump();
}

template <class S, class Table>
S read_settings(const std::string& text, const Table& table, uint64_t seed,
                const std::string& what) {
  S o;
  if constexpr (requires { o.seed; }) o.seed = seed;
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    std::apply([&](const auto&... e) { (read_entry(o, e, j), ...); }, table);
  } catch (const nlohmann::json::exception& e) {
    throw BakeError(what + ": " + e.what());
  } catch (const BakeError& e) {
    throw BakeError(what + ": " + e.what());
  }
  return o;
}

template <class S, class M>
void list_not_carried(const Carried<S, M>&, std::vector<std::string>&) {}
template <class S, class M>
void list_not_carried(const NotCarried<S, M>& e, std::vector<std::string>& out) {
  out.push_back(std::string(e.name) + ": " + e.why);
}

}  // namespace

std::string sh_bake_settings(const BakeOptions& o) {
  return write_settings(o, kShTable, "sh");
}
BakeOptions sh_options_from_settings(const std::string& s, uint64_t seed, const std::string& what) {
  return read_settings<BakeOptions>(s, kShTable, seed, what);
}
std::string haar_bake_settings(const HaarBakeOptions& o) {
  return write_settings(o, kHaarTable, "haar");
}
HaarBakeOptions haar_options_from_settings(const std::string& s, uint64_t seed,
                                           const std::string& what) {
  return read_settings<HaarBakeOptions>(s, kHaarTable, seed, what);
}
std::string glossy_bake_settings(const GlossyBakeOptions& o) {
  return write_settings(o, kGlossyTable, "glossy");
}
GlossyBakeOptions glossy_options_from_settings(const std::string& s, uint64_t seed,
                                               const std::string& what) {
  return read_settings<GlossyBakeOptions>(s, kGlossyTable, seed, what);
}

std::string subsurface_bake_settings(const SubsurfaceBakeOptions& o) {
  nlohmann::json j;
  std::apply([&](const auto&... e) { (write_entry(o, e, j), ...); }, kSubsurfaceTable);
  return j.dump();
}
SubsurfaceBakeOptions subsurface_options_from_settings(const std::string& s,
                                                       const std::string& what) {
  return read_settings<SubsurfaceBakeOptions>(s, kSubsurfaceTable, 0, what);
}

std::vector<std::string> settings_not_carried() {
  std::vector<std::string> out;
  const auto list = [&out](const auto&... e) { (list_not_carried(e, out), ...); };
  std::apply(list, kShTable);
  std::apply(list, kHaarTable);
  std::apply(list, kGlossyTable);
  std::apply(list, kSubsurfaceTable);
  return out;
}

}  // namespace prt::bake
