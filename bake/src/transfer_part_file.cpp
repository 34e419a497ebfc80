// bake/src/transfer_part_file.cpp — the SH transfer part file (transfer_part_file.h).
#include "bake/transfer_part_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

#include "numerics/hash.h"
#include "prt/formats/geometry_check.h"
#include "prt/haar/cube_map.h"

namespace prt::bake {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "part files are written in host order");

enum Tag : uint32_t {
  kSettings = 1,
  kScene,
  kPositions,
  kNormals,
  kAlbedo,
  kTriangles,
  kDirect,
  kAo,
  kBent,
  kGatherRows,
  kGatherHits,
  kCounters,
  kSparseLengths,
  kSparseIndex,
  kSparseValues,
  kWavelets,
  kHaarGatherLengths,
  kHaarGatherColumns,
  kHaarGatherWeights,
  kFormFactors
};

template <class T>
prt::PartSection section_of(uint32_t tag, const T* data, std::size_t count) {
  prt::PartSection s;
  s.tag = tag;
  s.bytes.resize(count * sizeof(T));
  if (count) std::memcpy(s.bytes.data(), data, s.bytes.size());
  return s;
}

// A section that refers to the caller's `count` values at `data` (no copy: they must outlive
// the write).
template <class T>
prt::PartSection view_of(uint32_t tag, const T* data, std::size_t count) {
  prt::PartSection s;
  s.tag = tag;
  s.view = count ? static_cast<const void*>(data) : s.bytes.data();
  s.view_size = count * sizeof(T);
  return s;
}

prt::PartSection text_section(uint32_t tag, const std::string& text) {
  return section_of(tag, text.data(), text.size());
}

// The section `tag` as `count` values of T; BakeError when absent or of another size.
template <class T>
std::vector<T> read_array(const prt::PartFile& f, uint32_t tag, uint64_t count,
                          const std::string& name, const char* what) {
  const prt::PartSection* s = f.find(tag);
  const uint64_t bytes = s ? s->bytes.size() : 0;
  if (count > (uint64_t{1} << 40) / sizeof(T) || bytes != count * sizeof(T))
    throw BakeError(name + ": " + what + " section holds " + std::to_string(bytes) +
                    " bytes, expected " + std::to_string(count * sizeof(T)));
  std::vector<T> out(count);
  if (count) std::memcpy(out.data(), s->bytes.data(), bytes);
  return out;
}

std::string read_text(const prt::PartFile& f, uint32_t tag, const std::string& name,
                      const char* what) {
  const prt::PartSection* s = f.find(tag);
  if (!s) throw BakeError(name + ": no " + std::string(what) + " section");
  return std::string(s->bytes.begin(), s->bytes.end());
}

template <class T>
void hash_bytes(numerics::WordHash& h, const std::vector<T>& v) {
  static_assert(sizeof(T) % 4 == 0, "hashed in 32-bit words");
  const std::size_t words = v.size() * sizeof(T) / 4;
  for (std::size_t i = 0; i < words; ++i) {
    uint32_t w;
    std::memcpy(&w, reinterpret_cast<const unsigned char*>(v.data()) + 4 * i, 4);
    h.add_word(w);
  }
}

// What besides the positions decides the bake's output: normals, albedo, triangles, primitives.
std::string scene_inputs_hash(const scene::Scene& scene) {
  numerics::WordHash h;
  h.add_u64(scene.positions.size());
  hash_bytes(h, scene.normals);
  hash_bytes(h, scene.albedo);
  h.add_u64(scene.triangles.size());
  hash_bytes(h, scene.triangles);
  for (const scene::ScenePrimitive& p : scene.primitives) {
    h.add_u64(p.first_vertex);
    h.add_u64(p.vertex_count);
    for (unsigned char c : p.name) h.add_word(c);
  }
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h.finish()));
  return text;
}

prt::TransferKind kind_named(const std::string& kind) {
  return kind == "unshadowed"       ? prt::TransferKind::Unshadowed
         : kind == "interreflected" ? prt::TransferKind::Interreflected
                                    : prt::TransferKind::Shadowed;
}

nlohmann::json settings_of(const BakeOptions& o) {
  nlohmann::json s;
  s["basis"] = "sh";
  s["transfer"] = transfer_kind_name(o.kind);
  s["order"] = o.order;
  s["samples"] = o.samples;
  s["bounces"] = o.bounces;
  s["tolerance"] = o.bounce_tolerance;
  s["max_solver_iterations"] = o.max_solver_iterations;
  s["ao"] = o.ao;
  s["bent_normals"] = o.bent_normals;
  s["precision"] = o.precision == prt::Precision::F16 ? "f16" : "f32";
  return s;
}

BakeOptions options_of(const nlohmann::json& s, uint64_t seed) {
  BakeOptions o;
  o.kind = kind_named(s.at("transfer").get<std::string>());
  o.order = s.at("order").get<int>();
  o.samples = s.at("samples").get<int>();
  o.bounces = s.at("bounces").get<int>();
  o.bounce_tolerance = s.at("tolerance").get<double>();
  o.max_solver_iterations = s.at("max_solver_iterations").get<int>();
  o.ao = s.at("ao").get<bool>();
  o.bent_normals = s.at("bent_normals").get<bool>();
  o.precision =
      s.at("precision").get<std::string>() == "f16" ? prt::Precision::F16 : prt::Precision::F32;
  o.seed = seed;
  return o;
}

nlohmann::json haar_settings_of(const HaarBakeOptions& o) {
  nlohmann::json s;
  s["basis"] = "haar";
  s["transfer"] = transfer_kind_name(o.transport);
  s["cube"] = o.cube_size;
  s["supersample"] = o.supersample;
  s["relative_threshold"] = o.compression.relative_threshold;
  s["max_terms_per_vertex"] = o.compression.max_terms_per_vertex;
  s["quantization_bits"] = static_cast<int>(o.compression.quantization);
  s["bounces"] = o.bounces;
  s["tolerance"] = o.bounce_tolerance;
  s["max_solver_iterations"] = o.max_solver_iterations;
  return s;
}

HaarBakeOptions haar_options_of(const nlohmann::json& s, uint64_t seed) {
  HaarBakeOptions o;
  o.transport = kind_named(s.at("transfer").get<std::string>());
  o.cube_size = s.at("cube").get<int>();
  o.supersample = s.at("supersample").get<int>();
  o.compression.relative_threshold = s.at("relative_threshold").get<double>();
  o.compression.max_terms_per_vertex = s.at("max_terms_per_vertex").get<int64_t>();
  const int bits = s.at("quantization_bits").get<int>();
  o.compression.quantization = bits == 8    ? prt::HaarQuantization::Bits8
                               : bits == 16 ? prt::HaarQuantization::Bits16
                                            : prt::HaarQuantization::Float32;
  o.bounces = s.at("bounces").get<int>();
  o.bounce_tolerance = s.at("tolerance").get<double>();
  o.max_solver_iterations = s.at("max_solver_iterations").get<int>();
  o.seed = seed;
  return o;
}

void add_scene_sections(const scene::Scene& scene, prt::PartFile& f) {
  nlohmann::json j;
  j["source_path"] = scene.source_path;
  j["skipped_degenerate_triangles"] = scene.skipped_degenerate_triangles;
  j["triangles"] = scene.triangles.size();
  nlohmann::json prims = nlohmann::json::array();
  for (const scene::ScenePrimitive& p : scene.primitives)
    prims.push_back(
        {{"name", p.name}, {"first_vertex", p.first_vertex}, {"vertex_count", p.vertex_count}});
  j["primitives"] = prims;
  f.sections.push_back(text_section(kScene, j.dump()));
  f.sections.push_back(view_of(kPositions, &scene.positions[0].x, 3 * scene.positions.size()));
  f.sections.push_back(view_of(kNormals, &scene.normals[0].x, 3 * scene.normals.size()));
  f.sections.push_back(view_of(kAlbedo, &scene.albedo[0].x, 3 * scene.albedo.size()));
  f.sections.push_back(view_of(kTriangles,
                               scene.triangles.empty() ? nullptr : &scene.triangles[0].x,
                               3 * scene.triangles.size()));
}

scene::Scene decode_scene(const prt::PartFile& f, const std::string& name) {
  scene::Scene scene;
  const uint64_t V = f.total_rows;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_text(f, kScene, name, "scene"));
    scene.source_path = j.at("source_path").get<std::string>();
    scene.skipped_degenerate_triangles = j.at("skipped_degenerate_triangles").get<std::size_t>();
    const uint64_t T = j.at("triangles").get<uint64_t>();
    const auto vec3s = [&](uint32_t tag, const char* what) {
      const std::vector<float> raw = read_array<float>(f, tag, 3 * V, name, what);
      std::vector<glm::vec3> out(V);
      for (uint64_t v = 0; v < V; ++v) out[v] = {raw[3 * v], raw[3 * v + 1], raw[3 * v + 2]};
      return out;
    };
    scene.positions = vec3s(kPositions, "positions");
    scene.normals = vec3s(kNormals, "normals");
    scene.albedo = vec3s(kAlbedo, "albedo");
    const std::vector<uint32_t> tris =
        read_array<uint32_t>(f, kTriangles, 3 * T, name, "triangles");
    scene.triangles.resize(T);
    for (uint64_t t = 0; t < T; ++t) {
      scene.triangles[t] = {tris[3 * t], tris[3 * t + 1], tris[3 * t + 2]};
      if (tris[3 * t] >= V || tris[3 * t + 1] >= V || tris[3 * t + 2] >= V)
        throw BakeError(name + ": a triangle index is out of range");
    }
    for (const nlohmann::json& p : j.at("primitives")) {
      scene::ScenePrimitive prim;
      prim.name = p.at("name").get<std::string>();
      prim.first_vertex = p.at("first_vertex").get<uint32_t>();
      prim.vertex_count = p.at("vertex_count").get<uint32_t>();
      if (prim.first_vertex > V || prim.vertex_count > V - prim.first_vertex)
        throw BakeError(name + ": a primitive's vertices are out of range");
      scene.primitives.push_back(std::move(prim));
    }
  } catch (const nlohmann::json::exception& e) {
    throw BakeError(name + ": scene section: " + e.what());
  }
  if (prt::geometry_fingerprint(&scene.positions[0].x, V) != f.fingerprint)
    throw BakeError(name + ": the scene's positions do not match the header's fingerprint");
  return scene;
}

}  // namespace

namespace {

// A part's header, settings section and (shard 0) scene sections.
prt::PartFile part_with_settings(prt::PartKind kind, ShardSpec shard, RowRange rows,
                                 const scene::Scene& scene, const nlohmann::json& settings,
                                 uint64_t seed, const std::string& prt_version) {
  prt::PartFile f;
  f.kind = kind;
  f.index = shard.index;
  f.count = shard.count;
  std::vector<float> xyz(3 * scene.positions.size());
  for (std::size_t v = 0; v < scene.positions.size(); ++v)
    for (int a = 0; a < 3; ++a) xyz[3 * v + a] = scene.positions[v][a];
  f.fingerprint = prt::geometry_fingerprint(xyz.data(), scene.positions.size());
  f.total_rows = scene.positions.size();
  f.first_row = rows.first;
  f.row_count = rows.size();
  nlohmann::json j;
  j["generator"] = "prt bake --shard";
  j["prt_version"] = prt_version;
  j["seed"] = seed;
  j["settings"] = settings;
  j["scene_inputs"] = scene_inputs_hash(scene);
  f.sections.push_back(text_section(kSettings, j.dump()));
  if (shard.index == 0) add_scene_sections(scene, f);
  return f;
}

prt::PartSection counters_section(uint64_t rays, uint64_t back_face_hits, double offset) {
  uint64_t counters[3] = {rays, back_face_hits, 0};
  std::memcpy(&counters[2], &offset, sizeof(double));
  return section_of(kCounters, counters, 3);
}

void decode_haar(const prt::PartFile& f, const std::string& name, TransferPartFile& out) {
  const HaarBakeOptions& o = out.haar_options;
  if (!prt::is_valid_cube_size(o.cube_size) || o.supersample < 1 ||
      o.supersample > kMaxHaarSupersample)
    throw BakeError(name + ": settings out of range");
  HaarPart& p = out.haar_part;
  p.shard = {f.index, f.count};
  p.vertices = f.total_rows;
  p.rows = {f.first_row, f.first_row + f.row_count};
  const uint64_t n = f.row_count, W = uint64_t{6} * o.cube_size * o.cube_size;
  const bool interreflect = o.transport == prt::TransferKind::Interreflected;
  p.sparse_lengths =
      read_array<uint32_t>(f, kSparseLengths, interreflect ? 0 : n, name, "sparse lengths");
  uint64_t entries = 0;
  for (uint32_t len : p.sparse_lengths) entries += len;
  p.sparse_index = read_array<uint32_t>(f, kSparseIndex, entries, name, "sparse index");
  const prt::PartSection* values = f.find(kSparseValues);
  p.channels = entries > 0 && values ? static_cast<int>(values->bytes.size() / 4 / entries) : 1;
  if (interreflect) {
    const prt::PartSection* w = f.find(kWavelets);
    p.channels = n > 0 && w ? static_cast<int>(w->bytes.size() / 4 / (n * W)) : 1;
  }
  if (p.channels != 1 && p.channels != 3) throw BakeError(name + ": bad channel count");
  p.sparse_values =
      read_array<float>(f, kSparseValues, entries * p.channels, name, "sparse values");
  p.wavelets =
      read_array<float>(f, kWavelets, interreflect ? n * W * p.channels : 0, name, "wavelets");
  p.gather_lengths =
      read_array<uint32_t>(f, kHaarGatherLengths, interreflect ? n : 0, name, "gather lengths");
  uint64_t gathered = 0;
  for (uint32_t len : p.gather_lengths) gathered += len;
  p.gather_columns = read_array<uint32_t>(f, kHaarGatherColumns, gathered, name, "gather columns");
  p.gather_weights = read_array<float>(f, kHaarGatherWeights, gathered, name, "gather weights");
  p.rays = read_array<uint64_t>(f, kCounters, 3, name, "counters")[0];
  out.part.shard = p.shard;
  out.part.vertices = p.vertices;
  out.part.rows = p.rows;
}

}  // namespace

prt::PartFile encode_transfer_part(const TransferPart& part, const scene::Scene& scene,
                                   const BakeOptions& options, const std::string& prt_version) {
  prt::PartFile f = part_with_settings(prt::PartKind::ShTransfer, part.shard, part.rows, scene,
                                       settings_of(options), options.seed, prt_version);
  f.sections.push_back(view_of(kDirect, part.direct.data(), part.direct.size()));
  f.sections.push_back(view_of(kAo, part.ao.data(), part.ao.size()));
  f.sections.push_back(view_of(kBent, part.bent.data(), part.bent.size()));
  f.sections.push_back(view_of(kGatherRows, part.gather_rows.data(), part.gather_rows.size()));
  f.sections.push_back(view_of(kGatherHits, part.gather_hits.data(), part.gather_hits.size()));
  f.sections.push_back(counters_section(part.rays, part.back_face_hits, part.ray_offset_max));
  return f;
}

prt::PartFile encode_haar_part(const HaarPart& part, const scene::Scene& scene,
                               const HaarBakeOptions& options, const std::string& prt_version) {
  prt::PartFile f = part_with_settings(prt::PartKind::HaarTransfer, part.shard, part.rows, scene,
                                       haar_settings_of(options), options.seed, prt_version);
  f.sections.push_back(
      view_of(kSparseLengths, part.sparse_lengths.data(), part.sparse_lengths.size()));
  f.sections.push_back(view_of(kSparseIndex, part.sparse_index.data(), part.sparse_index.size()));
  f.sections.push_back(
      view_of(kSparseValues, part.sparse_values.data(), part.sparse_values.size()));
  f.sections.push_back(view_of(kWavelets, part.wavelets.data(), part.wavelets.size()));
  f.sections.push_back(
      view_of(kHaarGatherLengths, part.gather_lengths.data(), part.gather_lengths.size()));
  f.sections.push_back(
      view_of(kHaarGatherColumns, part.gather_columns.data(), part.gather_columns.size()));
  f.sections.push_back(
      view_of(kHaarGatherWeights, part.gather_weights.data(), part.gather_weights.size()));
  f.sections.push_back(counters_section(part.rays, 0, 0.0));
  return f;
}

prt::PartFile encode_form_factor_part(ShardSpec shard, uint64_t key, uint64_t patches,
                                      uint64_t first, const std::vector<float>& rows,
                                      const std::string& settings, uint64_t seed,
                                      const std::string& prt_version) {
  prt::PartFile f;
  f.kind = prt::PartKind::FormFactorRows;
  f.index = shard.index;
  f.count = shard.count;
  f.fingerprint = key;
  f.total_rows = patches;
  f.first_row = first;
  f.row_count = patches ? rows.size() / patches : 0;
  nlohmann::json j;
  j["generator"] = "prt radiosity --shard";
  j["prt_version"] = prt_version;
  j["seed"] = seed;
  nlohmann::json s = nlohmann::json::parse(settings);
  s["basis"] = "form factors";
  j["settings"] = s;
  char text[24];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(key));
  j["scene_inputs"] = text;
  f.sections.push_back(text_section(kSettings, j.dump()));
  f.sections.push_back(view_of(kFormFactors, rows.data(), rows.size()));
  return f;
}

TransferPartFile decode_transfer_part(const prt::PartFile& f, const std::string& name) {
  TransferPartFile out;
  out.name = name;
  out.fingerprint = f.fingerprint;
  out.haar = f.kind == prt::PartKind::HaarTransfer;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_text(f, kSettings, name, "settings"));
    out.prt_version = j.at("prt_version").get<std::string>();
    out.seed = j.at("seed").get<uint64_t>();
    out.settings = j.at("settings").dump();
    out.scene_inputs = j.at("scene_inputs").get<std::string>();
    out.form_factors = f.kind == prt::PartKind::FormFactorRows;
    if (out.haar)
      out.haar_options = haar_options_of(j.at("settings"), out.seed);
    else if (!out.form_factors)
      out.options = options_of(j.at("settings"), out.seed);
  } catch (const nlohmann::json::exception& e) {
    throw BakeError(name + ": settings section: " + e.what());
  }
  if (out.form_factors) {
    out.key = f.fingerprint;
    out.form_factor_rows =
        read_array<float>(f, kFormFactors, f.row_count * f.total_rows, name, "form factors");
    out.part.shard = {f.index, f.count};
    out.part.vertices = f.total_rows;
    out.part.rows = {f.first_row, f.first_row + f.row_count};
    return out;
  }
  if (out.haar) {
    if (f.index == 0) out.scene = decode_scene(f, name);
    decode_haar(f, name, out);
    return out;
  }
  const BakeOptions& o = out.options;
  if (o.order < 1 || o.order > kMaxBakeOrder || o.samples < 1 || o.samples > kMaxBakeSamples)
    throw BakeError(name + ": settings out of range");
  if (f.index == 0) out.scene = decode_scene(f, name);
  TransferPart& p = out.part;
  p.shard = {f.index, f.count};
  p.vertices = f.total_rows;
  p.rows = {f.first_row, f.first_row + f.row_count};
  p.coefficients = o.order * o.order;
  const uint64_t n = f.row_count, K = static_cast<uint64_t>(p.coefficients);
  const bool need_sh = o.kind != prt::TransferKind::Unshadowed;
  const bool interreflect = o.kind == prt::TransferKind::Interreflected;
  p.direct = read_array<double>(f, kDirect, need_sh ? n * K : 0, name, "direct transfer");
  p.ao = read_array<float>(f, kAo, o.ao ? n : 0, name, "ao");
  p.bent = read_array<float>(f, kBent, o.bent_normals ? 3 * n : 0, name, "bent normal");
  p.gather_rows = read_array<uint32_t>(f, kGatherRows, interreflect ? n : 0, name, "gather rows");
  uint64_t hits = 0;
  for (uint32_t len : p.gather_rows) hits += len;
  p.gather_hits = read_array<CompactHit>(f, kGatherHits, hits, name, "gather hits");
  const std::vector<uint64_t> counters = read_array<uint64_t>(f, kCounters, 3, name, "counters");
  p.rays = counters[0];
  p.back_face_hits = counters[1];
  std::memcpy(&p.ray_offset_max, &counters[2], sizeof(double));
  return out;
}

namespace {

std::string shard_name(uint32_t index, uint32_t count) {
  return std::to_string(index) + "/" + std::to_string(count);
}

// The first setting in which `a` differs from `b`: "samples 64 here, 32 in REF".
std::string settings_difference(const std::string& a, const std::string& b,
                                const std::string& ref) {
  const nlohmann::json ja = nlohmann::json::parse(a), jb = nlohmann::json::parse(b);
  for (auto it = ja.begin(); it != ja.end(); ++it)
    if (!jb.contains(it.key()) || jb.at(it.key()) != it.value())
      return it.key() + " " + it.value().dump() + " here, " +
             (jb.contains(it.key()) ? jb.at(it.key()).dump() : "none") + " in " + ref;
  return "other settings than " + ref;
}

// One line saying how `p` differs from the reference part `r` (empty: it does not).
std::string difference(const TransferPartFile& p, const TransferPartFile& r) {
  if (p.prt_version != r.prt_version)
    return p.name + ": written by prt " + p.prt_version + ", " + r.name + " by prt " +
           r.prt_version + " (the parts of one bake must come from one prt version)";
  // A form-factor part's key covers its options too: name the settings first.
  if (p.form_factors && p.settings != r.settings)
    return p.name +
           ": baked with other settings: " + settings_difference(p.settings, r.settings, r.name);
  if (p.fingerprint != r.fingerprint || p.scene_inputs != r.scene_inputs ||
      p.part.vertices != r.part.vertices)
    return p.name + ": a part of another scene than " + r.name + " (" +
           (p.fingerprint != r.fingerprint ? "other positions"
                                           : "other normals, albedo or triangles") +
           ")";
  if (p.seed != r.seed)
    return p.name + ": baked with --seed " + std::to_string(p.seed) + ", " + r.name +
           " with --seed " + std::to_string(r.seed);
  if (p.settings != r.settings)
    return p.name +
           ": baked with other settings: " + settings_difference(p.settings, r.settings, r.name);
  if (p.part.shard.count != r.part.shard.count)
    return p.name + ": shard " + shard_name(p.part.shard.index, p.part.shard.count) +
           " of another split (" + r.name + " is one of " + std::to_string(r.part.shard.count) +
           " shards)";
  return {};
}

}  // namespace

std::vector<const TransferPartFile*> check_parts_fit(const std::vector<TransferPartFile>& parts) {
  if (parts.empty()) throw BakeError("no parts to merge");
  // The reference: the part whose (version, scene, seed, settings, count) most parts share.
  std::size_t ref = 0, best = 0;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    std::size_t agree = 0;
    for (const TransferPartFile& q : parts) agree += difference(q, parts[i]).empty();
    if (agree > best) best = agree, ref = i;
  }
  const TransferPartFile& r = parts[ref];
  for (const TransferPartFile& p : parts) {
    const std::string why = difference(p, r);
    if (!why.empty()) throw BakeError(why);
  }
  const uint32_t N = r.part.shard.count;
  std::vector<const TransferPartFile*> ordered(N, nullptr);
  for (const TransferPartFile& p : parts) {
    const TransferPart& t = p.part;
    const RowRange want = shard_rows(t.vertices, t.shard);
    if (t.rows.first != want.first || t.rows.end != want.end)
      throw BakeError(p.name + ": rows " + std::to_string(t.rows.first) + ".." +
                      std::to_string(t.rows.end) + " are not those of shard " +
                      shard_name(t.shard.index, N));
    if (ordered[t.shard.index])
      throw BakeError(p.name + ": shard " + shard_name(t.shard.index, N) + " given twice (also " +
                      ordered[t.shard.index]->name + ")");
    ordered[t.shard.index] = &p;
  }
  for (uint32_t i = 0; i < N; ++i)
    if (!ordered[i]) {
      const RowRange rows = shard_rows(r.part.vertices, {i, N});
      throw BakeError("shard " + shard_name(i, N) + " is missing (rows " +
                      std::to_string(rows.first) + ".." + std::to_string(rows.end) + " of " +
                      std::to_string(r.part.vertices) + "): no part given holds it");
    }
  if (!ordered[0]->scene) return ordered;  // form-factor parts carry no scene
  const uint64_t T = ordered[0]->scene->triangles.size();
  for (const TransferPartFile* p : ordered)
    for (const CompactHit& h : p->part.gather_hits)
      if (h.triangle >= T) throw BakeError(p->name + ": a gather hit names no triangle");
  return ordered;
}

}  // namespace prt::bake
