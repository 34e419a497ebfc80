// prt/brdf/vec3.h — the small vector and colour types of the BRDF library.
//
// Directions are unit vectors in the BRDF's LOCAL shading frame: +z is the surface normal n,
// +x the tangent t, +y the bitangent b = n × t (right-handed). Both ωi (towards the light) and
// ωo (towards the viewer) point AWAY from the surface. Everything is double precision.
// Compiles as C++17.
#pragma once

#include <cmath>

namespace prt::brdf {

struct Vec3 {
  double x = 0.0, y = 0.0, z = 0.0;
};

inline Vec3 operator+(const Vec3& a, const Vec3& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
inline Vec3 operator-(const Vec3& a, const Vec3& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
inline Vec3 operator*(double s, const Vec3& a) {
  return {s * a.x, s * a.y, s * a.z};
}
inline double dot(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline double length(const Vec3& a) {
  return std::sqrt(dot(a, a));
}
// a / |a|; the zero vector stays zero.
inline Vec3 normalize(const Vec3& a) {
  const double l = length(a);
  return l > 0.0 ? (1.0 / l) * a : Vec3{};
}
// Mirror of w about the unit vector h: 2(w·h)h − w.
inline Vec3 reflect(const Vec3& w, const Vec3& h) {
  return 2.0 * dot(w, h) * h - w;
}
// Unit vector from spherical angles in the local frame (θ from +z, φ from +x towards +y).
inline Vec3 spherical_direction(double cos_theta, double phi) {
  const double s = std::sqrt(std::fmax(0.0, 1.0 - cos_theta * cos_theta));
  return {s * std::cos(phi), s * std::sin(phi), cos_theta};
}

// Linear RGB; a BRDF value in 1/sr, a reflectance or an albedo (dimensionless).
struct Rgb {
  double r = 0.0, g = 0.0, b = 0.0;
};

inline Rgb operator+(const Rgb& a, const Rgb& c) {
  return {a.r + c.r, a.g + c.g, a.b + c.b};
}
inline Rgb operator*(double s, const Rgb& a) {
  return {s * a.r, s * a.g, s * a.b};
}
inline Rgb grey(double v) {
  return {v, v, v};
}
// The unweighted channel mean, used only to split samples between lobes.
inline double channel_mean(const Rgb& c) {
  return (c.r + c.g + c.b) / 3.0;
}

}  // namespace prt::brdf
