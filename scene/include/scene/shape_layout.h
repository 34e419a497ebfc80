// scene/shape_layout.h — a scene described as named parts made of simple shapes (rectangular
// panels with rectangular holes, boxes, UV spheres, open cylinders), tessellated at one cell
// size, and the cell size that brings the tessellation to a requested vertex or triangle count.
// The procedural level and field scenes (scene/level_scene.h, scene/field_scene.h) are layouts.
//
// Frame: glTF's (right-handed, +Y up); units: the caller's. Winding is counter-clockwise seen
// from the front (scene/procedural_mesh.h's convention); normals are exact per shape (flat for
// panels and box faces, radial for spheres and cylinders).
// Tessellation at cell size h: every length ℓ that a shape splits into equal segments gets
// segments(ℓ, h) = max(1, ⌈ℓ/h⌉) of them — a panel's spans between hole edges, a box face's
// sides, a cylinder's height; a sphere gets max(kMinSphereRings, ⌈πr/h⌉) rings and twice as
// many segments, a cylinder max(kMinCylinderSegments, ⌈2πr/h⌉) segments. So no edge is longer
// than about h, and counts grow as 1/h² for the large shapes. layout_counts() gives the exact
// vertex and triangle counts of tessellate_layout() at any h without building it; both are
// non-increasing in h, so cell_size_for_count() can bisect.
// Each part becomes one primitive (its name, material, albedo, emission, BRDF); its shapes do not
// share vertices with each other (edges stay sharp), a panel's cells share theirs.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/brdf/material.h"
#include "scene/scene.h"

namespace prt::scene {

constexpr int kMinSphereRings = 5;
constexpr int kMinCylinderSegments = 12;

// A rectangle corner + s·u + t·v, s ∈ [0, length_u], t ∈ [0, length_v] (u, v unit and
// orthogonal), facing cross(u, v), with rectangular holes [s0, s1] × [t0, t1] (inside the
// rectangle, not overlapping): the grid lines run through every hole edge, and the cells inside
// a hole are left out, so a hole's border is a line of shared vertices.
struct PanelShape {
  struct Hole {
    double s0 = 0, s1 = 0, t0 = 0, t1 = 0;
  };
  glm::dvec3 corner{0.0}, u{1, 0, 0}, v{0, 1, 0};
  double length_u = 1, length_v = 1;
  std::vector<Hole> holes;
};

// The panel corner + s·u + t·v, s ∈ [0, length_u], t ∈ [0, length_v], without holes.
PanelShape make_panel(glm::dvec3 corner, glm::dvec3 u, double length_u, glm::dvec3 v,
                      double length_v);

// An axis-aligned box with outward faces, +X, −X, +Y, −Y, +Z, −Z; `bottom` false leaves out the
// −Y face (an object resting on a floor: that face would be hidden).
struct BoxShape {
  glm::dvec3 min{0.0}, max{1.0};
  bool bottom = true;
};

// A UV sphere with outward normals (make_uv_sphere's vertex order).
struct SphereShape {
  glm::dvec3 center{0.0};
  double radius = 1;
};

// A vertical cylinder's side, from base.y to base.y + height, without caps, normals outward
// (a pillar from floor to ceiling).
struct CylinderShape {
  glm::dvec3 base{0.0};
  double radius = 1, height = 1;
};

struct LayoutPart {
  std::string name, material;
  glm::vec3 albedo{0.8f};
  glm::vec3 emission{0.f};
  std::optional<brdf::Material> brdf;
  std::vector<PanelShape> panels;
  std::vector<BoxShape> boxes;
  std::vector<SphereShape> spheres;
  std::vector<CylinderShape> cylinders;
};

struct ShapeLayout {
  std::vector<LayoutPart> parts;
  std::vector<SceneCamera> cameras;
  std::string source_path;  // "procedural:NAME"
};

struct LayoutCounts {
  std::size_t vertices = 0, triangles = 0;
};

// max(1, ⌈length / cell⌉) (with a relative slack of 1e-9, so that a length that is a whole
// number of cells is not split once more by rounding).
int segments_for(double length, double cell);

// Exact counts of tessellate_layout(layout, cell).
LayoutCounts layout_counts(const ShapeLayout& layout, double cell);

// The scene: one primitive per part, in order (panels, boxes, spheres, cylinders), cameras
// copied. Throws std::invalid_argument when cell is not finite and positive.
Scene tessellate_layout(const ShapeLayout& layout, double cell);

// The cell size whose counts (vertices when `vertices`, else triangles) come closest to
// `target`, by bisection on log h in [1e-5, 1e3] × the layout's extent. The caller checks the
// result against its tolerance (the counts move in steps, so a target may fall between two).
double cell_size_for_count(const ShapeLayout& layout, std::size_t target, bool vertices);

}  // namespace prt::scene
