// scene/field_scene.h — the bake benchmark scene: a square ground plane with a few spheres and
// boxes resting on it, tessellated to a requested vertex count (shape_layout.h), for diffuse
// and glossy bakes at 0.5–5 million vertices.
//
// Frame: glTF's (+Y up); units: metres. The ground is 24 m × 24 m centred on the origin
// (primitive "ground"); on it three grey spheres (radii 1, 0.6, 0.45), one coloured sphere
// (radius 0.8), two grey boxes and one coloured box (no bottom faces), and one camera looking at
// them from +Z, 3.5 m up. The ground holds about 88% of the vertices (at 0.5M and above).
// Diffuse materials: "ground" (grey 0.5), "grey" (0.7), "red" (0.75, 0.15, 0.1).
// Glossy (glTF metallic-roughness, the GGX BRDF of prt/brdf with α = roughness²): "ground"
// a rough dielectric (roughness 0.7), "glossy_grey" (roughness 0.3), "glossy_red" (0.25),
// "metal" (metallic 1, roughness 0.35) on the largest sphere, "rough_gold" (metallic 1,
// roughness 0.5) on the boxes.
#pragma once

#include "scene/shape_layout.h"

namespace prt::scene {

ShapeLayout make_field_layout(bool glossy);

}  // namespace prt::scene
