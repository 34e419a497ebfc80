// cli/view/glossy_payload.cpp — the payloads of glossy_payload.h, from the functions
// `prt relight` runs for a glossy file (relight/glossy_relight.h).
#include "glossy_payload.h"

#include "payload_parts.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>

#include "numerics/gauss_legendre.h"
#include "prt/core/half.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/glossy/brdf_projection.h"
#include "relight/auto_exposure.h"
#include "relight/environment_input.h"
#include "relight/glossy_relight.h"
#include "relight/relight_pipeline.h"
#include "relight/shown_window.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "sh/basis.h"
#include "sh/window.h"

namespace prt::cli::view {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr std::size_t kTextureWidth = 4096;  // texels a row (whole vertices a row)
constexpr std::size_t kMaxTextureSide = 8192;

template <class T>
void append(std::vector<std::uint8_t>* out, const T* data, std::size_t count) {
  const std::size_t at = out->size();
  out->resize(at + count * sizeof(T));
  if (count > 0) std::memcpy(out->data() + at, data, count * sizeof(T));
}

// Width and height of a texture holding `per_vertex` texels for each of `vertices`, a whole
// number of vertices a row; throws when it exceeds kMaxTextureSide².
std::pair<std::size_t, std::size_t> texture_size(std::size_t per_vertex, std::size_t vertices,
                                                 const std::string& what) {
  std::size_t width = per_vertex * std::max<std::size_t>(1, kTextureWidth / per_vertex);
  const std::size_t texels = per_vertex * vertices;
  if ((texels + width - 1) / width > kMaxTextureSide)
    width = per_vertex * std::max<std::size_t>(1, kMaxTextureSide / per_vertex);
  const std::size_t rows = std::max<std::size_t>(1, (texels + width - 1) / width);
  if (rows > kMaxTextureSide || width > kMaxTextureSide)
    throw std::runtime_error(what + " takes " + std::to_string(texels) + " texels, more than a " +
                             std::to_string(kMaxTextureSide) + "² texture");
  return {width, rows};
}

nlohmann::json layout_json(std::size_t width, std::size_t height, std::size_t per_vertex,
                           const char* type) {
  return {{"width", width},
          {"height", height},
          {"texels_per_vertex", per_vertex},
          {"vertices_per_row", width / per_vertex},
          {"type", type}};
}

// .prtg: the matrices as float16 RGBA texels, P = ⌈C·n⁴/4⌉ a vertex.
std::vector<std::uint8_t> matrix_texture(const ViewInputs& inputs,
                                         const prt::GlossyTransferData& data,
                                         nlohmann::json* layout) {
  const std::size_t per_vertex = std::size_t(data.channels) * data.matrix_floats();
  const std::size_t texels = (per_vertex + 3) / 4;
  const auto [width, height] =
      texture_size(texels, data.vertex_count, inputs.transfer_path + ": the matrices");
  charge_payload(inputs, std::uint64_t(width) * height * 4 * sizeof(std::uint16_t), "the matrices");
  std::vector<std::uint16_t> halves(width * height * 4, 0);
  for (std::size_t v = 0; v < data.vertex_count; ++v)
    convert_floats_to_halves(&data.matrices[v * per_vertex], per_vertex, &halves[v * texels * 4]);
  *layout = layout_json(width, height, texels, "float16 RGBA");
  std::vector<std::uint8_t> out;
  append(&out, halves.data(), halves.size());
  return out;
}

// .prtq: per cluster the mean, then the K vectors, float32.
std::vector<std::uint8_t> cpca_arrays(const ViewInputs& inputs, const prt::CpcaTransfer& cpca,
                                      nlohmann::json* layout) {
  const std::size_t d = cpca.dimension(), k = cpca.vector_count;
  std::vector<std::uint8_t> out;
  charge_payload(inputs, cpca.cluster_count * (k + 1) * d * sizeof(float), "the CPCA clusters");
  out.reserve(cpca.cluster_count * (k + 1) * d * sizeof(float));
  for (std::size_t q = 0; q < cpca.cluster_count; ++q) {
    append(&out, &cpca.means[q * d], d);
    append(&out, cpca.basis.data() + q * k * d, k * d);
  }
  *layout = {{"clusters", cpca.cluster_count},
             {"vectors", cpca.vector_count},
             {"dimension", d},
             {"type", "float32 ((q*(K+1) + k)*D + d), k = 0 the mean"}};
  return out;
}

// The relighter's frame rows t, b, n of vertex k (prt/glossy/relighter.h: Gram–Schmidt of the
// tangent against the normal, b = w·n × t), in double, rounded to float once.
void frame_rows(const prt::GlossyTransferData& d, std::size_t k, float rows[9]) {
  double n[3] = {d.normals[3 * k], d.normals[3 * k + 1], d.normals[3 * k + 2]};
  double t[3] = {d.tangents[4 * k], d.tangents[4 * k + 1], d.tangents[4 * k + 2]};
  const double w = d.tangents[4 * k + 3] < 0.f ? -1.0 : 1.0;
  const double ln = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  for (double& x : n) x /= ln;
  const double tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
  for (int i = 0; i < 3; ++i) t[i] -= tn * n[i];
  const double lt = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (double& x : t) x /= lt;
  const double b[3] = {w * (n[1] * t[2] - n[2] * t[1]), w * (n[2] * t[0] - n[0] * t[2]),
                       w * (n[0] * t[1] - n[1] * t[0])};
  for (int i = 0; i < 3; ++i) {
    rows[i] = float(t[i]);
    rows[3 + i] = float(b[i]);
    rows[6 + i] = float(n[i]);
  }
}

// The per-vertex texels: frame rows (material in texel 0's w), then cluster id and weights.
std::vector<float> vertex_texels(const prt::GlossyTransferData& data, const prt::CpcaTransfer* cpca,
                                 nlohmann::json* layout) {
  const std::size_t k = cpca ? cpca->vector_count : 0;
  const std::size_t per_vertex = 3 + (cpca ? (k + 1 + 3) / 4 : 0);
  const auto [width, height] = texture_size(per_vertex, data.vertex_count, "the vertex data");
  std::vector<float> out(width * height * 4, 0.f);
  for (std::size_t v = 0; v < data.vertex_count; ++v) {
    float* texel = &out[v * per_vertex * 4];
    float rows[9];
    frame_rows(data, v, rows);
    for (int r = 0; r < 3; ++r) std::copy(rows + 3 * r, rows + 3 * r + 3, texel + 4 * r);
    texel[3] = float(data.material_of_vertex[v]);
    if (cpca) {
      texel[12] = float(cpca->cluster_of_vertex[v]);
      std::copy(&cpca->weights[v * k], &cpca->weights[v * k] + k, texel + 13);
    }
  }
  *layout = layout_json(width, height, per_vertex, "float32 RGBA");
  return out;
}

// Appends b(ωo) of `projection` at local `wo` as n² RGBA texels.
void append_node(const prt::BrdfProjection& projection, const brdf::Vec3& wo,
                 std::vector<double>* nodes) {
  const std::size_t n2 = std::size_t(projection.order()) * projection.order();
  std::vector<double> b(3 * n2);
  projection.evaluate(wo, b.data());
  for (std::size_t i = 0; i < n2; ++i)
    nodes->insert(nodes->end(), {b[i], b[n2 + i], b[2 * n2 + i], 0.0});
}

// Replaces the node row at the horizon (`count` nodes from `horizon`) by 2·(row above) − (row
// two above), the library's extrapolation of b's limit there (b itself is 0 at the horizon).
void extrapolate_horizon(std::vector<double>* nodes, std::size_t horizon, std::size_t count,
                         std::size_t row_doubles) {
  double* h = nodes->data() + horizon * row_doubles;
  const double* a = h - count * row_doubles;
  const double* b = a - count * row_doubles;
  for (std::size_t i = 0; i < count * row_doubles; ++i) h[i] = 2.0 * a[i] - b[i];
}

// kMatrix: the nodes B_·,·,e of b_c,i(ωo) = Σ_e B_c,i,e y_e(ωo), e over the view-side SH (l, m)
// of order m_v with l + m even, in the order e = l(l+1)/2 + (m + l)/2. b is that polynomial
// above the horizon, and the even y_e are orthogonal there with norm 1/2, so
// B_c,i,e = 2 ∫_{H+} b_c,i y_e, which a product rule integrates EXACTLY (the integrand is a
// polynomial of degree ≤ 2(m_v − 1) in ωo): m_v Gauss–Legendre nodes in cos θo × 2·m_v azimuths.
void append_matrix_nodes(const prt::BrdfProjection& p, std::vector<double>* nodes) {
  const int mv = p.view_order(), n2 = p.order() * p.order();
  const int count = mv * (mv + 1) / 2;
  std::vector<double> z, zw;
  numerics::append_gauss_legendre(mv, 0.0, 1.0, &z, &zw);
  std::vector<double> b(3 * std::size_t(n2)), y(std::size_t(mv) * mv);
  std::vector<double> sums(std::size_t(count) * 3 * n2, 0.0);
  const int azimuths = 2 * mv;
  for (std::size_t a = 0; a < z.size(); ++a)
    for (int f = 0; f < azimuths; ++f) {
      const double phi = 2 * kPi * (f + 0.5) / azimuths, s = std::sqrt(1 - z[a] * z[a]);
      const double w = 2.0 * zw[a] * (2 * kPi / azimuths);
      const double x = s * std::cos(phi), yy = s * std::sin(phi);
      p.evaluate(brdf::Vec3{x, yy, z[a]}, b.data());
      sh::evaluate(mv, x, yy, z[a], y.data());
      for (int l = 0; l < mv; ++l)
        for (int m = -l; m <= l; m += 2) {
          const double ye = w * y[std::size_t(sh::index(l, m))];
          double* row = &sums[std::size_t(l * (l + 1) / 2 + (m + l) / 2) * 3 * n2];
          for (int i = 0; i < 3 * n2; ++i) row[i] += ye * b[std::size_t(i)];
        }
    }
  for (int e = 0; e < count; ++e)
    for (int i = 0; i < n2; ++i) {
      const double* row = &sums[std::size_t(e) * 3 * n2];
      nodes->insert(nodes->end(), {row[i], row[n2 + i], row[2 * n2 + i], 0.0});
    }
}

// The "brdf" nodes of every material and their manifest entries.
std::vector<float> brdf_nodes(const prt::GlossyTransferData& data, const std::string& path,
                              nlohmann::json* materials) {
  const int order = int(data.order), n2 = order * order;
  const int elevations = prt::BrdfProjectionOptions{}.table_size;
  std::vector<double> nodes;
  *materials = nlohmann::json::array();
  for (const brdf::Material& material : data.materials) {
    prt::Result<prt::BrdfProjection> made = prt::BrdfProjection::create(material, order);
    if (!made.ok()) throw std::runtime_error(path + ": " + made.status().message());
    const prt::BrdfProjection& p = *made;
    const std::size_t first = nodes.size() / (4 * std::size_t(n2));
    nlohmann::json entry = {{"first_node", first}, {"material", brdf::describe(material)}};
    if (material.lambertian()) {  // b is the same for every ωo above the horizon
      append_node(p, {0, 0, 1}, &nodes);
      append_node(p, {0, 0, 1}, &nodes);
      entry.update({{"kind", "table"}, {"elevations", 2}, {"azimuths", 1}});
    } else if (p.method() == prt::BrdfProjectionMethod::kIsotropicTable) {
      for (int t = 0; t < elevations; ++t) {
        const double theta = 0.5 * kPi * t / (elevations - 1);
        append_node(p, {std::sin(theta), 0, std::cos(theta)}, &nodes);
      }
      extrapolate_horizon(&nodes, first + elevations - 1, 1, 4 * std::size_t(n2));
      entry.update({{"kind", "table"}, {"elevations", elevations}, {"azimuths", 1}});
    } else {  // kMatrix: b_c,i(ωo) = Σ_e B_c,i,e y_e(ωo) over the even view-side SH
      append_matrix_nodes(p, &nodes);
      entry.update({{"kind", "matrix"}, {"view_order", p.view_order()}});
    }
    materials->push_back(entry);
  }
  return std::vector<float>(nodes.begin(), nodes.end());
}

// The glossy.bin sections and the manifest's "glossy" object.
std::vector<std::uint8_t> glossy_bytes(const prt::GlossyTransferData& data,
                                       const prt::CpcaTransfer* cpca, const std::string& path,
                                       nlohmann::json* glossy) {
  nlohmann::json vertex_layout, materials;
  const std::vector<float> vertex = vertex_texels(data, cpca, &vertex_layout);
  std::vector<float> brdf = brdf_nodes(data, path, &materials);
  const std::size_t texels = brdf.size() / 4;
  const std::size_t per_node = std::size_t(data.order) * data.order;  // whole nodes a row
  const std::size_t width = std::min(texels, per_node * (kTextureWidth / per_node));
  const std::size_t height = (texels + width - 1) / width;
  if (height > kMaxTextureSide)
    throw std::runtime_error(path + ": the BRDF tables take " + std::to_string(texels) +
                             " texels, more than a " + std::to_string(kMaxTextureSide) +
                             "² texture");
  brdf.resize(width * height * 4, 0.f);
  std::vector<std::uint8_t> out;
  vertex_layout["offset"] = 0;
  append(&out, vertex.data(), vertex.size());
  (*glossy)["vertex"] = vertex_layout;
  (*glossy)["brdf"] = {{"offset", out.size()},   {"width", width},
                       {"height", height},       {"texels_per_node", data.order * data.order},
                       {"materials", materials}, {"type", "float32 RGBA"}};
  append(&out, brdf.data(), brdf.size());
  (*glossy)["url"] = "/api/glossy.bin";
  return out;
}

}  // namespace

bool is_glossy_view_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char magic[4] = {};
  return in.read(magic, 4) &&
         (prt::is_glossy_transfer_file(magic, 4) || prt::is_cpca_transfer_file(magic, 4));
}

ViewPayload build_glossy_view_payload(const ViewInputs& inputs) {
  if (!inputs.emitters_path.empty())
    throw std::runtime_error(inputs.transfer_path +
                             ": a glossy file; prt view adds emitters to coefficient files only");
  scene::Scene scene = scene::load_scene(inputs.scene_path);
  if (inputs.max_edge) scene = scene::subdivide_to_edge_length(scene, *inputs.max_edge);
  relight::LoadedGlossy loaded = relight::load_glossy_any_for_scene(inputs.transfer_path, scene);
  const prt::GlossyTransferData& data = loaded.data;
  const prt::CpcaTransfer* cpca = loaded.cpca ? &*loaded.cpca : nullptr;
  const int order = int(data.order);
  ViewPayload payload;
  nlohmann::json manifest, transfer_layout, glossy;
  payload.transfer = cpca ? cpca_arrays(inputs, *cpca, &transfer_layout)
                          : matrix_texture(inputs, data, &transfer_layout);
  payload.glossy = glossy_bytes(data, cpca, inputs.transfer_path, &glossy);
  charge_payload(inputs, payload.glossy.size(), "the vertex frames and BRDF tables");
  glossy["form"] = cpca ? "cpca" : "matrices";
  const uint32_t channels = data.channels;
  const prt::GlossyRelighter relighter =
      relight::make_glossy_relighter(std::move(loaded), inputs.transfer_path, {});

  const sh::EnvMap env = payload_environment(inputs, order);
  relight::LightingOptions options;
  options.window = sh::Window::None;  // auto: chosen on the vertices below, as prt relight does
  const prt::ShLighting unwindowed = relight::project_lighting(env, order, options);
  const scene::RayCaster caster(scene);
  const relight::CameraChoice camera = relight::choose_camera("auto", scene, caster, inputs.aspect);
  const glm::vec3 eye = camera.camera.eye;
  relight::ShownWindowSearch search(order);
  search.add_view(unwindowed, [&](const prt::ShLighting& lighting) {
    return relight::shade_glossy_vertices(relighter, lighting, eye);
  });
  const relight::ShownWindowChoice choice = search.choose();
  prt::ShLighting windowed = unwindowed;
  const std::string window_note = relight::apply_shown_window(choice, &windowed);
  const float exposure =
      relight::choose_auto_exposure(relight::shade_glossy_vertices(relighter, windowed, eye));

  manifest = payload_manifest_head(inputs, scene, cpca ? "glossy-cpca" : "glossy", order,
                                   int(channels), true);
  manifest["sh_basis"] =
      "real orthonormal SH, no Condon-Shortley phase, k = l(l+1)+m, polar axis +z, glTF frame";
  nlohmann::json sections;
  const std::size_t v = scene.vertex_count();
  std::vector<std::uint8_t>& mesh = payload.mesh;
  const auto section = [&](const char* name, const void* p, std::size_t count, std::size_t size,
                           const char* type) {
    sections[name] = {{"offset", mesh.size()}, {"count", count}, {"type", type}};
    append(&mesh, static_cast<const std::uint8_t*>(p), count * size);
  };
  section("positions", &scene.positions[0].x, 3 * v, 4, "float32");
  section("normals", &scene.normals[0].x, 3 * v, 4, "float32");
  section("albedo", &scene.albedo[0].x, 3 * v, 4, "float32");
  section("indices", &scene.triangles[0].x, 3 * scene.triangles.size(), 4, "uint32");
  manifest["mesh"] = {{"url", "/api/mesh.bin"}, {"sections", sections}};
  transfer_layout["url"] = "/api/transfer.bin";
  manifest["transfer"] = transfer_layout;
  manifest["glossy"] = glossy;
  add_payload_lighting(unwindowed, choice, window_note, &manifest);
  add_payload_view(inputs, env, exposure, camera, &manifest, &payload);
  payload.manifest_json = manifest.dump(1);
  payload.summary = std::to_string(v) + " vertices, " + manifest["kind"].get<std::string>() +
                    " order " + std::to_string(order) + "; " + window_note + "; exposure " +
                    payload_exposure_text(exposure);
  return payload;
}

}  // namespace prt::cli::view
