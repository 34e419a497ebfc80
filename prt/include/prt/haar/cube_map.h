// prt/haar/cube_map.h — the cube-map domain of all-frequency (Haar-wavelet) relighting.
//
// Ng, Ramamoorthi & Hanrahan, "All-Frequency Shadows Using Non-linear Wavelet Lighting
// Approximation", SIGGRAPH 2003, represent lighting and transfer on the six faces of a cube
// map, N×N texels per face, and project both onto a 2D Haar basis per face.
//
// Conventions (the same as sh::EnvLayout::Faces in sh/env_map.h, so the two agree):
//   * Scene frame: glTF's, right-handed, +Y up. Directions are unit vectors.
//   * Faces in the order +X, −X, +Y, −Y, +Z, −Z (face index 0..5), each N×N, row-major,
//     row 0 at the top. Face-local coordinates a (right) and b (down) lie in [−1, 1]; the
//     texel (col, row) has centre a = 2(col+½)/N − 1, b = 2(row+½)/N − 1, and the face point
//     (a, b) looks along
//       +X: (1, −b, a)   −X: (−1, −b, −a)   +Y: (a, 1, −b)
//       −Y: (a, −1, b)   +Z: (−a, −b, 1)    −Z: (a, −b, −1)       (then normalised).
//   * Texel t = face·N² + row·N + col; CubeMap::rgb[3t + c] holds radiance (scene units,
//     W·sr⁻¹·m⁻² or whatever the source map holds), channel c ∈ {R, G, B}.
//   * Solid angles are exact (the texel-corner formula): the region [a0,a1]×[b0,b1] of a face
//     at unit distance subtends F(a1,b1) − F(a0,b1) − F(a1,b0) + F(a0,b0) with
//     F(a, b) = atan2(a·b, √(a² + b² + 1)). Every face has the same table; Σ = 4π.
// Compiles as C++17.
// References: [4] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/core/status.h"

namespace prt {

namespace sh {
struct EnvMap;  // sh/env_map.h
}

// Face indices in storage order.
enum class CubeFace : int { PosX = 0, NegX = 1, PosY = 2, NegY = 3, PosZ = 4, NegZ = 5 };
inline constexpr int kCubeFaceCount = 6;
inline constexpr int kMinCubeSize = 8;
inline constexpr int kMaxCubeSize = 128;

// A cube map of RGB radiance, N×N per face (N a power of two in [kMinCubeSize, kMaxCubeSize]).
struct CubeMap {
  int size = 0;            // N
  std::vector<float> rgb;  // 6·N·N·3: faces in the order above, row-major per face, RGB
  int64_t texel_count() const { return int64_t{kCubeFaceCount} * size * size; }
};

// True when size is a power of two in [kMinCubeSize, kMaxCubeSize].
bool is_valid_cube_size(int size) noexcept;

// A black cube map of the given size (size is not validated).
CubeMap make_black_cube_map(int size);

// The unit direction of face point (a, b), a and b in [−1, 1] (any real values are accepted;
// the result is the normalised face-plane point).
void cube_face_point_direction(int face, double a, double b, double dir[3]) noexcept;

// The unit direction through the centre of texel (col, row) of `face` on an N×N face.
void cube_texel_direction(int size, int face, int col, int row, double dir[3]) noexcept;

// The face and face-local (a, b) ∈ [−1, 1]² a direction hits; false for a zero or non-finite
// direction. Ties between axes go to x, then y, then z (a direction on a cube edge or corner
// belongs to exactly one face).
bool direction_to_cube_face_point(const double dir[3], int* face, double* a, double* b) noexcept;

// The texel containing a direction (face, col, row); false for a zero or non-finite direction.
bool direction_to_cube_texel(int size, const double dir[3], int* face, int* col, int* row) noexcept;

// Exact solid angle (sr) of texel (col, row) of any face of an N×N cube map.
double cube_texel_solid_angle(int size, int col, int row) noexcept;

// Exact solid angle of the face rectangle [a0, a1]×[b0, b1] (a0 ≤ a1, b0 ≤ b1, in [−1, 1]).
double cube_face_rect_solid_angle(double a0, double a1, double b0, double b1) noexcept;

// The N² exact texel solid angles of one face, row-major (identical for all six faces).
std::vector<double> cube_face_solid_angles(int size);

// Σ L·dω per channel of a cube map (power; double accumulation, exact texel solid angles).
void cube_map_power(const CubeMap& cube, double power[3]);

// What resample_to_cube skipped and what it preserved.
struct CubeResampleStats {
  int64_t skipped_texels = 0;          // source texels with a NaN, ±Inf or negative channel
  int64_t subsamples_per_texel = 0;    // S² (S×S stratified pattern)
  double source_power[3] = {0, 0, 0};  // Σ L·Ω over the used source texels (double)
  double cube_power[3] = {0, 0, 0};    // Σ L·ω over the cube texels (from the float result)
};

// Resamples an environment map (any sh::EnvLayout) to an N×N cube map with exact area
// weighting, so the total power Σ L·dω is preserved to float precision at any resolution.
//
// Method (a splat, not a gather): every source texel s with exact solid angle Ω_s (from
// sh::texel_solid_angle) is split into a fixed S×S stratified pattern of sub-texels — the
// texels of the same layout at S× the resolution, whose directions and exact solid angles
// come from sh::texel_direction / sh::texel_solid_angle. Sub-texel i carries the power
// L_s · Ω_s · ω_i / Σ_j ω_j into the cube texel containing its direction; each cube texel's
// accumulated power (double) is divided by its exact solid angle. Because the weights of each
// source texel sum to exactly Ω_s, Σ_cube L·ω = Σ_source L·Ω up to rounding, whatever S, N and
// the source resolution. S = max(2, min(⌈8·√(Ω_max/ω̄)⌉, ⌊√(2²⁴/(w·h))⌋)),
// Ω_max the largest source texel, ω̄ = 4π/(6N²): about 8 sub-samples across a cube texel when
// upsampling (so no cube texel is left empty), S = 2 for fine sources, and never more than
// 2²⁴ sub-samples in all. Local accuracy is that of an 8×8-per-texel point splat (a cube
// texel's value is off by up to ~1/8 per axis of its area where a source edge crosses it);
// the total power is exact.
// Source texels outside the layout's domain (solid angle 0, e.g. the angular probe's
// corners) carry no power. Texels with any NaN, ±Inf or negative channel are skipped (their
// power is dropped) and counted in stats->skipped_texels.
// Errors: invalid size, empty or inconsistent map (rgb.size() ≠ 3·w·h).
Result<CubeMap> resample_to_cube(const sh::EnvMap& env, int size,
                                 CubeResampleStats* stats = nullptr);

}  // namespace prt
