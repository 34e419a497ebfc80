// prt/glossy/brdf_projection.h — the BRDF side of glossy PRT: the vector b(ωo) that turns
// transferred incident radiance into exit radiance (prt/glossy/transfer.h),
//     b_c,i(ωo) = ∫ y_i(ωi) f_c(ωi, ωo) cos⁺θi dωi,   i < n², c = R, G, B,
// so that L_o,c(ωo) = Σ_i b_c,i(ωo) L'_c,i for incident radiance L' of order n (exact when L' is
// band-limited to order n). Sloan, Kautz & Snyder 2002 [2]; Kautz, Sloan & Snyder 2002 [55] of
// docs/REFERENCES.md.
//
// Conventions: the local shading frame of prt/brdf/brdf.h (+z normal, +x tangent, +y
// bitangent), ωo unit and pointing away from the surface; SH basis of sh/basis.h (real,
// orthonormal, no Condon–Shortley phase, k = l(l+1)+m) evaluated in that local frame. Outputs are
// channel-major: out[c·n² + i]. Every BRDF is one-sided: for cos θo ≤ 0 (and for a non-finite or
// zero ωo) b = 0 exactly.
//
// Three ways to get b (docs/GLOSSY.md, "Runtime and relight", derives and measures them):
// - project_brdf_slice(): the REFERENCE, direct quadrature for one ωo, in double: Gauss–Legendre
//   panels in cos θi and in φi, both graded towards the mirror direction R = (−ωo.x, −ωo.y,
//   ωo.z) so glossy lobes are resolved, and with cos θi = 0 a panel edge (the horizon kink is
//   integrated exactly). Slow (about a million BRDF evaluations at the default resolution).
// - BrdfProjectionMethod::kZonal, for ISOTROPIC materials: the diffuse part ρ_d/π is exact
//   (b_l0 = ρ_d/π · z_l of the clamped cosine about the normal, sh/zonal.h); the rest of the
//   BRDF, f_s = f − ρ_d/π, is replaced for each ωo by its least-squares ZONAL approximation about
//   R: the function ωi ↦ f_s(ωi, ωo) cos⁺θi averaged over rotations about R, with zonal
//   coefficients g_l(cos θo) (they depend on the elevation of ωo only, the material being
//   isotropic), tabulated at `zonal_table` values of cos θo and interpolated linearly; then
//   b = rotate_zonal(g, R) + the diffuse part. Exact for a lobe that is symmetric about R (a
//   Phong lobe far from the horizon); the error is the part of the lobe that is not: the
//   horizon clipping cos⁺θi and the elongation of half-vector lobes at grazing views.
// - BrdfProjectionMethod::kIsotropicTable, for ISOTROPIC materials (analytic or MERL), without
//   approximation in the lobe's shape: f(Rz ωi, Rz ωo) = f(ωi, ωo) for every rotation Rz about the
//   normal, so b(θo, φo) is b(θo, 0) rotated about +z by φo. The full n² vectors b(θo, 0) are
//   tabulated by project_brdf_slice() at `table_size` elevations uniform in θo ∈ [0, π/2],
//   interpolated linearly in θo and rotated by φo (per band, the pairs (m, −m) mix by cos mφo,
//   sin mφo). Its only errors are the table's interpolation and quadrature (Kautz, Sloan &
//   Snyder 2002 [55] reduce isotropic BRDFs to the elevation of ωo the same way).
//   In both tables the node at the horizon (cos θo = 0) holds the limit of b as the view
//   approaches the horizon (extrapolated linearly from the two nearest nodes), not b there.
// - BrdfProjectionMethod::kMatrix, for any material (anisotropic and measured ones): the
//   n² × m² matrix B_c,ij = 2 ∫_{H+} b_c,i(ωo) y_j(ωo) dωo over j with l_j + m_j even, so that
//   b_c,i(ωo) ≈ Σ_j B_c,ij y_j(ωo) with view-side order m. The factor 2 and the parity are the
//   EVEN extension of b across the horizon (b(x, y, −z) = b(x, y, z)), which is continuous, so
//   its projection converges faster than that of b cut to zero below the horizon. The inner
//   integral is a fixed product rule (Gauss–Legendre in cos θi × uniform φi), the outer one
//   Gauss–Legendre in cos θo × uniform φo (sizes in BrdfProjectionOptions).
// kAuto picks kZonal for Lambert (exact there), kIsotropicTable for the other isotropic materials
// (Blinn-Phong, isotropic Ward and microfacet, MERL) and kMatrix for anisotropic ones. kZonal is
// kept for what it costs (n values per channel per table entry): docs/GLOSSY.md measures its
// error, 0 at normal incidence and tens of percent of |b| for half-vector lobes at 40°.
// Nothing here throws and nothing starts threads; a built BrdfProjection is immutable and may be
// shared between threads. Compiles as C++17.
#pragma once

#include <memory>
#include <vector>

#include "prt/brdf/brdf.h"
#include "prt/brdf/material.h"
#include "prt/core/status.h"

namespace prt {

// Largest SH order (lighting side and view side) the projections accept.
inline constexpr int kMaxBrdfProjectionOrder = 32;

// Resolution of project_brdf_slice(): Gauss–Legendre nodes per panel (panels in cos θi and in φi
// are graded towards the mirror direction, see above). Its error falls quickly with `nodes`.
struct SliceQuadrature {
  int nodes_per_panel = 12;
};

// The reference b(ωo) for order n: 3·n² doubles into out (channel-major). Errors: order outside
// [1, kMaxBrdfProjectionOrder], null out, nodes_per_panel outside [2, 64].
Status project_brdf_slice(const brdf::Brdf& brdf, int order, const brdf::Vec3& wo,
                          const SliceQuadrature& quadrature, double* out);

enum class BrdfProjectionMethod { kAuto, kZonal, kIsotropicTable, kMatrix };

struct BrdfProjectionOptions {
  BrdfProjectionMethod method = BrdfProjectionMethod::kAuto;
  int view_order = 0;     // kMatrix: m; 0 → order + 6 (docs/GLOSSY.md measures the choice)
  int zonal_table = 128;  // kZonal: values of cos θo in the table, uniform in [0, 1]
  int table_size = 91;    // kIsotropicTable: elevations θo, uniform in [0, π/2] (1° apart)
  int table_nodes = 8;    // kIsotropicTable: project_brdf_slice's nodes per panel
  int inner_theta = 64;   // kMatrix: Gauss–Legendre nodes in cos θi ∈ [0, 1] (8 panels)
  int inner_phi = 128;    // kMatrix: uniform nodes in φi
  int outer_theta = 0;    // kMatrix: Gauss–Legendre nodes in cos θo; 0 → 2·m + 8
  int outer_phi = 0;      // kMatrix: uniform nodes in φo; 0 → 4·m + 8
};

class BrdfProjection {
 public:
  BrdfProjection();  // b = 0 at order 1
  BrdfProjection(BrdfProjection&&) noexcept;
  BrdfProjection& operator=(BrdfProjection&&) noexcept;
  BrdfProjection(const BrdfProjection&);
  BrdfProjection& operator=(const BrdfProjection&);
  ~BrdfProjection();

  // Builds the projection of `material` at lighting order `order`. Errors: make_brdf()'s, an
  // order or view order outside [1, kMaxBrdfProjectionOrder], quadrature sizes out of range
  // (zonal_table and table_size 2..65536, table_nodes 2..64, inner sizes 8..4096, outer sizes 0
  // or 4..4096), kZonal or kIsotropicTable asked for an anisotropic material, kZonal for MERL.
  static Result<BrdfProjection> create(const brdf::Material& material, int order,
                                       const BrdfProjectionOptions& options = {});
  // The same for a BRDF object; kZonal then needs the diffuse reflectance ρ_d that f contains as
  // an additive Lambert term (grey(0) for none); kZonal and kIsotropicTable trust the caller
  // that f is isotropic; kAuto means kMatrix.
  static Result<BrdfProjection> create(std::shared_ptr<const brdf::Brdf> brdf, int order,
                                       const brdf::Rgb& lambert_part,
                                       const BrdfProjectionOptions& options);

  int order() const;
  int view_order() const;               // kMatrix's m; 0 otherwise
  BrdfProjectionMethod method() const;  // never kAuto

  // b(ωo) at unit local ωo: 3·order² values (channel-major) into out. ωo with z ≤ 0, not finite
  // or of zero length gives zeros. ωo is normalised first.
  void evaluate(const brdf::Vec3& wo, double* out) const;
  // Float version for the shading kernel. `scratch` holds at least scratch_floats() floats.
  void evaluate(const float wo[3], float* out, float* scratch) const;
  // The same for channel 0 only (order² values), the same bits as evaluate()'s channel 0.
  void evaluate_channel0(const float wo[3], float* out, float* scratch) const;
  // b for `count` views at once: wo holds 3 floats per view (as evaluate()'s), out receives
  // channels·order² floats per view (channels 1: evaluate_channel0()'s values; otherwise 3:
  // evaluate()'s). kIsotropicTable takes θo from a polynomial arccosine (Abramowitz & Stegun
  // [116] of docs/REFERENCES.md) instead of acosf and fuses the lerp with the rotation, so its
  // values may differ from evaluate()'s in the last bits (docs/GLOSSY_CPCA.md; the tests bound
  // the difference); the other methods give evaluate()'s bits. `scratch` as evaluate()'s.
  void evaluate_many(const float* wo, std::size_t count, float* out, float* scratch,
                     int channels) const;
  // True when the float evaluate() gives three bitwise equal channels for every ωo (a grey
  // material: its float tables repeat one channel); evaluate() then computes channel 0 and
  // copies it, and a caller may keep channel 0 alone.
  bool grey() const;
  std::size_t scratch_floats() const;

  struct Impl;

 private:
  // create() with `orthotropic`: f is unchanged when ωi and ωo are both reflected by y → −y or
  // x → −x (the analytic models), which lets kMatrix evaluate a quarter of the views.
  static Result<BrdfProjection> create_impl(std::shared_ptr<const brdf::Brdf> brdf, int order,
                                            const brdf::Rgb& lambert_part,
                                            const BrdfProjectionOptions& options, bool orthotropic);
  std::unique_ptr<Impl> impl_;
};

}  // namespace prt
