// numerics/sampling.h — warping uniform numbers in [0, 1)² to directions, disc points and
// triangle points, with their densities, and the orthonormal frame that takes a local direction
// to the world.
//
// Frame: every direction is returned in a LOCAL frame with +z up (the surface normal, the axis of
// the hemisphere): z = cos θ. Take it to the world with build_orthonormal_basis(n, t, b) and
// l.x·t + l.y·b + l.z·n. Disc points are on the unit disc in the xy plane.
// Names are verb-first with a matching density (pbrt-v4's util/sampling.h: sample_X / X_pdf);
// densities are per unit solid angle (directions) or per unit area (points).
//   uniform sphere        z = 1 − 2u₀, φ = 2πu₁                        pdf 1/(4π)
//   uniform hemisphere    z = 1 − u₀,  φ = 2πu₁                        pdf 1/(2π)
//   cosine hemisphere     Malley's method: a concentric-disc point lifted to the hemisphere,
//                         z = √(1 − x² − y²)                            pdf cos θ/π
//   concentric disc       Shirley & Chiu's area-preserving square-to-disc map (low distortion:
//                         strata of the square stay compact on the disc) pdf 1/π
//   polar disc            r = √u₀, φ = 2πu₁                             pdf 1/π
//   uniform triangle      barycentrics (1 − √u₀, √u₀(1 − u₁), √u₀u₁)    pdf 1/area
// build_orthonormal_basis is Duff et al.'s branch-free construction (continuous except across
// n.z = 0): for unit n, (t, b, n) is right-handed orthonormal to rounding; no normalisation.
// All are templates on the scalar (float or double): the float versions are what the bakers run,
// operation for operation, so their results do not depend on this header being shared.
// References: [11] (Shirley & Chiu; Malley), [12] (Duff et al.) of docs/REFERENCES.md; M. Pharr,
// W. Jakob, G. Humphreys, Physically Based Rendering, 4th ed., §A.5.
#pragma once

#include <algorithm>
#include <cmath>

#include "numerics/constants.h"

namespace prt::numerics {

template <typename T>
struct Vec2 {
  T x, y;
};

template <typename T>
struct Vec3 {
  T x, y, z;
};

// Shirley–Chiu concentric map of [0, 1)² onto the unit disc (area preserving).
template <typename T>
Vec2<T> sample_uniform_disk_concentric(Vec2<T> u) {
  const T a = T(2) * u.x - T(1), b = T(2) * u.y - T(1);
  if (a == T(0) && b == T(0)) return {T(0), T(0)};
  constexpr T kQuarterPi = static_cast<T>(kPi) / T(4), kHalfPiT = static_cast<T>(kPi) / T(2);
  T r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = kQuarterPi * (b / a);
  } else {
    r = b;
    phi = kHalfPiT - kQuarterPi * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// Polar map of [0, 1)² onto the unit disc: r = √u₀, φ = 2πu₁ (area preserving, more distortion).
template <typename T>
Vec2<T> sample_uniform_disk_polar(Vec2<T> u) {
  const T r = std::sqrt(u.x), phi = static_cast<T>(kTwoPi) * u.y;
  return {r * std::cos(phi), r * std::sin(phi)};
}

// The density of both disc maps, per unit area.
template <typename T>
constexpr T uniform_disk_pdf() {
  return static_cast<T>(kInvPi);
}

// Cosine-weighted direction about +z (Malley's method on the concentric disc): z ≥ 0.
template <typename T>
Vec3<T> sample_cosine_hemisphere(Vec2<T> u) {
  const Vec2<T> d = sample_uniform_disk_concentric(u);
  const T z = std::sqrt(std::max(T(0), T(1) - d.x * d.x - d.y * d.y));
  return {d.x, d.y, z};
}

// The density of sample_cosine_hemisphere at a direction with cos θ = cos_theta: cos θ/π above
// the horizon, 0 at or below it.
template <typename T>
constexpr T cosine_hemisphere_pdf(T cos_theta) {
  return cos_theta > T(0) ? cos_theta / static_cast<T>(kPi) : T(0);
}

// Uniform direction on the upper hemisphere (about +z): z = 1 − u₀ ∈ (0, 1].
template <typename T>
Vec3<T> sample_uniform_hemisphere(Vec2<T> u) {
  const T z = T(1) - u.x;
  const T r = std::sqrt(std::max(T(0), T(1) - z * z));
  const T phi = static_cast<T>(kTwoPi) * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

template <typename T>
constexpr T uniform_hemisphere_pdf() {
  return static_cast<T>(kInvTwoPi);
}

// Uniform direction on the unit sphere: z = 1 − 2u₀ ∈ (−1, 1].
template <typename T>
Vec3<T> sample_uniform_sphere(Vec2<T> u) {
  const T z = T(1) - T(2) * u.x;
  const T r = std::sqrt(std::max(T(0), T(1) - z * z));
  const T phi = static_cast<T>(kTwoPi) * u.y;
  return {r * std::cos(phi), r * std::sin(phi), z};
}

template <typename T>
constexpr T uniform_sphere_pdf() {
  return static_cast<T>(kInvFourPi);
}

// Barycentric weights (b₀, b₁, b₂) of a point uniform on a triangle: p = b₀p₀ + b₁p₁ + b₂p₂,
// density 1/area. b₀ = 1 − √u₀, b₁ = √u₀(1 − u₁), b₂ = √u₀u₁.
template <typename T>
Vec3<T> sample_uniform_triangle(Vec2<T> u) {
  const T r = std::sqrt(u.x);
  return {T(1) - r, r * (T(1) - u.y), r * u.y};
}

template <typename T>
constexpr T uniform_triangle_pdf(T area) {
  return T(1) / area;
}

// Duff et al. 2017: t, b such that (t, b, n) is a right-handed orthonormal frame, for unit n.
template <typename T>
void build_orthonormal_basis(const Vec3<T>& n, Vec3<T>* t, Vec3<T>* b) {
  const T sign = std::copysign(T(1), n.z);
  const T a = T(-1) / (sign + n.z);
  const T c = n.x * n.y * a;
  *t = {T(1) + sign * n.x * n.x * a, sign * c, -sign * n.x};
  *b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace prt::numerics
