// bake/subsurface/subsurface_baker.h — diffuse SH transfer with subsurface scattering: the
// dipole BSSRDF (prt/subsurface/dipole.h) summed over the shadowed irradiance transfer of every
// vertex (bake/subsurface/dipole_gather.h), stored as an ordinary 3-channel .prt transfer file
// (albedo folded), so every relight path and the runtime read it unchanged.
//
// Per vertex v: S_v = (1/N) Σ_s V(ω_s) Y(ω_s), the shadowed transfer without albedo of
// bake/transfer_baker.h (irradiance transfer / π). A translucent vertex o (material m) exits
//     T_o,c = Σ_{i ∈ m} w_c(o, i) S_i   (dipole_gather.h: A_i R_d,c(|x_o − x_i|), own disc exact),
// so that a large flat slab under uniform radiance gives exit radiance R_total,c · E/π
// (derivation with the Fresnel terms in docs/SUBSURFACE.md); an opaque vertex keeps ρ_c S_v.
// Vertex areas: a third of each adjacent triangle's area. Distances: straight lines in space.
// Units: the coefficients are in mm⁻¹; mm_per_unit converts scene units (0: automatic, the
// scene's bounding-box diagonal taken as 100 mm, a figurine; default_mm_per_unit).
//
// Kinds: Shadowed — T as above. Interreflected — T = X + diag(ρ) H T through the baker's
// interreflection solve (bake/transfer_baker.h, BakeOptions::direct_override), with X the exit
// transfer above as the direct term: light leaving translucent surfaces (their subsurface exit,
// back-lit glow included) reaches every other surface; the bounce light arriving at a
// translucent vertex is returned locally with albedo R_total,c (clamped to 0.999), i.e. the
// indirect irradiance is assumed to vary little over the diffusion length (docs/SUBSURFACE.md).
// Refused (BakeError, one line): an adaptive or Haar bake, a textured scene, coefficients that
// prt::subsurface::validate refuses, a vertex_material index out of range, mm_per_unit < 0.
// References: Jensen et al. 2001; Jensen & Buhler 2002; Sloan, Kautz & Snyder 2002.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "bake/subsurface/dipole_gather.h"
#include "bake/transfer_baker.h"
#include "prt/subsurface/dipole.h"

namespace prt::bake {

struct SubsurfaceBakeOptions {
  std::vector<subsurface::DipoleCoefficients> materials;  // mm⁻¹
  // Per vertex: index into materials, −1 opaque. Empty: every vertex is material 0.
  std::vector<int32_t> vertex_material;
  double mm_per_unit = 0;  // 0: default_mm_per_unit(scene)
  SubsurfaceGatherOptions gather;
};

struct SubsurfaceBakeStatistics {
  double mm_per_unit = 0;
  double seconds_gather = 0;
  uint64_t translucent_vertices = 0;
  SubsurfaceGatherStats gather;
};

struct SubsurfaceBakeResult {
  BakeResult bake;
  SubsurfaceBakeStatistics subsurface;
};

// 100 mm over the scene's bounding-box diagonal (1 when the scene is a point).
double default_mm_per_unit(const scene::Scene& scene);

// Per-vertex areas (a third of each adjacent triangle's area).
std::vector<double> vertex_areas(const scene::Scene& scene);

// The scene an interreflected subsurface bake's inner bake (sampling and solve) sees: every
// translucent vertex's albedo replaced by its material's R_total per channel, clamped to 0.999
// (the solve's ρ < 1 rule: the vertex's own base colour is not used, so any is accepted); the
// other vertices as given (checked by the inner bake). The single bake and its shards
// (bake/subsurface/subsurface_part.h) both bake on it, so they accept the same scenes.
scene::Scene subsurface_solve_scene(const scene::Scene& scene, const SubsurfaceBakeOptions& ss);

// Throws the BakeError above when (scene, options, subsurface) cannot be baked.
void validate_subsurface(const scene::Scene& scene, const BakeOptions& options,
                         const SubsurfaceBakeOptions& subsurface);

SubsurfaceBakeResult bake_subsurface_transfer(const scene::Scene& scene, const BakeOptions& options,
                                              const SubsurfaceBakeOptions& subsurface,
                                              ProgressSink* progress = nullptr);

// The transfer bake a subsurface bake runs: what bake_transfer(scene, options) returns, by
// whatever means (bake_subsurface_transfer: bake_transfer; the farm merge,
// bake/subsurface/subsurface_part.h: merge_transfer_parts of the parts' rows).
using TransferBakeFunction =
    std::function<BakeResult(const scene::Scene& scene, const BakeOptions& options)>;

// bake_subsurface_transfer with the inner transfer bake given: the one code path of the single
// bake and the merge, so both write the same bytes.
SubsurfaceBakeResult bake_subsurface_transfer_with(const scene::Scene& scene,
                                                   const BakeOptions& options,
                                                   const SubsurfaceBakeOptions& subsurface,
                                                   const TransferBakeFunction& bake);

}  // namespace prt::bake
