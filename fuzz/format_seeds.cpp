// fuzz/format_seeds.cpp — the seeds of format_seeds.h.
#include "format_seeds.h"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/transfer_part_file.h"
#include "prt/emitters/emitter_responses.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/formats/haar_transfer_file.h"
#include "radiosity/form_factor_cache.h"
#include "radiosity/link_cache.h"
#include "scene/image_codec.h"

namespace prt::fuzz {
namespace {

namespace fs = std::filesystem;

void write_bytes(const fs::path& path, const void* bytes, std::size_t size) {
  std::ofstream out(path, std::ios::binary);
  out.write(static_cast<const char*>(bytes), static_cast<std::streamsize>(size));
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

void write_result(const fs::path& path, const Result<std::vector<unsigned char>>& bytes) {
  if (!bytes.ok()) throw std::runtime_error(path.string() + ": " + bytes.status().message());
  write_bytes(path, bytes->data(), bytes->size());
}

// A deterministic value in [-1, 1).
float wave(std::size_t i) {
  return static_cast<float>((i * 37 + 11) % 64) / 32.0f - 1.0f;
}

GlossyTransferData glossy(uint64_t vertices, uint32_t order, uint32_t channels, Precision storage) {
  GlossyTransferData d;
  d.order = order;
  d.channels = channels;
  d.storage = storage;
  d.interreflected = channels == 3;
  d.vertex_count = vertices;
  for (uint64_t v = 0; v < vertices; ++v) {
    d.positions.insert(d.positions.end(), {float(v), 0.5f * float(v), -1.0f});
    d.normals.insert(d.normals.end(), {0.f, 0.f, 1.f});
    d.tangents.insert(d.tangents.end(), {1.f, 0.f, 0.f, v % 2 ? -1.f : 1.f});
    d.material_of_vertex.push_back(static_cast<uint32_t>(v % 3));
  }
  brdf::Material lambert;
  brdf::Material ward;
  ward.model = brdf::MaterialModel::kWard;
  ward.diffuse = {0.1, 0.2, 0.3};
  ward.specular = brdf::grey(0.25);
  ward.alpha_x = 0.1;
  ward.alpha_y = 0.3;
  brdf::Material merl;
  merl.model = brdf::MaterialModel::kMerl;
  merl.merl_path = "brdfs/gold.binary";
  d.materials = {lambert, ward, merl};
  d.matrices.resize(vertices * channels * d.matrix_floats());
  for (std::size_t i = 0; i < d.matrices.size(); ++i) d.matrices[i] = 0.5f * wave(i);
  if (vertices > 1)
    d.primitives = {{0, vertices / 2, "floor"}, {vertices / 2, vertices - vertices / 2, "box"}};
  d.metadata_json = R"({"samples":64})";
  return d;
}

void write_glossy_seeds(const fs::path& dir) {
  struct Shape {
    uint64_t vertices;
    uint32_t order, channels;
    Precision storage;
  };
  const Shape shapes[] = {{1, 1, 1, Precision::F32},
                          {3, 2, 1, Precision::F16},
                          {2, 2, 3, Precision::F32},
                          {2, 3, 1, Precision::F16}};
  int n = 0;
  for (const Shape& s : shapes) {
    const GlossyTransferData d = glossy(s.vertices, s.order, s.channels, s.storage);
    write_result(dir / ("seed_" + std::to_string(n++) + ".prtg"),
                 encode_glossy_transfer_file(d, "seed"));
  }
}

// Two clusters of K vectors for `vertices` vertices of order-2 (or order-1) matrices.
CpcaTransfer cpca(uint64_t vertices, uint32_t order, uint32_t channels, uint32_t k) {
  CpcaTransfer t;
  t.order = order;
  t.channels = channels;
  t.cluster_count = 2;
  t.vector_count = k;
  t.vertex_count = vertices;
  const std::size_t d = t.dimension();
  t.means.resize(2 * d);
  t.basis.assign(2 * k * d, 0.0f);
  for (std::size_t i = 0; i < t.means.size(); ++i) t.means[i] = 0.25f * wave(i);
  for (std::size_t q = 0; q < 2; ++q)
    for (std::size_t j = 0; j < k && j < d; ++j) t.basis[(q * k + j) * d + j] = 1.0f;
  for (uint64_t v = 0; v < vertices; ++v) t.cluster_of_vertex.push_back(uint32_t(v % 2));
  t.weights.resize(vertices * k);
  for (std::size_t i = 0; i < t.weights.size(); ++i) t.weights[i] = wave(i + 5);
  return t;
}

void write_cpca_seeds(const fs::path& dir) {
  write_result(dir / "seed_0.prtq", encode_cpca_file(cpca(3, 2, 1, 2)));
  write_result(dir / "seed_1.prtq", encode_cpca_file(cpca(2, 1, 3, 1)));
  // With its source section: the geometry and materials of an order-2 glossy transfer.
  const CpcaTransfer t = cpca(4, 2, 1, 3);
  GlossyTransferData source = glossy(4, 2, 1, Precision::F32);
  write_result(dir / "seed_2.prtq", encode_cpca_file(t, source));
}

void write_emitter_seeds(const fs::path& dir) {
  EmitterResponses d;
  d.emitters = {{"lamp", {5.f, 5.f, 5.f}}, {"window-panel", {0.f, 1.f, 2.5f}}};
  d.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  d.normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  d.triangles = {0, 1, 2, 0, 2, 3};
  for (std::size_t i = 0; i < 2 * 4 * 3; ++i) d.responses.push_back(0.01f * float(1 + i));
  write_result(dir / "seed_0.prte", encode_emitter_responses(d, "seed"));
  d.emitters.resize(1);
  d.emitters[0].name = "sun \xc3\xa9";
  d.positions.resize(9);
  d.normals.resize(9);
  d.triangles = {0, 1, 2};
  d.responses.assign(9, 0.5f);
  write_result(dir / "seed_1.prte", encode_emitter_responses(d, "seed"));
}

void write_haar_seeds(const fs::path& dir) {
  constexpr int kCube = 8;  // the smallest cube size: 384 wavelet indices
  int n = 0;
  for (HaarQuantization q :
       {HaarQuantization::Float32, HaarQuantization::Bits16, HaarQuantization::Bits8}) {
    const int channels = q == HaarQuantization::Bits16 ? 1 : 3;
    const int vertices = q == HaarQuantization::Bits8 ? 6 : 3;
    HaarTransferBuilder builder(kCube, channels, q);
    for (int v = 0; v < vertices; ++v) {
      SparseVertexTransfer s;
      for (uint32_t i = static_cast<uint32_t>(v); i < 6u * kCube * kCube; i += 29) {
        s.index.push_back(i);
        for (int c = 0; c < channels; ++c) s.values.push_back(wave(i + c));
      }
      if (Status st = builder.add_vertex(s); !st.ok()) throw std::runtime_error(st.message());
    }
    Result<HaarTransfer> t = builder.finish();
    if (!t.ok()) throw std::runtime_error(t.status().message());
    HaarTransferFile file;
    file.transfer = std::move(t.value());
    file.info.kind = TransferKind::Haar;
    file.info.order = kCube;
    file.info.channels = static_cast<uint32_t>(channels);
    file.info.vertex_count = static_cast<uint64_t>(vertices);
    for (int v = 0; v < vertices; ++v) {
      file.info.positions.insert(file.info.positions.end(), {wave(v), wave(v + 1), wave(v + 2)});
      file.info.normals.insert(file.info.normals.end(), {0.f, 1.f, 0.f});
    }
    file.info.primitives.push_back({0, static_cast<uint64_t>(vertices), "mesh/0"});
    file.info.metadata_json = R"({"basis":"haar"})";
    write_result(dir / ("seed_" + std::to_string(n++) + ".prt"),
                 encode_haar_transfer_file(file, "seed"));
  }
}

void write_form_factor_seeds(const fs::path& dir) {
  for (std::size_t n : {1u, 3u, 8u}) {
    radiosity::FormFactorMatrix m;
    m.size = n;
    for (std::size_t i = 0; i < n * n; ++i)
      m.f.push_back(i % (n + 1) == 0 ? 0.0f : 1.0f / static_cast<float>(n));
    radiosity::save_form_factors((dir / ("seed_" + std::to_string(n) + ".ffcache")).string(), m,
                                 0x0123456789abcdefull * n);
  }
}

// Link caches of N = 1, 3 and 4 patches, as save_link_cache writes a solve's: a leaf order,
// the starting radiance and links sorted by (receiver, sender) between nodes of the 2N − 1 node
// tree, exact ones among them; coarse and fine transfer.
void write_link_cache_seeds(const fs::path& dir) {
  for (uint32_t n : {1u, 3u, 4u}) {
    radiosity::HierarchicalSolution solved;
    for (uint32_t p = 0; p < n; ++p) solved.hierarchy.order.push_back((p + 1) % n);
    for (uint32_t p = 0; p < n; ++p) solved.last_start.push_back({wave(p) + 1.0, 0.5, 0.25 * p});
    const uint32_t nodes = 2 * n - 1;
    for (uint32_t r = 0; r < nodes; ++r)
      for (uint32_t s = 0; s < nodes; s += 2) {
        if (r == s && n > 1) continue;
        const uint32_t exact = (r + s) % 3 == 0 ? radiosity::Link::kExact : 0u;
        solved.links.push_back({r, s | exact, 0.01f * float(1 + r + s)});
      }
    std::sort(solved.links.begin(), solved.links.end(),
              [](const radiosity::Link& a, const radiosity::Link& b) {
                return a.receiver != b.receiver ? a.receiver < b.receiver : a.source < b.source;
              });
    solved.stats.fine = n != 3;
    radiosity::HierarchicalOptions options;
    options.max_passes = 2 + static_cast<int>(n);
    radiosity::LinkCacheKeys keys{0x1111u * n, 0x2222u * n, 0x3333u * n};
    radiosity::save_link_cache((dir / ("seed_" + std::to_string(n) + ".links")).string(), keys,
                               options, solved);
  }
}

// A quad of 4 vertices (2 triangles, 1 primitive): the scene of the part seeds.
scene::Scene part_scene() {
  scene::Scene s;
  s.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  s.normals.assign(4, {0, 0, 1});
  s.albedo = {{0.5f, 0.5f, 0.5f}, {0.8f, 0.2f, 0.2f}, {0.2f, 0.8f, 0.2f}, {0.2f, 0.2f, 0.8f}};
  s.triangles = {{0, 1, 2}, {0, 2, 3}};
  scene::ScenePrimitive quad;
  quad.name = "quad";
  quad.vertex_count = 4;
  quad.triangle_count = 2;
  s.primitives = {quad};
  s.source_path = "quad.obj";
  return s;
}

void write_part(const fs::path& path, const PartFile& part) {
  const Status s = write_part_file(path.string(), part);
  if (!s.ok()) throw std::runtime_error(s.message());
}

// SH parts: shadowed with AO and bent normals (shard 0 of 2: the scene sections), interreflected
// with gather rows and hits (shard 1 of 2), and a subsurface bake's part (shard 0 of 1).
void write_sh_part_seeds(const fs::path& dir, const scene::Scene& scene) {
  bake::BakeOptions options;
  options.order = 2;
  options.samples = 16;
  options.ao = true;
  options.bent_normals = true;
  bake::TransferPart part;
  part.shard = {0, 2};
  part.vertices = 4;
  part.rows = bake::shard_rows(4, part.shard);
  part.coefficients = 4;
  for (std::size_t i = 0; i < part.rows.size() * 4; ++i) part.direct.push_back(wave(i));
  part.ao.assign(part.rows.size(), 0.75f);
  for (std::size_t i = 0; i < part.rows.size(); ++i) part.bent.insert(part.bent.end(), {0, 0, 1});
  part.rays = 32;
  part.ray_offset_max = 1e-4;
  write_part(dir / "sh_shadowed.prtpart", bake::encode_transfer_part(part, scene, options, "seed"));

  options.kind = TransferKind::Interreflected;
  options.ao = options.bent_normals = false;
  part.shard = {1, 2};
  part.rows = bake::shard_rows(4, part.shard);
  part.ao.clear();
  part.bent.clear();
  part.gather_rows = {2, 1};
  const std::vector<bake::CompactHit> hits = {{0, 100, 200}, {1, 65535, 0}, {0, 0, 30000}};
  part.hits_view = hits.data();
  part.hit_count = hits.size();
  part.back_face_hits = 1;
  write_part(dir / "sh_interreflected.prtpart",
             bake::encode_transfer_part(part, scene, options, "seed"));

  bake::SubsurfaceBakeOptions subsurface;
  subsurface.materials = {{{0.01, 0.02, 0.03}, {1.0, 1.5, 2.0}, 1.3}};
  subsurface.vertex_material = {0, -1, 0, 0};
  subsurface.mm_per_unit = 100;
  options.kind = TransferKind::Shadowed;
  bake::TransferPart whole;
  whole.shard = {0, 1};
  whole.vertices = 4;
  whole.rows = bake::shard_rows(4, whole.shard);
  whole.coefficients = 4;
  whole.direct.assign(16, 0.125);
  write_part(dir / "sh_subsurface.prtpart",
             bake::encode_transfer_part(whole, scene, options, "seed", &subsurface));
}

// Haar parts: shadowed sparse vectors (shard 0 of 1), interreflected wavelets and gather rows
// (shard 1 of 2, one row of an 8 × 8 cube).
void write_haar_part_seeds(const fs::path& dir, const scene::Scene& scene) {
  bake::HaarBakeOptions options;
  options.cube_size = 8;
  bake::HaarPart part;
  part.shard = {0, 1};
  part.vertices = 4;
  part.rows = bake::shard_rows(4, part.shard);
  part.sparse_lengths = {2, 0, 1, 3};
  part.sparse_index = {0, 7, 383, 1, 2, 3};
  for (std::size_t i = 0; i < part.sparse_index.size(); ++i) part.sparse_values.push_back(wave(i));
  part.rays = 64;
  write_part(dir / "haar_shadowed.prtpart", bake::encode_haar_part(part, scene, options, "seed"));

  options.transport = TransferKind::Interreflected;
  bake::HaarPart bounce;
  bounce.shard = {1, 4};
  bounce.vertices = 4;
  bounce.rows = bake::shard_rows(4, bounce.shard);
  for (std::size_t i = 0; i < bounce.rows.size() * 6 * 8 * 8; ++i)
    bounce.wavelets.push_back(0.01f * wave(i));
  bounce.gather_lengths.assign(bounce.rows.size(), 2);
  for (std::size_t i = 0; i < 2 * bounce.rows.size(); ++i) {
    bounce.gather_columns.push_back(static_cast<uint32_t>(i % 4));
    bounce.gather_weights.push_back(0.25f);
  }
  bounce.rays = 64;
  write_part(dir / "haar_interreflected.prtpart",
             bake::encode_haar_part(bounce, scene, options, "seed"));
}

// A glossy part with one bounce (shard 0 of 1: the scene and the glossy inputs, a Lambert and a
// Ward material).
void write_glossy_part_seeds(const fs::path& dir, const scene::Scene& scene) {
  bake::GlossyBakeOptions options;
  options.order = 2;
  options.samples = 16;
  options.bounces = 1;
  bake::GlossyInputs inputs;
  inputs.tangents.assign(4, {1, 0, 0, 1});
  brdf::Material ward;
  ward.model = brdf::MaterialModel::kWard;
  ward.specular = brdf::grey(0.25);
  ward.alpha_x = 0.2;
  ward.alpha_y = 0.2;
  inputs.materials = {brdf::Material{}, ward};
  inputs.material_of_vertex = {0, 1, 1, 0};
  bake::GlossyPart part;
  part.shard = {0, 1};
  part.vertices = 4;
  part.rows = bake::shard_rows(4, part.shard);
  part.order = 2;
  for (std::size_t i = 0; i < 4 * 16; ++i) part.direct.push_back(0.1f * wave(i));
  part.hit_counts = {1, 0, 2, 0};
  part.hits = {{3, 1, 0.25f, 0.5f}, {0, 0, 0.1f, 0.1f}, {9, 1, 0.6f, 0.3f}};
  part.rays = 64;
  write_part(dir / "glossy.prtpart",
             bake::encode_glossy_part(part, scene, inputs, options, "seed"));
}

// A form-factor part: rows [1, 3) of a 3 × 3 matrix (shard 1 of 2).
void write_form_factor_part_seeds(const fs::path& dir) {
  const std::vector<float> rows = {0.0f, 0.5f, 0.25f, 0.5f, 0.0f, 0.125f};
  write_part(dir / "form_factors.prtpart",
             bake::encode_form_factor_part({1, 2}, 0x0123456789abcdefull, 3, 1, rows,
                                           R"({"resolution":64})", 7, "seed"));
}

void write_part_seeds(const fs::path& dir) {
  const scene::Scene scene = part_scene();
  write_sh_part_seeds(dir, scene);
  write_haar_part_seeds(dir, scene);
  write_glossy_part_seeds(dir, scene);
  write_form_factor_part_seeds(dir);
}

// Selector byte (fuzz_merl_brdf.cpp) + file: a bare header (refused: truncated), and the
// table-sized expansion of a header and a few doubles (accepted: byte 1 of the remainder is 0,
// an exact size; one with a negative value, which evaluates as 0).
void write_merl_seeds(const fs::path& dir) {
  const int32_t dims[3] = {90, 90, 180};
  std::string header(reinterpret_cast<const char*>(dims), 12);
  write_bytes(dir / "header_only", (std::string(1, '\0') + header).data(), 13);
  for (int s = 0; s < 2; ++s) {
    const double values[4] = {0.5, 1500.0, s ? -1.0 : 0.0, 2.25};
    std::string seed = std::string(1, '\1') + header +
                       std::string(reinterpret_cast<const char*>(values), sizeof values);
    write_bytes(dir / ("table_" + std::to_string(s)), seed.data(), seed.size());
  }
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Selector byte (fuzz_texture.cpp) + PNG / JPEG files written through the OpenImageIO plugin
// (8-bit grey, grey + alpha, RGB, RGBA), and raw float images.
void write_texture_seeds(const fs::path& dir) {
  struct Image {
    int w, h, channels;
    const char* extension;
    uint8_t selector;  // source (0 PNG, 1 JPEG) + 4 · content + 16 · sampler
  };
  const Image images[] = {{3, 2, 1, ".png", 0},      {4, 4, 2, ".png", 0 + 4 * 2},
                          {5, 3, 3, ".png", 0 + 16}, {2, 7, 4, ".png", 0 + 4 * 2 + 64},
                          {8, 8, 3, ".jpg", 1 + 4},  {9, 5, 1, ".jpg", 1 + 128}};
  int n = 0;
  for (const Image& im : images) {
    std::vector<float> pixels(static_cast<std::size_t>(im.w) * im.h * im.channels);
    for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = 0.5f + 0.5f * wave(i);
    const fs::path tmp = dir / (std::string("tmp") + im.extension);
    const Status s = scene::encode_image_file(tmp.string(), tmp.string(), im.w, im.h, im.channels,
                                              scene::ImageSampleType::UInt8,
                                              scene::ImageSampleType::Float, false, pixels.data());
    if (!s.ok()) throw std::runtime_error(s.message());
    const std::string file = std::string(1, static_cast<char>(im.selector)) + read_bytes(tmp);
    fs::remove(tmp);
    write_bytes(dir / ("image_" + std::to_string(n++)), file.data(), file.size());
  }
  // Raw: selector 2 (sRGB) / 2 + 4 (linear), width 1 + 3, height 1 + 2, channels 1 + 2; floats
  // including NaN, Inf, negatives and values above 1.
  const float samples[] = {0.f,   0.25f, 1.f,   -1.f,  2.f,   NAN,   INFINITY, 0.5f,  0.75f,
                           1e-3f, 0.9f,  0.1f,  0.3f,  0.6f,  0.2f,  0.8f,     0.4f,  0.7f,
                           0.05f, 0.95f, 0.33f, 0.66f, 0.15f, 0.85f, 0.45f,    0.55f, 0.35f,
                           0.65f, 0.25f, 0.5f,  0.12f, 0.88f, 0.42f, 0.58f,    0.22f, 0.78f};
  for (uint8_t selector : {uint8_t{2}, uint8_t{2 + 4 + 32}}) {
    std::string seed = std::string(1, static_cast<char>(selector)) + std::string("\x03\x02\x02", 3);
    seed.append(reinterpret_cast<const char*>(samples), sizeof samples);
    write_bytes(dir / ("raw_" + std::to_string(selector)), seed.data(), seed.size());
  }
}

}  // namespace

void write_format_seeds(const fs::path& out) {
  const char* names[] = {"fuzz_glossy_file", "fuzz_cpca_file",  "fuzz_emitter_responses",
                         "fuzz_haar_file",   "fuzz_merl_brdf",  "fuzz_form_factor_cache",
                         "fuzz_texture",     "fuzz_link_cache", "fuzz_part_file"};
  for (const char* name : names) fs::create_directories(out / name);
  write_glossy_seeds(out / "fuzz_glossy_file");
  write_cpca_seeds(out / "fuzz_cpca_file");
  write_emitter_seeds(out / "fuzz_emitter_responses");
  write_haar_seeds(out / "fuzz_haar_file");
  write_merl_seeds(out / "fuzz_merl_brdf");
  write_form_factor_seeds(out / "fuzz_form_factor_cache");
  write_texture_seeds(out / "fuzz_texture");
  write_link_cache_seeds(out / "fuzz_link_cache");
  write_part_seeds(out / "fuzz_part_file");
}

}  // namespace prt::fuzz
