// bake/src/transfer_part_file.cpp — the SH transfer part file (transfer_part_file.h).
#include "bake/transfer_part_file.h"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include <nlohmann/json.hpp>

#include "aggregate_fields.h"
#include "bake/bake_settings.h"
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
  kFormFactors,
  kGlossyDirect,
  kGlossyHitCounts,
  kGlossyHits,
  kGlossyTangents,
  kGlossyMaterialOfVertex,
  kGlossyMaterials,
  kSubsurfaceMaterialOfVertex
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

// The section `tag` as `count` values of T at their place in the file's mapping; BakeError when
// absent or of another size. (Sections are 16-byte aligned in the file, the mapping on a page.)
template <class T>
const T* section_values(const prt::PartFile& f, uint32_t tag, uint64_t count,
                        const std::string& name, const char* what) {
  const prt::PartSection* s = f.find(tag);
  const uint64_t bytes = s ? s->size() : 0;
  if (count > (uint64_t{1} << 40) / sizeof(T) || bytes != count * sizeof(T))
    throw BakeError(name + ": " + what + " section holds " + std::to_string(bytes) +
                    " bytes, expected " + std::to_string(count * sizeof(T)));
  return count ? reinterpret_cast<const T*>(s->data()) : nullptr;
}

// a · b values, computed without wrapping: BakeError "NAME: WHAT section: …" when the product
// passes what section_values accepts (2⁴⁰ bytes), so that counts a hostile header gives (rows,
// vertices, triangles) cannot wrap to the size of a small section.
uint64_t count_of(uint64_t a, uint64_t b, const std::string& name, const char* what) {
  constexpr uint64_t kLimit = uint64_t{1} << 40;
  if (a != 0 && b > kLimit / a)
    throw BakeError(name + ": " + what + " section: " + std::to_string(a) + " x " +
                    std::to_string(b) + " values, more than a part holds");
  return a * b;
}

// The same values copied into an array of their own (no zero-filling first).
template <class T>
std::vector<T> read_array(const prt::PartFile& f, uint32_t tag, uint64_t count,
                          const std::string& name, const char* what) {
  const T* p = section_values<T>(f, tag, count, name, what);
  return p ? std::vector<T>(p, p + count) : std::vector<T>();
}

std::string read_text(const prt::PartFile& f, uint32_t tag, const std::string& name,
                      const char* what) {
  const prt::PartSection* s = f.find(tag);
  if (!s) throw BakeError(name + ": no " + std::string(what) + " section");
  return std::string(reinterpret_cast<const char*>(s->data()), s->size());
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
      const std::vector<float> raw =
          read_array<float>(f, tag, count_of(3, V, name, what), name, what);
      std::vector<glm::vec3> out(V);
      for (uint64_t v = 0; v < V; ++v) out[v] = {raw[3 * v], raw[3 * v + 1], raw[3 * v + 2]};
      return out;
    };
    scene.positions = vec3s(kPositions, "positions");
    scene.normals = vec3s(kNormals, "normals");
    scene.albedo = vec3s(kAlbedo, "albedo");
    const std::vector<uint32_t> tris =
        read_array<uint32_t>(f, kTriangles, count_of(3, T, name, "triangles"), name, "triangles");
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
  const float* xyz = scene.positions.empty() ? nullptr : &scene.positions[0].x;
  if (prt::geometry_fingerprint(xyz, V) != f.fingerprint)
    throw BakeError(name + ": the scene's positions do not match the header's fingerprint");
  return scene;
}

static_assert(detail::aggregate_member_count<brdf::Material>() == 12,
              "brdf::Material changed: carry the new member in glossy parts' materials");

nlohmann::json rgb_json(const brdf::Rgb& c) {
  return {c.r, c.g, c.b};
}
brdf::Rgb rgb_of(const nlohmann::json& j) {
  return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()};
}

// Every field of the materials (doubles round-trip exactly through nlohmann's shortest form).
std::string materials_json(const std::vector<brdf::Material>& materials) {
  nlohmann::json a = nlohmann::json::array();
  for (const brdf::Material& m : materials)
    a.push_back({{"model", static_cast<int>(m.model)},
                 {"diffuse", rgb_json(m.diffuse)},
                 {"specular", rgb_json(m.specular)},
                 {"exponent", m.exponent},
                 {"alpha_x", m.alpha_x},
                 {"alpha_y", m.alpha_y},
                 {"ward_form", static_cast<int>(m.ward_form)},
                 {"distribution", static_cast<int>(m.distribution)},
                 {"fresnel", static_cast<int>(m.fresnel)},
                 {"eta", m.eta},
                 {"metallic", m.metallic},
                 {"merl_path", m.merl_path}});
  return a.dump();
}

std::vector<brdf::Material> materials_of(const std::string& text, const std::string& name) {
  std::vector<brdf::Material> out;
  try {
    for (const nlohmann::json& j : nlohmann::json::parse(text)) {
      brdf::Material m;
      const int model = j.at("model").get<int>(), ward = j.at("ward_form").get<int>(),
                distribution = j.at("distribution").get<int>(),
                fresnel = j.at("fresnel").get<int>();
      if (model < 0 || model > static_cast<int>(brdf::MaterialModel::kGltf) || ward < 0 ||
          ward > static_cast<int>(brdf::WardForm::kNormalized) || distribution < 0 ||
          distribution > static_cast<int>(brdf::NormalDistribution::kBeckmann) || fresnel < 0 ||
          fresnel > static_cast<int>(brdf::FresnelMode::kDielectric))
        throw BakeError(name + ": materials section: an unknown enumerator");
      m.model = static_cast<brdf::MaterialModel>(model);
      m.diffuse = rgb_of(j.at("diffuse"));
      m.specular = rgb_of(j.at("specular"));
      m.exponent = j.at("exponent").get<double>();
      m.alpha_x = j.at("alpha_x").get<double>();
      m.alpha_y = j.at("alpha_y").get<double>();
      m.ward_form = static_cast<brdf::WardForm>(ward);
      m.distribution = static_cast<brdf::NormalDistribution>(distribution);
      m.fresnel = static_cast<brdf::FresnelMode>(fresnel);
      m.eta = j.at("eta").get<double>();
      m.metallic = j.at("metallic").get<double>();
      m.merl_path = j.at("merl_path").get<std::string>();
      out.push_back(std::move(m));
    }
  } catch (const nlohmann::json::exception& e) {
    throw BakeError(name + ": materials section: " + e.what());
  }
  return out;
}

// "/" and the hash of what a glossy bake derives from the scene besides its geometry.
std::string glossy_inputs_hash(const GlossyInputs& in) {
  numerics::WordHash h;
  h.add_u64(in.tangents.size());
  hash_bytes(h, in.tangents);
  hash_bytes(h, in.material_of_vertex);
  for (unsigned char c : materials_json(in.materials)) h.add_word(c);
  char text[24];
  std::snprintf(text, sizeof text, "/%016llx", static_cast<unsigned long long>(h.finish()));
  return text;
}

GlossyInputs decode_glossy_inputs(const prt::PartFile& f, const std::string& name) {
  const uint64_t V = f.total_rows;
  GlossyInputs in;
  const std::vector<float> t =
      read_array<float>(f, kGlossyTangents, count_of(4, V, name, "tangents"), name, "tangents");
  in.tangents.resize(V);
  for (uint64_t v = 0; v < V; ++v)
    in.tangents[v] = {t[4 * v], t[4 * v + 1], t[4 * v + 2], t[4 * v + 3]};
  in.material_of_vertex =
      read_array<uint32_t>(f, kGlossyMaterialOfVertex, V, name, "material of each vertex");
  in.materials = materials_of(read_text(f, kGlossyMaterials, name, "materials"), name);
  for (uint32_t m : in.material_of_vertex)
    if (m >= in.materials.size()) throw BakeError(name + ": a vertex names no material");
  return in;
}

// The material of each vertex of a subsurface bake (empty in the options: every vertex 0).
std::vector<int32_t> subsurface_materials_of_vertices(const SubsurfaceBakeOptions& ss,
                                                      std::size_t vertices) {
  return ss.vertex_material.empty() ? std::vector<int32_t>(vertices, 0) : ss.vertex_material;
}

// "/s" and the hash of the subsurface material of every vertex.
std::string subsurface_inputs_hash(const std::vector<int32_t>& material) {
  numerics::WordHash h;
  h.add_u64(material.size());
  hash_bytes(h, material);
  char text[24];
  std::snprintf(text, sizeof text, "/s%016llx", static_cast<unsigned long long>(h.finish()));
  return text;
}

// The shape of a settings object: its keys (nested objects' too) and their JSON types, in order.
void hash_shape(numerics::WordHash& h, const nlohmann::json& j) {
  h.add_word(static_cast<uint32_t>(j.type()));
  if (!j.is_object()) return;
  for (auto it = j.begin(); it != j.end(); ++it) {
    for (unsigned char c : it.key()) h.add_word(c);
    hash_shape(h, it.value());
  }
}

}  // namespace

namespace {

// A part's header, settings section and (shard 0) scene sections.
prt::PartFile part_with_settings(prt::PartKind kind, ShardSpec shard, RowRange rows,
                                 const scene::Scene& scene, const nlohmann::json& settings,
                                 uint64_t seed, const std::string& prt_version,
                                 const std::string& more_inputs = {}) {
  prt::PartFile f;
  f.layout = part_layout_id();
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
  j["scene_inputs"] = scene_inputs_hash(scene) + more_inputs;
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
  const uint64_t texels = interreflect ? count_of(n, W, name, "wavelets") : 0;
  // The large arrays stay where the mapping has them, as an SH part's do (the merge copies them
  // once and releases each part's pages); out.mapping keeps them.
  HaarPart::Mapped& m = p.view;
  p.mapped = true;
  p.sparse_lengths =
      read_array<uint32_t>(f, kSparseLengths, interreflect ? 0 : n, name, "sparse lengths");
  for (uint32_t len : p.sparse_lengths) m.entries += len;
  m.sparse_index = section_values<uint32_t>(f, kSparseIndex, m.entries, name, "sparse index");
  const prt::PartSection* values = f.find(kSparseValues);
  p.channels = m.entries > 0 && values ? static_cast<int>(values->size() / 4 / m.entries) : 1;
  if (interreflect) {
    const prt::PartSection* w = f.find(kWavelets);
    p.channels = texels > 0 && w ? static_cast<int>(w->size() / 4 / texels) : 1;
  }
  if (p.channels != 1 && p.channels != 3) throw BakeError(name + ": bad channel count");
  m.sparse_values =
      section_values<float>(f, kSparseValues, m.entries * p.channels, name, "sparse values");
  m.texels = count_of(texels, p.channels, name, "wavelets");
  m.wavelets = section_values<float>(f, kWavelets, m.texels, name, "wavelets");
  p.gather_lengths =
      read_array<uint32_t>(f, kHaarGatherLengths, interreflect ? n : 0, name, "gather lengths");
  for (uint32_t len : p.gather_lengths) m.gathered += len;
  m.gather_columns =
      section_values<uint32_t>(f, kHaarGatherColumns, m.gathered, name, "gather columns");
  m.gather_weights =
      section_values<float>(f, kHaarGatherWeights, m.gathered, name, "gather weights");
  out.mapping = f.mapping;
  p.rays = read_array<uint64_t>(f, kCounters, 3, name, "counters")[0];
  out.part.shard = p.shard;
  out.part.vertices = p.vertices;
  out.part.rows = p.rows;
}

void decode_glossy(const prt::PartFile& f, const std::string& name, TransferPartFile& out) {
  const GlossyBakeOptions& o = out.glossy_options;
  if (o.order < 1 || o.order > kMaxGlossyBakeOrder || o.samples < 1 || o.samples > kMaxBakeSamples)
    throw BakeError(name + ": settings out of range");
  GlossyPart& p = out.glossy_part;
  p.shard = {f.index, f.count};
  p.vertices = f.total_rows;
  p.rows = {f.first_row, f.first_row + f.row_count};
  p.order = o.order;
  const uint64_t n = f.row_count, KK = uint64_t(o.order) * o.order * o.order * o.order;
  const bool interreflect = o.bounces != 0;
  // The two large arrays stay where the mapping has them, as an SH part's do (the merge copies
  // them once and releases each part's pages); out.mapping keeps them.
  p.direct_count = count_of(n, KK, name, "direct matrices");
  p.direct_view = section_values<float>(f, kGlossyDirect, p.direct_count, name, "direct matrices");
  p.hit_counts =
      read_array<uint32_t>(f, kGlossyHitCounts, interreflect ? n : 0, name, "hit counts");
  uint64_t hits = 0;
  for (uint32_t c : p.hit_counts) hits += c;
  p.hit_count = hits;
  p.hits_view = section_values<GlossyHitRecord>(f, kGlossyHits, hits, name, "hits");
  out.mapping = f.mapping;
  const std::vector<uint64_t> counters = read_array<uint64_t>(f, kCounters, 3, name, "counters");
  p.rays = counters[0];
  p.back_face_hits = counters[1];
  if (f.index == 0) out.glossy_inputs = decode_glossy_inputs(f, name);
  out.part.shard = p.shard;
  out.part.vertices = p.vertices;
  out.part.rows = p.rows;
}

}  // namespace

prt::PartFile encode_glossy_part(const GlossyPart& part, const scene::Scene& scene,
                                 const GlossyInputs& inputs, const GlossyBakeOptions& options,
                                 const std::string& prt_version) {
  prt::PartFile f = part_with_settings(prt::PartKind::GlossyTransfer, part.shard, part.rows, scene,
                                       nlohmann::json::parse(glossy_bake_settings(options)),
                                       options.seed, prt_version, glossy_inputs_hash(inputs));
  f.sections.push_back(view_of(kGlossyDirect, part.direct.data(), part.direct.size()));
  f.sections.push_back(view_of(kGlossyHitCounts, part.hit_counts.data(), part.hit_counts.size()));
  f.sections.push_back(view_of(kGlossyHits, part.hits.data(), part.hits.size()));
  f.sections.push_back(counters_section(part.rays, part.back_face_hits, 0.0));
  if (part.shard.index == 0) {
    f.sections.push_back(view_of(kGlossyTangents,
                                 inputs.tangents.empty() ? nullptr : &inputs.tangents[0].x,
                                 4 * inputs.tangents.size()));
    f.sections.push_back(view_of(kGlossyMaterialOfVertex, inputs.material_of_vertex.data(),
                                 inputs.material_of_vertex.size()));
    f.sections.push_back(text_section(kGlossyMaterials, materials_json(inputs.materials)));
  }
  return f;
}

prt::PartFile encode_transfer_part(const TransferPart& part, const scene::Scene& scene,
                                   const BakeOptions& options, const std::string& prt_version,
                                   const SubsurfaceBakeOptions* subsurface) {
  nlohmann::json settings = nlohmann::json::parse(sh_bake_settings(options));
  std::vector<int32_t> materials;
  if (subsurface) {
    settings["subsurface"] = nlohmann::json::parse(subsurface_bake_settings(*subsurface));
    materials = subsurface_materials_of_vertices(*subsurface, scene.positions.size());
  }
  prt::PartFile f = part_with_settings(prt::PartKind::ShTransfer, part.shard, part.rows, scene,
                                       settings, options.seed, prt_version,
                                       subsurface ? subsurface_inputs_hash(materials) : "");
  if (subsurface && part.shard.index == 0)
    f.sections.push_back(
        section_of(kSubsurfaceMaterialOfVertex, materials.data(), materials.size()));
  f.sections.push_back(view_of(kDirect, part.direct.data(), part.direct.size()));
  f.sections.push_back(view_of(kAo, part.ao.data(), part.ao.size()));
  f.sections.push_back(view_of(kBent, part.bent.data(), part.bent.size()));
  f.sections.push_back(view_of(kGatherRows, part.gather_rows.data(), part.gather_rows.size()));
  prt::PartSection hits;  // the hits' runs (the shard's blocks), written one after another
  hits.tag = kGatherHits;
  for (const TransferPart::HitRun& run : part.hit_runs())
    hits.pieces.push_back({run.data, run.size * sizeof(CompactHit)});
  f.sections.push_back(std::move(hits));
  f.sections.push_back(counters_section(part.rays, part.back_face_hits, part.ray_offset_max));
  return f;
}

prt::PartFile encode_haar_part(const HaarPart& part, const scene::Scene& scene,
                               const HaarBakeOptions& options, const std::string& prt_version) {
  prt::PartFile f = part_with_settings(prt::PartKind::HaarTransfer, part.shard, part.rows, scene,
                                       nlohmann::json::parse(haar_bake_settings(options)),
                                       options.seed, prt_version);
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
  f.layout = part_layout_id();
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

uint64_t part_layout_id() {
  static const uint64_t id = [] {
    numerics::WordHash h;
    h.add_word(prt::kPartFileVersion);
    h.add_word(kSubsurfaceMaterialOfVertex);  // the last section tag
    hash_shape(h, nlohmann::json::parse(sh_bake_settings(BakeOptions{})));
    hash_shape(h, nlohmann::json::parse(haar_bake_settings(HaarBakeOptions{})));
    hash_shape(h, nlohmann::json::parse(glossy_bake_settings(GlossyBakeOptions{})));
    hash_shape(h, nlohmann::json::parse(subsurface_bake_settings(SubsurfaceBakeOptions{})));
    return h.finish();
  }();
  return id;
}

TransferPartFile decode_transfer_part(const prt::PartFile& f, const std::string& name) {
  if (f.layout != part_layout_id()) {
    char text[160];
    std::snprintf(text, sizeof text,
                  ": written by another prt version (part layout %016llx, this prt's %016llx): "
                  "bake it again with this prt",
                  static_cast<unsigned long long>(f.layout),
                  static_cast<unsigned long long>(part_layout_id()));
    throw BakeError(name + text);
  }
  TransferPartFile out;
  out.name = name;
  out.fingerprint = f.fingerprint;
  out.haar = f.kind == prt::PartKind::HaarTransfer;
  out.glossy = f.kind == prt::PartKind::GlossyTransfer;
  try {
    const nlohmann::json j = nlohmann::json::parse(read_text(f, kSettings, name, "settings"));
    out.prt_version = j.at("prt_version").get<std::string>();
    out.seed = j.at("seed").get<uint64_t>();
    out.settings = j.at("settings").dump();
    out.scene_inputs = j.at("scene_inputs").get<std::string>();
    out.form_factors = f.kind == prt::PartKind::FormFactorRows;
    if (out.glossy)
      out.glossy_options =
          glossy_options_from_settings(out.settings, out.seed, name + ": settings");
    else if (out.haar)
      out.haar_options = haar_options_from_settings(out.settings, out.seed, name + ": settings");
    else if (!out.form_factors)
      out.options = sh_options_from_settings(out.settings, out.seed, name + ": settings");
    if (!out.form_factors && !out.haar && !out.glossy && j.at("settings").contains("subsurface"))
      out.subsurface = subsurface_options_from_settings(j.at("settings").at("subsurface").dump(),
                                                        name + ": settings: subsurface");
  } catch (const nlohmann::json::exception& e) {
    throw BakeError(name + ": settings section: " + e.what());
  }
  if (out.form_factors) {
    out.key = f.fingerprint;
    out.form_factor_rows = read_array<float>(
        f, kFormFactors, count_of(f.row_count, f.total_rows, name, "form factors"), name,
        "form factors");
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
  if (out.glossy) {
    if (f.index == 0) out.scene = decode_scene(f, name);
    decode_glossy(f, name, out);
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
  // The two large arrays stay where the mapping has them (the merge copies them once, into the
  // single bake's stores); out.mapping keeps them.
  p.direct_count = need_sh ? count_of(n, K, name, "direct transfer") : 0;
  p.direct_view = section_values<double>(f, kDirect, p.direct_count, name, "direct transfer");
  p.ao = read_array<float>(f, kAo, o.ao ? n : 0, name, "ao");
  p.bent = read_array<float>(f, kBent, o.bent_normals ? count_of(3, n, name, "bent normal") : 0,
                             name, "bent normal");
  p.gather_rows = read_array<uint32_t>(f, kGatherRows, interreflect ? n : 0, name, "gather rows");
  uint64_t hits = 0;
  for (uint32_t len : p.gather_rows) hits += len;
  p.hit_count = hits;
  p.hits_view = section_values<CompactHit>(f, kGatherHits, hits, name, "gather hits");
  out.mapping = f.mapping;
  const std::vector<uint64_t> counters = read_array<uint64_t>(f, kCounters, 3, name, "counters");
  p.rays = counters[0];
  p.back_face_hits = counters[1];
  std::memcpy(&p.ray_offset_max, &counters[2], sizeof(double));
  if (out.subsurface && f.index == 0) {
    const uint64_t materials = out.subsurface->materials.size();
    out.subsurface->vertex_material = read_array<int32_t>(
        f, kSubsurfaceMaterialOfVertex, f.total_rows, name, "subsurface material of each vertex");
    for (int32_t m : out.subsurface->vertex_material)
      if (m < -1 || (m >= 0 && static_cast<uint64_t>(m) >= materials))
        throw BakeError(name + ": a vertex names no subsurface material");
    if (subsurface_inputs_hash(out.subsurface->vertex_material) !=
        out.scene_inputs.substr(std::min(out.scene_inputs.size(), std::size_t{16})))
      throw BakeError(name + ": the subsurface materials of the vertices do not match their hash");
  }
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
  if (ja.contains("basis") && jb.contains("basis") && ja.at("basis") != jb.at("basis"))
    return "basis " + ja.at("basis").dump() + " here, " + jb.at("basis").dump() + " in " + ref;
  if (ja.contains("subsurface") != jb.contains("subsurface"))
    return std::string(ja.contains("subsurface") ? "--subsurface here, none"
                                                 : "no --subsurface here, --subsurface") +
           " in " + ref;
  if (ja.contains("subsurface") && ja.at("subsurface") != jb.at("subsurface")) {
    const nlohmann::json &sa = ja.at("subsurface"), &sb = jb.at("subsurface");
    for (auto it = sa.begin(); it != sa.end(); ++it)
      if (!sb.contains(it.key()) || sb.at(it.key()) != it.value())
        return "subsurface " + it.key() + " " + it.value().dump() + " here, " +
               (sb.contains(it.key()) ? sb.at(it.key()).dump() : "none") + " in " + ref;
  }
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
  // A form-factor part's key covers its options too, and parts of other kinds of bake hash other
  // scene inputs: name the settings first.
  const bool other_kind = p.form_factors || p.haar != r.haar || p.glossy != r.glossy ||
                          p.form_factors != r.form_factors ||
                          p.subsurface.has_value() != r.subsurface.has_value();
  if (other_kind && p.settings != r.settings)
    return p.name +
           ": baked with other settings: " + settings_difference(p.settings, r.settings, r.name);
  if (p.fingerprint != r.fingerprint || p.scene_inputs != r.scene_inputs ||
      p.part.vertices != r.part.vertices)
    return p.name + ": a part of another scene than " + r.name + " (" +
           (p.fingerprint != r.fingerprint ? "other positions"
            : p.glossy ? "other normals, albedo, triangles, materials or tangent frames"
            : p.subsurface
                ? "other normals, albedo, triangles or subsurface materials of the vertices"
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
  if (N > parts.size()) {  // a shard is missing: name the first without N slots (N is a header's)
    std::vector<uint32_t> given;
    for (const TransferPartFile& p : parts) given.push_back(p.part.shard.index);
    std::sort(given.begin(), given.end());
    uint32_t i = 0;
    for (std::size_t k = 0; k < given.size() && given[k] <= i; ++k) i += given[k] == i;
    const RowRange rows = shard_rows(r.part.vertices, {i, N});
    throw BakeError("shard " + shard_name(i, N) + " is missing (rows " +
                    std::to_string(rows.first) + ".." + std::to_string(rows.end) + " of " +
                    std::to_string(r.part.vertices) + "): no part given holds it");
  }
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
  for (const TransferPartFile* p : ordered) {
    for (uint64_t i = 0; i < p->part.hit_count; ++i)
      if (p->part.hits_view[i].triangle >= T)
        throw BakeError(p->name + ": a gather hit names no triangle");
    // Read again, one part at a time, when the merge copies them (prt::release_part_pages).
    prt::release_part_pages(p->part.hits_view, p->part.hit_count * sizeof(CompactHit));
  }
  return ordered;
}

}  // namespace prt::bake
