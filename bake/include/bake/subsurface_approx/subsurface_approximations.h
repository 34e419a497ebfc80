// bake/subsurface_approx/subsurface_approximations.h — the real-time approximations of
// subsurface scattering, each written as ordinary SH transfer (the .prt kind every relight path
// reads), to be measured against the dipole bake.
//
// Input: the scene, the dipole material in scene units (prt/subsurface/dipole.h), a group per
// vertex (a translucent object, or −1: opaque), and the grey shadowed transfer S with the albedo
// kept apart (bake_transfer with kind Shadowed, keep_albedo_apart: Σ_k S_k L_k = E/π, E the
// shadowed irradiance). Output: three channels, albedo folded, kind Shadowed, the same
// vertices, order and fingerprint as S; opaque vertices get Lambert with their own albedo,
// T_c = ρ_c·S. For a translucent vertex v and channel c (R_c = R_total of the channel, σ_tr,c
// its effective transport coefficient, ℓ_c = 1/σ_tr,c its diffuse mean free path):
//   kLambert        T_c = R_c·S_v: a diffuse BRDF whose albedo is the dipole's total diffuse
//                   reflectance (good for large σ_t, no light through thin parts).
//   kNormalBlur     T_c = (R_c/π)·[U(n_c) − (2π/N) Σ_s (1 − V(ω_s)) max(n_c·ω_s, 0) Y(ω_s)]:
//                   the clamped cosine about the blurred normal n_c (the vertex normals blurred
//                   over the surface with σ = ℓ_c, surface_blur.h, renormalised), U its analytic
//                   SH, minus the part of it that rays blocked: N uniform directions ω_s over the
//                   geometric upper hemisphere (Owen-scrambled Sobol', seeded per vertex), V the
//                   ray visibility. Directions below the tangent plane are not tested: the
//                   technique evaluates n_c·L without a self-shadow test, so its lobe wraps past
//                   the terminator.
//   kMeshDiffusion  T_c = Σ_i w_i,c · blur_{v_i}(S)_v: the shadowed irradiance blurred over the
//                   surface (surface_blur.h, straight-line distance, normalised) by each Gaussian
//                   of the fit of R_d (gaussian_sum_fit.h) and summed with its weights.
//   kDepthMap       T_c = R_c·S_v + (4π/M) Σ_d [n_v·ω_d < 0] (R_c/π) e^{−σ_tr,c t_d} cos_d Y(ω_d):
//                   Lambert for the lit side plus the light transmitted through the object from
//                   each of M spherical-Fibonacci directions ω_d behind v's tangent plane; t_d the
//                   thickness between v and the surface a shadow map along ω_d sees (thickness()
//                   below: an exact, infinite-resolution shadow map), cos_d = max(n_e·ω_d, 0) at
//                   that entry point. Zero thickness transmits R_c, as the surface reflects.
//                   Light whose shadow-map surface belongs to another object is blocked.
// References: d'Eon & Luebke 2007 (GPU Gems 3 ch. 14); Green 2004 (GPU Gems ch. 16, depth-map
// translucency); Jensen et al. 2001. Measured in docs/SUBSURFACE_APPROXIMATIONS.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bake/subsurface_approx/gaussian_sum_fit.h"
#include "prt/formats/transfer_data.h"
#include "prt/subsurface/dipole.h"
#include "scene/scene.h"

namespace prt::scene {
class RayCaster;
}  // namespace prt::scene

namespace prt::bake {

enum class SubsurfaceApproximation { kLambert, kNormalBlur, kMeshDiffusion, kDepthMap };

// "lambert-rtotal", "normal-blur", "mesh-diffusion", "depth-map".
const char* approximation_name(SubsurfaceApproximation a);
inline constexpr SubsurfaceApproximation kAllApproximations[] = {
    SubsurfaceApproximation::kLambert, SubsurfaceApproximation::kNormalBlur,
    SubsurfaceApproximation::kMeshDiffusion, SubsurfaceApproximation::kDepthMap};

struct SubsurfaceApproximationInputs {
  const scene::Scene* scene = nullptr;
  const scene::RayCaster* caster = nullptr;     // over *scene
  subsurface::DipoleMaterial material;          // coefficients in scene units
  std::vector<int32_t> group;                   // per vertex: translucent object, or −1
  const prt::TransferData* shadowed = nullptr;  // grey, albedo kept apart (see above)
  int normal_blur_samples = 256;                // N
  int depth_map_directions = 512;               // M
  int gaussians = 6;
  uint64_t seed = 1;
};

// Every primitive its own group, or only those named (primitive or material name); others −1.
std::vector<int32_t> translucent_groups(const scene::Scene& scene,
                                        const std::vector<std::string>& names = {});

// The transfer of one approximation (see above). Throws std::invalid_argument on inputs that do
// not match (sizes, a shadowed transfer that is not grey with the albedo kept apart).
prt::TransferData approximate_subsurface(const SubsurfaceApproximationInputs& in,
                                         SubsurfaceApproximation which);

// The shadow-map thickness at vertex v toward the light direction `toward_light` (unit): the
// distance from v to the first surface a ray from far outside (`far` along toward_light: pass
// 2 × the scene's extent) meets on its way to v. entry_cos = max(n_e·toward_light, 0) at that
// surface (interpolated normal; 0 for a back face); thickness 0 and entry_cos 0 (nothing to enter
// through) when nothing lies before v; blocked when that surface belongs to another group.
struct Thickness {
  double thickness = 0, entry_cos = 0;
  bool blocked = false;
};
Thickness shadow_map_thickness(const scene::RayCaster& caster, const scene::Scene& scene,
                               const std::vector<int32_t>& group, uint32_t v,
                               const glm::vec3& toward_light, float far);

// The M directions of kDepthMap: z_i = 1 − (2i + 1)/M, φ_i = i·π(3 − √5).
std::vector<glm::dvec3> fibonacci_directions(int count);

}  // namespace prt::bake
