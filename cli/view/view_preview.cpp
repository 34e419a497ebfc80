// cli/view/view_preview.cpp — vertex clustering of view_preview.h.
#include "view_preview.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <unordered_map>

#include <tbb/parallel_sort.h>

#include "prt/core/half.h"

namespace prt::cli::view {
namespace {

constexpr std::uint64_t kAxisCells = (1u << 20) - 1;  // cells per axis: 20 bits of the key

// 0..5: the normal's dominant axis and its sign (a zero normal goes to 0).
std::uint64_t normal_bucket(const glm::vec3& n) {
  const glm::vec3 a = glm::abs(n);
  const int axis = a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
  return std::uint64_t(2 * axis + (n[axis] < 0.f ? 1 : 0));
}

double surface_area(const scene::Scene& scene) {
  double area = 0.0;
  for (const glm::uvec3& t : scene.triangles) {
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    area += 0.5 * glm::length(glm::cross(b - a, c - a));
  }
  return area;
}

// Vertices on an edge that only one triangle uses.
std::vector<bool> boundary_vertices(const scene::Scene& scene) {
  std::vector<std::uint64_t> edges;
  edges.reserve(3 * scene.triangles.size());
  for (const glm::uvec3& t : scene.triangles)
    for (int i = 0; i < 3; ++i) {
      const std::uint64_t a = t[i], b = t[(i + 1) % 3];
      edges.push_back(std::min(a, b) << 32 | std::max(a, b));
    }
  tbb::parallel_sort(edges.begin(), edges.end());
  std::vector<bool> boundary(scene.vertex_count(), false);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary[edges[i] >> 32] = boundary[edges[i] & 0xffffffffu] = true;
    i = j;
  }
  return boundary;
}

template <class T>
void add_section(nlohmann::json* sections, std::vector<std::uint8_t>* out, const char* name,
                 const std::vector<T>& values, const char* type) {
  (*sections)[name] = {{"offset", out->size()}, {"count", values.size()}, {"type", type}};
  const std::size_t at = out->size();
  out->resize(at + values.size() * sizeof(T));
  if (!values.empty()) std::memcpy(out->data() + at, values.data(), values.size() * sizeof(T));
}

// The per-vertex vec3 `field` of the preview's vertices, flattened.
std::vector<float> gather(const std::vector<glm::vec3>& field, const PreviewMesh& preview) {
  std::vector<float> out;
  out.reserve(3 * preview.source_vertex.size());
  for (const std::uint32_t v : preview.source_vertex)
    out.insert(out.end(), {field[v].x, field[v].y, field[v].z});
  return out;
}

}  // namespace

std::vector<std::uint8_t> preview_bytes(const scene::Scene& scene, const prt::TransferData& data,
                                        const PreviewMesh& preview, nlohmann::json* manifest) {
  constexpr std::size_t kWidth = 4096;  // texels per row at most (a small texture: no 8192)
  const std::size_t count = preview.source_vertex.size();
  const std::size_t per_vertex = std::size_t(data.channels) * data.coefficients_per_channel();
  const std::size_t texels_per_vertex = (per_vertex + 3) / 4;
  const std::size_t width = texels_per_vertex * (kWidth / texels_per_vertex);
  const std::size_t rows =
      std::max<std::size_t>(1, (count * texels_per_vertex + width - 1) / width);
  std::vector<std::uint16_t> halves(rows * width * 4, 0);
  for (std::size_t i = 0; i < count; ++i)
    convert_floats_to_halves(&data.coefficients[preview.source_vertex[i] * per_vertex], per_vertex,
                             &halves[i * texels_per_vertex * 4]);
  std::vector<std::uint8_t> out;
  nlohmann::json sections;
  add_section(&sections, &out, "positions", gather(scene.positions, preview), "float32");
  add_section(&sections, &out, "normals", gather(scene.normals, preview), "float32");
  add_section(&sections, &out, "albedo", gather(scene.albedo, preview), "float32");
  add_section(&sections, &out, "indices", preview.indices, "uint32");
  add_section(&sections, &out, "transfer", halves, "float16 RGBA");
  *manifest = {{"url", "/api/preview.bin"},
               {"vertex_count", count},
               {"triangle_count", preview.indices.size() / 3},
               {"cell_size", preview.cell_size},
               {"sections", sections},
               {"transfer",
                {{"width", width},
                 {"height", rows},
                 {"texels_per_vertex", texels_per_vertex},
                 {"vertices_per_row", width / texels_per_vertex}}}};
  return out;
}

PreviewMesh build_preview_mesh(const scene::Scene& scene, std::size_t target_vertices) {
  if (target_vertices == 0) throw std::invalid_argument("build_preview_mesh: no target");
  PreviewMesh preview;
  const std::size_t v_count = scene.vertex_count();
  if (v_count == 0) return preview;
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (const glm::vec3& p : scene.positions) {
    lo = glm::min(lo, glm::dvec3(p));
    hi = glm::max(hi, glm::dvec3(p));
  }
  const double extent = std::max({hi.x - lo.x, hi.y - lo.y, hi.z - lo.z, 1e-30});
  double cell = std::sqrt(surface_area(scene) / double(target_vertices));
  cell = std::max(cell, extent / double(kAxisCells - 1));
  preview.cell_size = cell;

  // Clusters, numbered in order of their first vertex.
  std::unordered_map<std::uint64_t, std::uint32_t> cluster_of_key;
  cluster_of_key.reserve(4 * target_vertices);
  std::vector<std::uint32_t> cluster(v_count);
  std::vector<glm::dvec3> sum;
  std::vector<std::uint32_t> members;
  for (std::size_t v = 0; v < v_count; ++v) {
    const glm::dvec3 at = (glm::dvec3(scene.positions[v]) - lo) / cell;
    const auto axis = [&](double x) {
      return std::min<std::uint64_t>(kAxisCells, std::uint64_t(std::max(0.0, x)));
    };
    const std::uint64_t key = (axis(at.x) << 43) | (axis(at.y) << 23) | (axis(at.z) << 3) |
                              normal_bucket(scene.normals[v]);
    const auto [it, added] = cluster_of_key.emplace(key, std::uint32_t(sum.size()));
    if (added) {
      sum.emplace_back(0.0);
      members.push_back(0);
    }
    cluster[v] = it->second;
    sum[it->second] += glm::dvec3(scene.positions[v]);
    ++members[it->second];
  }
  // Each cluster's vertex: the one nearest to the cluster's mean (the first of equals), taken
  // from the cluster's boundary vertices when it has any, so that an open edge (where a box's
  // faces meet) stays on the edge and no gap opens onto the inside.
  const std::size_t clusters = sum.size();
  const std::vector<bool> boundary = boundary_vertices(scene);
  std::vector<bool> has_boundary(clusters, false);
  for (std::size_t v = 0; v < v_count; ++v)
    if (boundary[v]) has_boundary[cluster[v]] = true;
  preview.source_vertex.assign(clusters, 0);
  std::vector<double> best(clusters, std::numeric_limits<double>::max());
  for (std::size_t v = 0; v < v_count; ++v) {
    const std::uint32_t c = cluster[v];
    if (has_boundary[c] && !boundary[v]) continue;
    const glm::dvec3 d = glm::dvec3(scene.positions[v]) - sum[c] / double(members[c]);
    const double d2 = glm::dot(d, d);
    if (d2 < best[c]) {
      best[c] = d2;
      preview.source_vertex[c] = std::uint32_t(v);
    }
  }
  // Triangles between three clusters that face the way their scene triangle faces (a fold
  // would show its black back), each rotated to start at its smallest index (the winding
  // kept), then sorted and made unique.
  const auto facing = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    const glm::dvec3 p(scene.positions[a]);
    return glm::cross(glm::dvec3(scene.positions[b]) - p, glm::dvec3(scene.positions[c]) - p);
  };
  std::vector<std::array<std::uint32_t, 3>> triangles;
  for (const glm::uvec3& t : scene.triangles) {
    std::array<std::uint32_t, 3> c{cluster[t.x], cluster[t.y], cluster[t.z]};
    if (c[0] == c[1] || c[1] == c[2] || c[0] == c[2]) continue;
    const std::vector<std::uint32_t>& s = preview.source_vertex;
    if (glm::dot(facing(t.x, t.y, t.z), facing(s[c[0]], s[c[1]], s[c[2]])) <= 0.0) continue;
    std::rotate(c.begin(), std::min_element(c.begin(), c.end()), c.end());
    triangles.push_back(c);
  }
  std::sort(triangles.begin(), triangles.end());
  triangles.erase(std::unique(triangles.begin(), triangles.end()), triangles.end());
  preview.indices.reserve(3 * triangles.size());
  for (const auto& t : triangles) preview.indices.insert(preview.indices.end(), t.begin(), t.end());
  return preview;
}

}  // namespace prt::cli::view
