// prt/brdf/merl.h — measured isotropic BRDFs in the MERL binary format [40].
//
// File layout (little-endian): three int32 dimensions, which must be 90, 90, 180 (θ_h, θ_d,
// φ_d), then 3 × 90 × 90 × 180 float64 values, all red, then all green, then all blue; within
// a channel the index is (i_θh · 90 + i_θd) · 180 + i_φd. Stored values are multiplied by the
// channel scales 1/1500, 1.15/1500, 1.66/1500 to give f in 1/sr. Negative stored values (the
// database marks unmeasured cells with them) evaluate as 0.
// Half/difference angles (Rusinkiewicz [41]): h = normalize(ωi + ωo) with polar angle θ_h and
// azimuth φ_h; the difference vector is ωi rotated by −φ_h about the normal, then by −θ_h about
// the bitangent; θ_d and φ_d are its polar angle and azimuth. Lookup is nearest-cell (no
// interpolation): i_θh = floor(√(θ_h/(π/2)) · 90) — the non-linear mapping concentrates cells
// near the specular peak; i_θd = floor(θ_d/(π/2) · 90); i_φd = floor(φ_d'/π · 180) where
// φ_d' = φ_d + π when φ_d < 0 (reciprocity makes f π-periodic in φ_d); each clamped to its
// range. Frame and conventions: prt/brdf/brdf.h (the tabulated BRDF is isotropic, so the
// tangent's direction does not matter).
// Sampling is cosine-weighted over the upper hemisphere (pdf = cos θi / π): it importance-
// samples the cosine only, not the measured lobe, so glossy materials converge slowly.
// Reciprocal by construction of the lookup. Compiles as C++17.
// References: [40], [41] of docs/REFERENCES.md.
#pragma once

#include <string>
#include <vector>

#include "prt/brdf/brdf.h"
#include "prt/core/status.h"

namespace prt::brdf {

constexpr int kMerlThetaH = 90;
constexpr int kMerlThetaD = 90;
constexpr int kMerlPhiD = 180;
constexpr double kMerlScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

class MerlBrdf final : public Brdf {
 public:
  // Reads a MERL binary file. Errors name the file and the problem: missing, wrong dimensions,
  // truncated table, trailing bytes, non-finite values.
  static Result<MerlBrdf> read(const std::string& path);

  Rgb eval(const Vec3& wi, const Vec3& wo) const override;
  BrdfSample sample(const Vec3& wo, double u1, double u2) const override;
  double pdf(const Vec3& wo, const Vec3& wi) const override;
  bool reciprocal() const override { return true; }

 private:
  explicit MerlBrdf(std::vector<double> table) : table_(std::move(table)) {}
  std::vector<double> table_;  // 3 channels, already scaled to 1/sr, negatives set to 0
};

// Half/difference angles of (ωi, ωo) as described above: θ_h, θ_d in [0, π], φ_d in (−π, π].
struct HalfDiffAngles {
  double theta_h = 0, theta_d = 0, phi_d = 0;
};
HalfDiffAngles half_diff_angles(const Vec3& wi, const Vec3& wo);

}  // namespace prt::brdf
