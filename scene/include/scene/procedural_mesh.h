// scene/procedural_mesh.h — analytic test meshes (quads, boxes, spheres, a spherical cavity, a
// well) and the bundled demo scene.
//
// Frame: glTF's (right-handed, +Y up). Units: whatever the caller passes.
// Every builder returns a Scene whose primitives are named, with unit normals per vertex,
// per-vertex albedo copied from the primitive, and no degenerate triangles. Triangles are
// wound counter-clockwise when seen from the side their vertex normals point to (so a face
// normal cross(b - a, c - a) agrees with the vertex normals).
// Segment/ring counts below their minimum are raised to it (quad: 1, sphere: rings 2 and
// segments 3, cavity: rings 1 and segments 3, well: segments 3 and rings 1).
//
// The cavity and the well exist for analytic checks with closed-form answers:
//   - spherical cavity with an opening of polar half-angle a: every inner point sees the
//     opening with cosine-weighted fraction f = (1 - cos a) / 2 (the cap area over 4 pi R^2);
//     the mesh opening is a polygon inscribed in that circle, so f of the mesh is slightly
//     smaller (by the polygon-vs-circle area ratio);
//   - well of radius R and depth h: the centre of the bottom sees the sky with cosine-weighted
//     fraction R^2 / (R^2 + h^2); the wall is a prism inscribed in the cylinder.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::scene {

// A (segments_u+1) x (segments_v+1) grid spanning the parallelogram corner + s*edge_u + t*edge_v.
// Front normal = normalize(cross(edge_u, edge_v)); vertex (i, j) sits at index
// j*(segments_u+1) + i, at corner + edge_u*i/segments_u + edge_v*j/segments_v, with texture
// coordinates (i/segments_u, j/segments_v) (untextured: set base_color_texture to texture it).
Scene make_quad(glm::vec3 corner, glm::vec3 edge_u, glm::vec3 edge_v, int segments_u,
                int segments_v, glm::vec3 albedo, std::string name = "quad");

// An axis-aligned box, one primitive; each of its 6 faces is its own segments x segments grid
// (vertices are not shared across faces, so edges stay sharp). Faces in the order
// +X, -X, +Y, -Y, +Z, -Z. Normals point out of the box, or into it when normals_inward.
Scene make_box(glm::vec3 min, glm::vec3 max, int segments, bool normals_inward, glm::vec3 albedo,
               std::string name = "box");

// A UV sphere with its poles on the Y axis: vertex 0 is the +Y pole, then rings-1 circles of
// `segments` vertices each (theta = pi*r/rings from +Y, phi = 2 pi*s/segments from +X toward
// +Z), then the -Y pole: 2 + (rings-1)*segments vertices, 2*segments*(rings-1) triangles.
// Normals radial (outward, or inward when normals_inward).
Scene make_uv_sphere(glm::vec3 center, float radius, int rings, int segments, bool normals_inward,
                     glm::vec3 albedo, std::string name = "sphere");

// The inside of a sphere of radius R centred at the origin with a circular opening around +Y
// of polar half-angle `opening_half_angle` (radians); normals point inward (toward the centre).
// Vertices: `rings` circles of `segments` vertices at theta_r = a + (pi - a)*r/rings
// (r = 0..rings-1; circle 0 is the rim of the opening), then the -Y pole. Vertices lie on the
// sphere (to float rounding). An opening_half_angle <= 0 closes the top with a +Y pole vertex
// (appended last). Primitive name "cavity".
Scene make_spherical_cavity(float radius, float opening_half_angle, int rings, int segments,
                            glm::vec3 albedo);

// A well: a vertical cylinder wall of radius R from y = -depth to 0 with normals inward
// (primitive "well_wall": rings+1 circles of `segments` vertices, circle k at
// y = -depth + depth*k/rings), plus a bottom disc at y = -depth with normal +Y (primitive
// "well_bottom": its vertex 0 is the centre, then `rings` circles of radius R*k/rings).
// The ground outside the well is not included.
Scene make_well(float radius, float depth, int segments, int rings, glm::vec3 albedo);

// A flat disc of the given radius centred at `center` in the plane of axis_u and axis_v (normal
// cross(axis_u, axis_v), normalised; axis_v is made orthogonal to it): vertex 0 is the centre,
// then `rings` circles of `segments` vertices, circle k of radius R·k/rings, vertex s at angle
// φ = 2π s/segments from axis_u toward axis_v. Scene::tangents run along the circles
// (−sin φ·u + cos φ·v, w = +1; the centre takes φ = 0's), the frame of a brushed (lathe-turned)
// surface. Primitive name `name`.
Scene make_disc(glm::vec3 center, glm::vec3 axis_u, glm::vec3 axis_v, float radius, int rings,
                int segments, glm::vec3 albedo, std::string name = "disc");

// Appends part's vertices, normals, albedo, texture coordinates and tangents (zeros for the side
// that has none, when the other has some), triangles (indices offset), primitives (ranges offset,
// textures kept), cameras, and adds its skip/computed counters.
void append_scene(Scene& into, const Scene& part);

// The bundled demo (data/demo.glb): a light-grey ground, a red and a green wall meeting in a
// corner, a white sphere and a white box near the walls, and one perspective camera looking
// slightly down into the corner from the open side. About 12k vertices.
Scene make_demo_scene();

// The glossy demo (prt make-scene --scene glossy): a Lambert grey floor (material "floor"), a
// glossy red dielectric sphere ("glossy_red": GGX α 0.09, F0 0.04, red Lambert layer), a
// brushed-steel disc standing on its rim ("brushed_steel": metal, α_x 0.684 along concentric
// circles, α_y 0.1225), a rough gold box ("rough_gold": metal, α 0.25), and one camera. Every
// vertex has a tangent (Scene::tangents: the disc's circles, elsewhere tangent_frames()).
// Each BRDF is one that glTF metallic-roughness (+ KHR_materials_specular,
// KHR_materials_anisotropy) expresses, so write_glb + load_scene gives it back.
Scene make_glossy_scene();

// glTF's metallic-roughness BRDF as the glTF loader makes it (MaterialModel::kGltf): GGX with
// widths alpha_x, alpha_y (α = roughness², wider along the tangent with anisotropy), Schlick's
// Fresnel with the dielectric F0 0.04, base colour and metallic as given.
brdf::Material gltf_brdf(brdf::Rgb base, double metallic, double alpha_x, double alpha_y);

}  // namespace prt::scene
