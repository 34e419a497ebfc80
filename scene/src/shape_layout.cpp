// Tessellation of shape layouts at a cell size (see scene/shape_layout.h).
#include "scene/shape_layout.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "sh/constants.h"

namespace prt::scene {
namespace {

using sh::kPi;

// The lattice of a panel: its grid lines in s and t and which cells and vertices it keeps.
struct PanelGrid {
  std::vector<double> s, t;       // grid-line coordinates, increasing, from 0 to the lengths
  std::vector<char> cell_kept;    // (s.size() − 1) × (t.size() − 1), row-major in t
  std::vector<char> vertex_kept;  // s.size() × t.size(), row-major in t
  std::size_t vertices = 0, triangles = 0;
};

// Grid lines over [0, length] through every cut, each span split into segments_for(span, cell).
std::vector<double> grid_lines(double length, std::vector<double> cuts, double cell) {
  cuts.push_back(0.0);
  cuts.push_back(length);
  for (double& c : cuts) c = std::clamp(c, 0.0, length);
  std::sort(cuts.begin(), cuts.end());
  const double merge = 1e-9 * std::max(length, 1e-30);
  std::vector<double> breaks;
  for (double c : cuts)
    if (breaks.empty() || c - breaks.back() > merge) breaks.push_back(c);
  if (breaks.size() < 2) breaks = {0.0, length};
  breaks.back() = length;
  std::vector<double> lines;
  for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
    const double a = breaks[k], b = breaks[k + 1];
    const int n = segments_for(b - a, cell);
    for (int i = 0; i < n; ++i) lines.push_back(i == 0 ? a : a + (b - a) * i / n);
  }
  lines.push_back(length);
  return lines;
}

PanelGrid panel_grid(const PanelShape& panel, double cell, bool with_flags) {
  PanelGrid g;
  std::vector<double> cuts_s, cuts_t;
  for (const PanelShape::Hole& h : panel.holes) {
    cuts_s.insert(cuts_s.end(), {h.s0, h.s1});
    cuts_t.insert(cuts_t.end(), {h.t0, h.t1});
  }
  g.s = grid_lines(panel.length_u, cuts_s, cell);
  g.t = grid_lines(panel.length_v, cuts_t, cell);
  const std::size_t ns = g.s.size(), nt = g.t.size();
  if (panel.holes.empty()) {  // every cell and vertex: no flags needed
    g.vertices = ns * nt;
    g.triangles = 2 * (ns - 1) * (nt - 1);
    if (with_flags) {
      g.cell_kept.assign((ns - 1) * (nt - 1), 1);
      g.vertex_kept.assign(ns * nt, 1);
    }
    return g;
  }
  if (!with_flags) {  // counted: a hole's edges are grid lines, and holes do not touch
    g.vertices = ns * nt;
    g.triangles = 2 * (ns - 1) * (nt - 1);
    for (const PanelShape::Hole& h : panel.holes) {
      const auto span = [](const std::vector<double>& lines, double a, double b, double length) {
        // Intervals inside [a, b], and the lines whose every neighbouring cell lies in it.
        const double slack = 1e-9 * std::max(length, 1e-30);
        std::size_t inside = 0;
        for (double x : lines) inside += (x > a - slack && x < b + slack) ? 1 : 0;
        const std::size_t intervals = inside > 0 ? inside - 1 : 0;
        std::size_t removable = intervals > 0 ? intervals - 1 : 0;
        if (intervals > 0 && a <= slack) ++removable;
        if (intervals > 0 && b >= length - slack) ++removable;
        return std::pair<std::size_t, std::size_t>(intervals, removable);
      };
      const auto [is, rs] = span(g.s, h.s0, h.s1, panel.length_u);
      const auto [it, rt] = span(g.t, h.t0, h.t1, panel.length_v);
      g.triangles -= 2 * is * it;
      g.vertices -= rs * rt;
    }
    return g;
  }
  g.cell_kept.assign((ns - 1) * (nt - 1), 1);
  for (std::size_t j = 0; j + 1 < nt; ++j) {
    const double tc = 0.5 * (g.t[j] + g.t[j + 1]);
    for (std::size_t i = 0; i + 1 < ns; ++i) {
      const double sc = 0.5 * (g.s[i] + g.s[i + 1]);
      for (const PanelShape::Hole& h : panel.holes)
        if (sc > h.s0 && sc < h.s1 && tc > h.t0 && tc < h.t1) g.cell_kept[j * (ns - 1) + i] = 0;
    }
  }
  g.vertex_kept.assign(ns * nt, 0);
  for (std::size_t j = 0; j + 1 < nt; ++j)
    for (std::size_t i = 0; i + 1 < ns; ++i)
      if (g.cell_kept[j * (ns - 1) + i]) {
        g.triangles += 2;
        for (std::size_t dj = 0; dj < 2; ++dj)
          for (std::size_t di = 0; di < 2; ++di) g.vertex_kept[(j + dj) * ns + i + di] = 1;
      }
  for (char k : g.vertex_kept) g.vertices += k ? 1 : 0;
  return g;
}

uint32_t add_vertex(Scene& scene, glm::dvec3 position, glm::dvec3 normal) {
  scene.positions.emplace_back(glm::vec3(position));
  scene.normals.emplace_back(glm::vec3(glm::normalize(normal)));
  return static_cast<uint32_t>(scene.positions.size() - 1);
}

void add_panel(Scene& scene, const PanelShape& panel, double cell) {
  const PanelGrid g = panel_grid(panel, cell, true);
  const std::size_t ns = g.s.size(), nt = g.t.size();
  const glm::dvec3 normal = glm::normalize(glm::cross(panel.u, panel.v));
  std::vector<uint32_t> index(ns * nt, 0);
  for (std::size_t j = 0; j < nt; ++j)
    for (std::size_t i = 0; i < ns; ++i)
      if (g.vertex_kept[j * ns + i])
        index[j * ns + i] =
            add_vertex(scene, panel.corner + g.s[i] * panel.u + g.t[j] * panel.v, normal);
  for (std::size_t j = 0; j + 1 < nt; ++j)
    for (std::size_t i = 0; i + 1 < ns; ++i) {
      if (!g.cell_kept[j * (ns - 1) + i]) continue;
      const uint32_t a = index[j * ns + i], b = index[j * ns + i + 1];
      const uint32_t c = index[(j + 1) * ns + i + 1], d = index[(j + 1) * ns + i];
      scene.triangles.emplace_back(a, b, c);  // counter-clockwise seen from cross(u, v)
      scene.triangles.emplace_back(a, c, d);
    }
}

// The faces of a box as panels (+X, −X, +Y, −Y, +Z, −Z; −Y only with `bottom`), each with
// cross(u, v) pointing out of the box.
std::vector<PanelShape> box_faces(const BoxShape& box) {
  const glm::dvec3 lo = box.min, hi = box.max, d = hi - lo;
  const glm::dvec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  std::vector<PanelShape> faces = {
      make_panel({hi.x, lo.y, lo.z}, y, d.y, z, d.z), make_panel(lo, z, d.z, y, d.y),
      make_panel({lo.x, hi.y, lo.z}, z, d.z, x, d.x), make_panel(lo, x, d.x, z, d.z),
      make_panel({lo.x, lo.y, hi.z}, x, d.x, y, d.y), make_panel(lo, y, d.y, x, d.x)};
  if (!box.bottom) faces.erase(faces.begin() + 3);
  return faces;
}

int sphere_rings(const SphereShape& s, double cell) {
  return std::max(kMinSphereRings, segments_for(kPi * s.radius, cell));
}

int cylinder_segments(const CylinderShape& c, double cell) {
  return std::max(kMinCylinderSegments, segments_for(2.0 * kPi * c.radius, cell));
}

// Adds (a, b, c), flipped when its face normal disagrees with the sum of its vertex normals.
void add_oriented_triangle(Scene& scene, uint32_t a, uint32_t b, uint32_t c) {
  const glm::dvec3 pa(scene.positions[a]), pb(scene.positions[b]), pc(scene.positions[c]);
  const glm::dvec3 n =
      glm::dvec3(scene.normals[a]) + glm::dvec3(scene.normals[b]) + glm::dvec3(scene.normals[c]);
  if (glm::dot(glm::cross(pb - pa, pc - pa), n) < 0.0) std::swap(b, c);
  scene.triangles.emplace_back(a, b, c);
}

void add_sphere(Scene& scene, const SphereShape& sphere, double cell) {
  const int rings = sphere_rings(sphere, cell), segments = 2 * rings;
  const glm::dvec3 c = sphere.center;
  const double r = sphere.radius;
  const uint32_t top = add_vertex(scene, c + glm::dvec3(0, r, 0), {0, 1, 0});
  for (int ring = 1; ring < rings; ++ring) {
    const double theta = kPi * ring / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * kPi * s / segments;
      const glm::dvec3 dir(std::sin(theta) * std::cos(phi), std::cos(theta),
                           std::sin(theta) * std::sin(phi));
      add_vertex(scene, c + r * dir, dir);
    }
  }
  const uint32_t bottom = add_vertex(scene, c - glm::dvec3(0, r, 0), {0, -1, 0});
  const auto at = [&](int ring, int s) {  // ring 1..rings−1
    return top + 1 + static_cast<uint32_t>((ring - 1) * segments + s % segments);
  };
  for (int s = 0; s < segments; ++s) {
    add_oriented_triangle(scene, top, at(1, s), at(1, s + 1));
    for (int ring = 1; ring + 1 < rings; ++ring) {
      add_oriented_triangle(scene, at(ring, s), at(ring, s + 1), at(ring + 1, s + 1));
      add_oriented_triangle(scene, at(ring, s), at(ring + 1, s + 1), at(ring + 1, s));
    }
    add_oriented_triangle(scene, bottom, at(rings - 1, s), at(rings - 1, s + 1));
  }
}

void add_cylinder(Scene& scene, const CylinderShape& cylinder, double cell) {
  const int segments = cylinder_segments(cylinder, cell);
  const int rings = segments_for(cylinder.height, cell);
  const uint32_t first = static_cast<uint32_t>(scene.positions.size());
  for (int k = 0; k <= rings; ++k) {
    const double y = k == rings ? cylinder.height : cylinder.height * k / rings;
    for (int s = 0; s < segments; ++s) {
      const double phi = 2.0 * kPi * s / segments;
      const glm::dvec3 n(std::cos(phi), 0.0, std::sin(phi));
      add_vertex(scene, cylinder.base + cylinder.radius * n + glm::dvec3(0, y, 0), n);
    }
  }
  const auto at = [&](int k, int s) {
    return first + static_cast<uint32_t>(k * segments + s % segments);
  };
  for (int k = 0; k < rings; ++k)
    for (int s = 0; s < segments; ++s) {  // up × along φ points outward
      scene.triangles.emplace_back(at(k, s), at(k + 1, s), at(k + 1, s + 1));
      scene.triangles.emplace_back(at(k, s), at(k + 1, s + 1), at(k, s + 1));
    }
}

LayoutCounts part_counts(const LayoutPart& part, double cell) {
  LayoutCounts n;
  const auto add_panel_counts = [&](const PanelShape& p) {
    const PanelGrid g = panel_grid(p, cell, false);
    n.vertices += g.vertices;
    n.triangles += g.triangles;
  };
  for (const PanelShape& p : part.panels) add_panel_counts(p);
  for (const BoxShape& b : part.boxes)
    for (const PanelShape& f : box_faces(b)) add_panel_counts(f);
  for (const SphereShape& s : part.spheres) {
    const std::size_t rings = static_cast<std::size_t>(sphere_rings(s, cell));
    n.vertices += 2 + (rings - 1) * 2 * rings;
    n.triangles += 2 * 2 * rings * (rings - 1);
  }
  for (const CylinderShape& c : part.cylinders) {
    const std::size_t segments = static_cast<std::size_t>(cylinder_segments(c, cell));
    const std::size_t rings = static_cast<std::size_t>(segments_for(c.height, cell));
    n.vertices += segments * (rings + 1);
    n.triangles += 2 * segments * rings;
  }
  return n;
}

// The diagonal of the layout's bounds (1 when it is empty).
double layout_extent(const ShapeLayout& layout) {
  glm::dvec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  const auto grow = [&](glm::dvec3 p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  };
  for (const LayoutPart& part : layout.parts) {
    for (const PanelShape& p : part.panels) {
      grow(p.corner);
      grow(p.corner + p.length_u * p.u + p.length_v * p.v);
    }
    for (const BoxShape& b : part.boxes) {
      grow(b.min);
      grow(b.max);
    }
    for (const SphereShape& s : part.spheres) {
      grow(s.center - glm::dvec3(s.radius));
      grow(s.center + glm::dvec3(s.radius));
    }
    for (const CylinderShape& c : part.cylinders) {
      grow(c.base - glm::dvec3(c.radius, 0, c.radius));
      grow(c.base + glm::dvec3(c.radius, c.height, c.radius));
    }
  }
  const double d = hi.x >= lo.x ? glm::length(hi - lo) : 0.0;
  return d > 0.0 ? d : 1.0;
}

}  // namespace

PanelShape make_panel(glm::dvec3 corner, glm::dvec3 u, double length_u, glm::dvec3 v,
                      double length_v) {
  PanelShape p;
  p.corner = corner;
  p.u = u;
  p.v = v;
  p.length_u = length_u;
  p.length_v = length_v;
  return p;
}

int segments_for(double length, double cell) {
  const double n = std::ceil(length / cell * (1.0 - 1e-9));
  return n < 1.0 ? 1 : n > 1e9 ? 1'000'000'000 : static_cast<int>(n);
}

LayoutCounts layout_counts(const ShapeLayout& layout, double cell) {
  LayoutCounts total;
  for (const LayoutPart& part : layout.parts) {
    const LayoutCounts n = part_counts(part, cell);
    total.vertices += n.vertices;
    total.triangles += n.triangles;
  }
  return total;
}

Scene tessellate_layout(const ShapeLayout& layout, double cell) {
  if (!(cell > 0.0) || !std::isfinite(cell))
    throw std::invalid_argument("the cell size must be a finite positive number");
  const LayoutCounts counts = layout_counts(layout, cell);
  Scene scene;
  scene.positions.reserve(counts.vertices);
  scene.normals.reserve(counts.vertices);
  scene.albedo.reserve(counts.vertices);
  scene.triangles.reserve(counts.triangles);
  for (const LayoutPart& part : layout.parts) {
    ScenePrimitive primitive;
    primitive.name = part.name;
    primitive.material = part.material;
    primitive.albedo = part.albedo;
    primitive.emission = part.emission;
    primitive.brdf = part.brdf;
    primitive.first_vertex = static_cast<uint32_t>(scene.positions.size());
    primitive.first_triangle = static_cast<uint32_t>(scene.triangles.size());
    for (const PanelShape& p : part.panels) add_panel(scene, p, cell);
    for (const BoxShape& b : part.boxes)
      for (const PanelShape& f : box_faces(b)) add_panel(scene, f, cell);
    for (const SphereShape& s : part.spheres) add_sphere(scene, s, cell);
    for (const CylinderShape& c : part.cylinders) add_cylinder(scene, c, cell);
    primitive.vertex_count = static_cast<uint32_t>(scene.positions.size()) - primitive.first_vertex;
    primitive.triangle_count =
        static_cast<uint32_t>(scene.triangles.size()) - primitive.first_triangle;
    scene.albedo.resize(scene.positions.size(), part.albedo);
    scene.primitives.push_back(std::move(primitive));
  }
  scene.cameras = layout.cameras;
  scene.source_path = layout.source_path;
  return scene;
}

double cell_size_for_count(const ShapeLayout& layout, std::size_t target, bool vertices) {
  const double extent = layout_extent(layout);
  double lo = std::log(extent * 1e-5), hi = std::log(extent * 1e3);
  const auto count = [&](double log_cell) {
    const LayoutCounts n = layout_counts(layout, std::exp(log_cell));
    return vertices ? n.vertices : n.triangles;
  };
  for (int i = 0; i < 60 && hi - lo > 1e-12; ++i) {  // count(lo) > target ≥ count(hi)
    const double mid = 0.5 * (lo + hi);
    (count(mid) > target ? lo : hi) = mid;
  }
  const double miss_lo = std::fabs(double(count(lo)) - double(target));
  const double miss_hi = std::fabs(double(count(hi)) - double(target));
  return std::exp(miss_lo < miss_hi ? lo : hi);
}

}  // namespace prt::scene
