// scene/scene_loader.h — loading a Scene from glTF 2.0 (.gltf, .glb) or Wavefront OBJ (.obj).
//
// Frame: glTF's (right-handed, +Y up, cameras look down -Z). OBJ files are taken as they are
// (no axis change); units are the file's.
//
// glTF (through tinygltf): every TRIANGLES primitive of every mesh of every node of the
// default scene (scene 0 when none is set), nodes depth-first in child order, primitives in
// order. Node transforms (matrix or TRS) are composed down the hierarchy and applied; NORMAL
// is transformed by the inverse transpose and renormalised (a mirroring transform flips the
// winding, which is restored). POSITION is required; indices may be u8/u16/u32 or absent.
// Primitives of other modes (points, lines, strips, fans) are skipped and reported in one
// warning line on stderr. Albedo = pbrMetallicRoughness.baseColorFactor rgb, stored as it
// is (the baker refuses albedo >= 1); a primitive with no material, or with neither a factor nor
// a usable texture (factor left at 1), gets 0.8 grey instead of the spec's white, counted in
// Scene::default_albedo_primitives (prt bake says so). Perspective cameras attached to nodes become
// SceneCameras: eye = the node's world position, up = the node's +Y, yfov, and target the point
// of the view axis (the node's -Z) nearest the centre of the scene's bounding box, at least 1% of
// the box's diagonal ahead (glTF gives no target; a turntable orbits the scene, not a point a
// unit in front of the eye).
// Textures: a material's baseColorTexture is read (scene/texture.h): its texCoord set
// (TEXCOORD_n: float, or normalised unsigned byte/short), its texture's sampler (wrapS, wrapT,
// magFilter, minFilter) and image, PNG or JPEG, from a file beside the .gltf (URI
// percent-decoding), a data: URI or a buffer view (GLB), decoded through the OpenImageIO plugin
// (scene/image_codec.h) and linearised as sRGB. Albedo = baseColorFactor × the texture (clamped to
// kMaxTexturedAlbedo). Besides base-colour images only the BRDF parameter textures are decoded
// (metallicRoughnessTexture, KHR_materials_specular's specularTexture and specularColorTexture,
// KHR_materials_anisotropy's anisotropyTexture, for per-vertex BRDF variants and tangent
// rotations: scene/brdf_variants.h; one that cannot be used is recorded in
// ScenePrimitive::brdf_texture_problem, not warned about); normal and other maps are never read. A
// texture that cannot be used — its file missing (real assets are often shipped geometry-only), not
// PNG/JPEG, corrupt, over kMaxTextureTexels, or the primitive lacks its TEXCOORD_n — is NOT an
// error: one warning line on stderr ("PATH: warning: ..." naming the image file or index) and the
// material falls back to its baseColorFactor (0.8 grey when that is the default white). Alpha is
// ignored; KHR_texture_transform is not applied. Missing buffers (.bin) ARE an error.
//
// OBJ (through tinyobjloader): shapes in order; quads and polygons are triangulated; negative
// indices and CRLF line endings are handled. Albedo = the MTL's Kd (0.8 grey when a face has
// no material; a shape takes its first face's material). A material's map_Kd replaces Kd (as
// Blender reads it): the image file (relative to the OBJ's folder; '\\' read as '/'), decoded
// like a glTF texture and linearised as sRGB (unless `-colorspace linear`), with its options
// -clamp on (CLAMP_TO_EDGE; else REPEAT), -s and -o (scale and offset of the coordinates);
// `vt` coordinates have v up, so they become (u, 1 − v). A map_Kd that cannot be read, or a
// shape with a face corner lacking `vt`, gives one warning line and Kd. A textured shape makes
// one vertex per unique (position, normal, texture coordinate) triple in first-seen order (a
// texture seam splits a position), its missing normals computed over the positions (no shading
// seam along texture seams). Otherwise: when every face corner of a shape
// has a `vn`, one vertex is made per unique (position, normal) index pair, in first-seen order.
// Otherwise normals are computed and the vertices are the file's `v` entries in file order: a
// file with one shape keeps all of them, including `v` lines no face uses (they get the +Y
// fallback normal), so vertex i is the file's i-th `v` (stanford-bunny.obj: 35,947 v lines,
// 34,834 of them used, 35,947 vertices); with several shapes each keeps the entries it uses.
//
// Materials (BRDFs, ScenePrimitive::brdf; docs/BRDF.md "Materials from scenes"): glTF
// pbrMetallicRoughness with KHR_materials_specular, KHR_materials_ior and
// KHR_materials_anisotropy becomes GGX over a Lambert layer (the mapping, its defaults and its
// departures from the spec: scene/src/gltf_materials.h); glTF TANGENT (float VEC4) is read into
// Scene::tangents, transformed like a surface direction (w flipped by a mirroring transform);
// values that are not finite, of zero length or with w other than ±1 become zero (a frame is
// generated there, scene/tangent_frames.h) with one warning line. An anisotropic glTF material
// without TANGENT keeps its TEXCOORD_0 for tangents from the UVs. OBJ: a material whose Ks is
// not zero is normalised Blinn-Phong (k_L = Kd, k_G = Ks, s = Ns) unless `illum 1` (the MTL
// spec's "no specular"); illum 0 (also what a file without illum reads as), 2 and the higher
// models get the highlight (their reflection, refraction and transparency are not modelled).
// Where Kd + Ks > 1 in a channel, k_G is lowered to 1 − Kd (one note on stderr). A negative Ns
// is an error. The diffuse path (albedo) is the same with or without a BRDF.
//
// Emitters (both formats): ScenePrimitive::material is the material's name and
// ScenePrimitive::emission its emitted radiance: glTF emissiveFactor × the
// KHR_materials_emissive_strength extension's emissiveStrength (1 when absent); OBJ Ke. Values
// are stored as they are (consumers that use them check them).
//
// Both: a textured primitive's `albedo` is factor × the texture's mean and each of its vertices'
// albedo the texture (bilinear) at the vertex (scene/scene.h); missing normals are computed
// (scene/mesh_normals.h: area x angle weighting, +Y fallback); degenerate triangles (repeated
// indices, or area <= 1e-12 * extent^2) are removed and counted in
// Scene::skipped_degenerate_triangles; vertices keep the file's order per primitive.
//
// Errors throw SceneError with one line "PATH: problem": unreadable or unparsable file (the
// parser's messages condensed to one line), missing buffer, index out of range, NaN/Inf
// position (the vertex is named), no triangles at all, unsupported extension.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/material_override.h"
#include "scene/scene.h"

namespace prt::scene {

struct LoadOptions {
  // Replaces every material's albedo when set; base-colour textures are then not even decoded
  // (flat colour).
  std::optional<glm::vec3> albedo_override;
  // Per-material BRDF overrides (scene/material_override.h), applied in order after the
  // albedo override; one that matches no material or primitive is an error.
  std::vector<MaterialOverride> material_overrides;
};

// Loads a scene, dispatching on the file extension (case-insensitive): .gltf, .glb, .obj.
Scene load_scene(const std::string& path, const LoadOptions& options = {});

// A glTF URI's percent escapes decoded ("a%20b.bin" → "a b.bin"), as the loader resolves files
// beside a .gltf; malformed escapes are kept as they are.
std::string decode_uri(const std::string& uri);

}  // namespace prt::scene
