// relight/renderer.h — a preview ray caster that displays per-vertex exit radiance.
//
// Frame: glTF's (+Y up); the camera conventions are those of relight/camera.h.
// Each pixel averages N×N stratified sub-samples at the centres of an N×N grid of cells
// (deterministic, no randomness). A primary ray that hits triangle (v0, v1, v2) at Embree
// barycentrics (u, v) takes the radiance (1−u−v)·B(v0) + u·B(v1) + v·B(v2) (Gouraud shading of
// the relit vertex radiance) when it meets the triangle's front (counter-clockwise as seen by the
// ray, glTF's winding, scene/ray_caster.h). The back of a surface is black: the vertex radiance
// is the light leaving the front (a bake's hemisphere, a radiosity patch's lit side), and the
// back of a one-sided surface has none — so a wall seen from outside a room is black, never
// painted with the inside's light. Every image of prt (relight, radiosity, emitter responses,
// the demo, the report) is drawn here. A ray that misses shows the
// environment: when the lighting was rotated by M (row-major 3×3, so the rotated environment is
// g(ω) = f(Mᵀω), the convention of sh/rotation.h), the background in direction d is the source
// map bilinearly sampled at Mᵀd, so the visible sky turns with the light. Without a background
// misses are black. Output is linear radiance, RGB float, row 0 at the top.
// Albedo kept apart (RenderOptions::multiply_albedo, for coefficient files with albedo_folded =
// false): the vertex values are radiance per unit albedo, and each sub-sample multiplies the
// interpolated value by the surface's albedo at the hit, Scene::albedo_at — the base-colour
// texture read per sub-pixel with trilinear mipmapping (scene/texture.h), its footprint the
// sub-pixel's width at the hit, t·δ/(N·√max(|cos θ|, 1/16)) (δ = 2·tan(yfov/2)/height the
// angle of a pixel at the image centre, θ the angle between the ray and the triangle's normal:
// the geometric mean of the footprint's two axes, capped at grazing angles).
// Rows are rendered in parallel with TBB; the result does not depend on the thread count.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "relight/camera.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::relight {

struct Image {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 · width · height, row-major, row 0 at the top
};

struct RenderOptions {
  int width = 960;
  int height = 540;
  int samples_per_axis = 3;      // N: N×N sub-samples per pixel
  bool multiply_albedo = false;  // the vertex radiance is per unit albedo (see above)
  // Progress (optional): called with the number of rows just finished, from the rendering
  // threads, possibly concurrently (so it must be thread-safe); the counts add up to height.
  std::function<void(int rows)> rows_done;
};

// The identity, for unrotated backgrounds.
constexpr std::array<double, 9> kIdentityRotation{1, 0, 0, 0, 1, 0, 0, 0, 1};

// Throws std::runtime_error (one line) when vertex_radiance_rgb is not 3 floats per scene vertex,
// the size or sample count is out of range (1..16384 pixels a side, 1..16 samples per axis), or
// the camera is degenerate.
Image render(const scene::Scene& scene, const scene::RayCaster& caster,
             const std::vector<float>& vertex_radiance_rgb, const sh::EnvMap* background,
             const std::array<double, 9>& background_rotation, const Camera& camera,
             const RenderOptions& options);

// The background radiance seen in world direction `dir` (unit) for lighting rotated by M:
// the source map sampled at Mᵀ·dir. Used by render() for misses.
void look_up_background(const sh::EnvMap& background, const std::array<double, 9>& rotation,
                        const glm::vec3& dir, float rgb[3]);

}  // namespace prt::relight
