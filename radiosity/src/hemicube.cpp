// The hemicube of radiosity/hemicube.h: delta form factor table, z-buffer rasteriser, ray-cast
// item buffer, and the hemicube row of radiosity/form_factors.h.
#include "radiosity/hemicube.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "radiosity/form_factors.h"

namespace prt::radiosity {
namespace {

// Local (t, b, n) coordinates of face coordinates (s, h, d) on face f.
glm::dvec3 face_to_local(int f, double s, double h, double d) {
  switch (f) {
    case 0:
      return {s, h, d};
    case 1:
      return {d, s, h};
    case 2:
      return {-d, s, h};
    case 3:
      return {s, d, h};
    default:
      return {s, -d, h};
  }
}

glm::dvec3 local_to_face(int f, const glm::dvec3& p) {
  switch (f) {
    case 0:
      return p;
    case 1:
      return {p.y, p.z, p.x};
    case 2:
      return {p.y, p.z, -p.x};
    case 3:
      return {p.x, p.z, p.y};
    default:
      return {p.x, p.z, -p.y};
  }
}

// Exact form factor from the differential area at the origin (normal +z, local frame) to the
// cell [s0, s1] × [h0, h1] of face f at depth 1.
double cell_form_factor(int f, double s0, double s1, double h0, double h1) {
  const std::vector<glm::dvec3> cell = {
      face_to_local(f, s0, h0, 1.0), face_to_local(f, s1, h0, 1.0), face_to_local(f, s1, h1, 1.0),
      face_to_local(f, s0, h1, 1.0)};
  return point_polygon_form_factor(glm::dvec3(0.0), glm::dvec3(0, 0, 1), cell);
}

// A polygon in face coordinates (at most 3 corners + one per clipping plane).
struct Polygon {
  std::array<glm::dvec3, 12> v;
  int n = 0;
};

// Keeps the part of `p` where plane(q) ≥ 0, plane(q) = a·s + b·h + c·d + e.
void clip(const glm::dvec4& plane, Polygon* p) {
  const auto eval = [&](const glm::dvec3& q) {
    return plane.x * q.x + plane.y * q.y + plane.z * q.z + plane.w;
  };
  Polygon out;
  for (int k = 0; k < p->n; ++k) {
    const glm::dvec3& a = p->v[k];
    const glm::dvec3& b = p->v[(k + 1) % p->n];
    const double fa = eval(a), fb = eval(b);
    if (fa >= 0.0) out.v[out.n++] = a;
    if ((fa >= 0.0) != (fb >= 0.0)) out.v[out.n++] = a + (b - a) * (fa / (fa - fb));
  }
  *p = out;
}

// The view frustum of face f: d ≥ near, |s| ≤ d, and |h| ≤ d (top) or 0 ≤ h ≤ d (sides).
std::array<glm::dvec4, 5> frustum(int f, double near) {
  return {glm::dvec4(0, 0, 1, -near), glm::dvec4(-1, 0, 1, 0), glm::dvec4(1, 0, 1, 0),
          glm::dvec4(0, -1, 1, 0), f == 0 ? glm::dvec4(0, 1, 1, 0) : glm::dvec4(0, 1, 0, 0)};
}

// One face's z-buffer: inverse depth per cell (0 = empty) and the item buffer.
struct FaceTarget {
  int width = 0, height = 0;
  bool top = false;
  std::vector<double>* inverse_depth = nullptr;
  std::vector<uint32_t>* items = nullptr;
};

// Scan-converts triangle `tri` (face coordinates, eye at the origin) of a patch whose plane is
// m·q = c. The clipped polygon `p` (inside the frustum) only bounds the cells to visit; the
// inside test is the homogeneous one (Olano & Greer, [81] of docs/REFERENCES.md): the ray r through
// a cell centre meets the triangle at positive depth iff σ·(v_a × v_b)·r ≥ 0 for its three edges, σ
// = sign det(v0, v1, v2). It needs no projected corners, and a shared edge gives its two triangles
// exactly opposite edge functions; a centre exactly on an edge belongs to the triangle whose
// oriented edge normal is lexicographically positive (the top-left rule, made homogeneous).
void scan_convert(const std::array<glm::dvec3, 3>& tri, const Polygon& p, const glm::dvec3& m,
                  double c, uint32_t id, const FaceTarget& target) {
  const double det = glm::dot(glm::cross(tri[0], tri[1]), tri[2]);
  if (!(std::abs(det) > 0.0) || !(std::abs(c) > 0.0)) return;  // edge-on
  const double sigma = det > 0.0 ? 1.0 : -1.0;
  std::array<glm::dvec3, 3> edge;
  std::array<bool, 3> take_zero;
  for (int k = 0; k < 3; ++k) {
    edge[k] = sigma * glm::cross(tri[k], tri[(k + 1) % 3]);
    take_zero[k] = edge[k].x > 0.0 || (edge[k].x == 0.0 && edge[k].y > 0.0) ||
                   (edge[k].x == 0.0 && edge[k].y == 0.0 && edge[k].z > 0.0);
  }
  const double half = 0.5 * target.width;
  double min_x = 1e300, max_x = -1e300, min_y = 1e300, max_y = -1e300;
  for (int k = 0; k < p.n; ++k) {
    const double x = (p.v[k].x / p.v[k].z + 1.0) * half;
    const double y = target.top ? (p.v[k].y / p.v[k].z + 1.0) * half : p.v[k].y / p.v[k].z * half;
    min_x = std::min(min_x, x), max_x = std::max(max_x, x);
    min_y = std::min(min_y, y), max_y = std::max(max_y, y);
  }
  // A margin of 1e-9 cells against rounding in the clipped corners.
  const int x0 = std::max(0, static_cast<int>(std::ceil(min_x - 0.5 - 1e-9)));
  const int x1 = std::min(target.width - 1, static_cast<int>(std::floor(max_x - 0.5 + 1e-9)));
  const int y0 = std::max(0, static_cast<int>(std::ceil(min_y - 0.5 - 1e-9)));
  const int y1 = std::min(target.height - 1, static_cast<int>(std::floor(max_y - 0.5 + 1e-9)));
  for (int y = y0; y <= y1; ++y) {
    const double h = target.top ? (y + 0.5) / half - 1.0 : (y + 0.5) / half;
    for (int x = x0; x <= x1; ++x) {
      const double s = (x + 0.5) / half - 1.0;
      bool inside = true;
      for (int k = 0; k < 3 && inside; ++k) {
        const double e = edge[k].x * s + edge[k].y * h + edge[k].z;
        inside = e > 0.0 || (e == 0.0 && take_zero[k]);
      }
      if (!inside) continue;
      const double w = (m.x * s + m.y * h + m.z) / c;  // 1/d along the ray (s, h, 1)
      const std::size_t cell = static_cast<std::size_t>(y) * target.width + x;
      if (w > (*target.inverse_depth)[cell]) {
        (*target.inverse_depth)[cell] = w;
        (*target.items)[cell] = id;
      }
    }
  }
}

// Per-thread buffers of the rasteriser.
struct Workspace {
  std::array<std::vector<double>, 5> inverse_depth;
  std::vector<double> sums;
};

Workspace& workspace() {
  thread_local Workspace w;
  return w;
}

void prepare(int resolution, HemicubeBuffer* buffer) {
  check_hemicube_resolution(resolution);
  buffer->resolution = resolution;
  for (int f = 0; f < 5; ++f)
    buffer->faces[f].assign(
        static_cast<std::size_t>(resolution) * (f == 0 ? resolution : resolution / 2),
        kHemicubeEmpty);
}

}  // namespace

void check_hemicube_resolution(int resolution) {
  if (resolution < 2 || resolution > 4096 || resolution % 2 != 0)
    throw std::invalid_argument("form factors: the hemicube resolution must be even, 2..4096");
}

DeltaFormFactors::DeltaFormFactors(int resolution) : r_(resolution) {
  check_hemicube_resolution(resolution);
  const int half = r_ / 2;
  const double step = 2.0 / r_;
  // Representatives: top cells (half + i, half + j) with i ≥ j; side cells (half + i, j).
  top_.resize(static_cast<std::size_t>(half) * (half + 1) / 2);
  for (int i = 0; i < half; ++i)
    for (int j = 0; j <= i; ++j)
      top_[static_cast<std::size_t>(i) * (i + 1) / 2 + j] =
          cell_form_factor(0, i * step, (i + 1) * step, j * step, (j + 1) * step);
  side_.resize(static_cast<std::size_t>(half) * half);
  for (int i = 0; i < half; ++i)
    for (int j = 0; j < half; ++j)
      side_[static_cast<std::size_t>(i) * half + j] =
          cell_form_factor(1, i * step, (i + 1) * step, j * step, (j + 1) * step);
}

double DeltaFormFactors::top(int x, int y) const {
  int i = fold(x), j = fold(y);
  if (i < j) std::swap(i, j);
  return top_[static_cast<std::size_t>(i) * (i + 1) / 2 + j];
}

double DeltaFormFactors::side(int x, int y) const {
  return side_[static_cast<std::size_t>(fold(x)) * (r_ / 2) + y];
}

const DeltaFormFactors& delta_form_factors(int resolution) {
  static std::mutex mutex;
  static std::map<int, std::unique_ptr<DeltaFormFactors>> tables;
  check_hemicube_resolution(resolution);
  std::lock_guard<std::mutex> lock(mutex);
  std::unique_ptr<DeltaFormFactors>& table = tables[resolution];
  if (!table) table = std::make_unique<DeltaFormFactors>(resolution);
  return *table;
}

void hemicube_frame(const Patch& p, glm::dvec3* t, glm::dvec3* b) {
  const glm::dvec3 n = p.normal;
  const glm::dvec3 helper = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
  *t = glm::normalize(glm::cross(helper, n));
  *b = glm::cross(n, *t);
}

void rasterize_hemicube(const std::vector<Patch>& patches, uint32_t i, int resolution,
                        HemicubeBuffer* buffer) {
  prepare(resolution, buffer);
  const Patch& s = patches[i];
  if (s.area <= 0.0) return;
  glm::dvec3 t, b;
  hemicube_frame(s, &t, &b);
  const glm::dvec3 n = s.normal, c = s.centroid;
  const double near = 1e-6 * std::sqrt(s.area);
  Workspace& w = workspace();
  std::array<FaceTarget, 5> targets;
  std::array<std::array<glm::dvec4, 5>, 5> planes;
  for (int f = 0; f < 5; ++f) {
    w.inverse_depth[f].assign(buffer->faces[f].size(), 0.0);
    targets[f] = {resolution, f == 0 ? resolution : resolution / 2, f == 0, &w.inverse_depth[f],
                  &buffer->faces[f]};
    planes[f] = frustum(f, near);
  }
  const auto to_local = [&](const glm::dvec3& p) {
    const glm::dvec3 d = p - c;
    return glm::dvec3(glm::dot(d, t), glm::dot(d, b), glm::dot(d, n));
  };
  for (uint32_t j = 0; j < patches.size(); ++j) {
    const Patch& r = patches[j];
    if (j == i || r.area <= 0.0) continue;
    const std::array<glm::dvec3, 3> local = {to_local(r.corners[0]), to_local(r.corners[1]),
                                             to_local(r.corners[2])};
    if (local[0].z <= 0.0 && local[1].z <= 0.0 && local[2].z <= 0.0) continue;  // below
    const glm::dvec3 normal(glm::dot(r.normal, t), glm::dot(r.normal, b), glm::dot(r.normal, n));
    // Plane of j: normal · q = offset (local); the eye (origin) is in front when offset < 0.
    const double offset = glm::dot(normal, local[0]);
    const uint32_t id = offset < 0.0 ? j : kHemicubeBackFace;
    for (int f = 0; f < 5; ++f) {
      Polygon p;
      p.n = 3;
      std::array<int, 5> outside{};
      const std::array<glm::dvec3, 3> tri = {local_to_face(f, local[0]), local_to_face(f, local[1]),
                                             local_to_face(f, local[2])};
      for (int k = 0; k < 3; ++k) {
        p.v[k] = tri[k];
        for (int q = 0; q < 5; ++q)
          outside[q] += glm::dot(glm::dvec3(planes[f][q]), p.v[k]) + planes[f][q].w < 0.0;
      }
      if (std::find(outside.begin(), outside.end(), 3) != outside.end()) continue;
      for (int q = 0; q < 5 && p.n >= 3; ++q)
        if (outside[q] > 0) clip(planes[f][q], &p);
      if (p.n < 3) continue;
      scan_convert(tri, p, local_to_face(f, normal), offset, id, targets[f]);
    }
  }
}

void ray_cast_hemicube(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                       uint32_t i, int resolution, HemicubeBuffer* buffer) {
  prepare(resolution, buffer);
  const Patch& s = patches[i];
  if (s.area <= 0.0) return;
  glm::dvec3 t, b;
  hemicube_frame(s, &t, &b);
  const glm::vec3 origin = caster.surface_origin(i, glm::vec3(s.centroid), glm::vec3(s.normal));
  const float inf = std::numeric_limits<float>::infinity();
  const double step = 2.0 / resolution;
  for (int f = 0; f < 5; ++f) {
    const int height = f == 0 ? resolution : resolution / 2;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < resolution; ++x) {
        const double sx = -1.0 + (x + 0.5) * step;
        const double hy = f == 0 ? -1.0 + (y + 0.5) * step : (y + 0.5) * step;
        const glm::dvec3 l = face_to_local(f, sx, hy, 1.0);
        const glm::dvec3 d = glm::normalize(t * l.x + b * l.y + s.normal * l.z);
        const scene::RayCaster::Hit hit = caster.intersect(origin, glm::vec3(d), 0.f, inf);
        uint32_t id = kHemicubeEmpty;
        if (hit.hit && hit.triangle != i) id = hit.front_face ? hit.triangle : kHemicubeBackFace;
        buffer->faces[f][static_cast<std::size_t>(y) * resolution + x] = id;
      }
  }
}

void hemicube_form_factors(const HemicubeBuffer& buffer, std::size_t patch_count,
                           std::vector<float>* row) {
  const DeltaFormFactors& table = delta_form_factors(buffer.resolution);
  const int r = buffer.resolution;
  std::vector<double>& sums = workspace().sums;
  sums.assign(patch_count, 0.0);
  for (int f = 0; f < 5; ++f) {
    const int height = f == 0 ? r : r / 2;
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < r; ++x) {
        const uint32_t id = buffer.faces[f][static_cast<std::size_t>(y) * r + x];
        if (id < patch_count) sums[id] += table.cell(f, x, y);
      }
  }
  row->assign(patch_count, 0.f);
  for (std::size_t j = 0; j < patch_count; ++j) (*row)[j] = static_cast<float>(sums[j]);
}

void combine_hemicube_estimates(const std::vector<Patch>& patches, std::vector<float>* f) {
  const std::size_t n = patches.size();
  if (f->size() != n * n)
    throw std::invalid_argument("combine_hemicube_estimates: an N × N matrix is needed");
  constexpr std::size_t kTile = 64;  // pairs in 64 × 64 tiles: both entries stay in cache
  const std::size_t tiles = (n + kTile - 1) / kTile;
  float* m = f->data();
  std::vector<char> closed(n, 0);  // the hemicube at i saw no escape: its sum, 1, is exact
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += m[i * n + j];
    closed[i] = sum >= 1.0 - 1e-6;
  });

  // Task a handles every pair (i, j), i in tile a, j in a tile b ≥ a: the tasks write disjoint
  // entries, each from the same two raw values whatever the thread count.
  tbb::parallel_for(std::size_t(0), tiles, [&](std::size_t a) {
    for (std::size_t b = a; b < tiles; ++b)
      for (std::size_t i = a * kTile; i < std::min(n, (a + 1) * kTile); ++i) {
        const double ai = patches[i].area;
        for (std::size_t j = std::max(b * kTile, i + 1); j < std::min(n, (b + 1) * kTile); ++j) {
          const double aj = patches[j].area;
          float& fij = m[i * n + j];
          float& fji = m[j * n + i];
          if (!(ai > 0.0) || !(aj > 0.0)) {
            fij = fji = 0.f;
            continue;
          }
          const double g = ai * aj / (ai + aj) * (double(fij) + double(fji));
          fij = static_cast<float>(g / ai);
          fji = static_cast<float>(g / aj);
        }
      }
  });
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    float* row = m + i * n;
    if (!(patches[i].area > 0.0)) std::fill(row, row + n, 0.f);
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += row[j];
    if (sum > 0.0 && (sum > 1.0 || closed[i]))
      for (std::size_t j = 0; j < n; ++j) row[j] = static_cast<float>(row[j] / sum);
  });
}

void hemicube_row(const std::vector<Patch>& patches, const scene::RayCaster& /*caster*/, uint32_t i,
                  int resolution, std::vector<float>* row) {
  thread_local HemicubeBuffer buffer;
  rasterize_hemicube(patches, i, resolution, &buffer);
  hemicube_form_factors(buffer, patches.size(), row);
}

}  // namespace prt::radiosity
