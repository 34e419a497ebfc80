// prt/src/emitters/glossy_emitter_radiance.cpp — see prt/emitters/glossy_emitter_radiance.h.
#include "prt/emitters/glossy_emitter_radiance.h"

#include <cmath>
#include <string>

namespace prt {
namespace {

bool finite_non_negative(float x) {
  return std::isfinite(x) && x >= 0.f;
}

Status check_colors(const GlossyEmitterRadiance& data, const std::vector<float>& colors_rgb) {
  if (colors_rgb.size() != 3 * data.emitter_count())
    return Status::Error("glossy emitters: " + std::to_string(colors_rgb.size()) +
                         " colour values for " + std::to_string(data.emitter_count()) +
                         " emitters");
  for (float c : colors_rgb)
    if (!finite_non_negative(c))
      return Status::Error("glossy emitters: colour " + std::to_string(c) +
                           " is negative, NaN or infinite");
  return Status::Ok();
}

}  // namespace

Status validate_glossy_emitter_radiance(const GlossyEmitterRadiance& data) {
  if (data.order < 1 || data.order > uint32_t(kMaxBrdfProjectionOrder))
    return Status::Error("glossy emitters: order " + std::to_string(data.order) + " outside 1.." +
                         std::to_string(kMaxBrdfProjectionOrder));
  if (data.emitters.empty()) return Status::Error("glossy emitters: no emitters");
  const std::size_t expected =
      std::size_t(data.vertex_count) * data.emitter_count() * 3 * data.coefficient_count();
  if (data.coefficients.size() != expected)
    return Status::Error("glossy emitters: " + std::to_string(data.coefficients.size()) +
                         " coefficients, the counts need " + std::to_string(expected));
  for (float x : data.coefficients)
    if (!std::isfinite(x)) return Status::Error("glossy emitters: a coefficient is not finite");
  if (data.emitter_of_vertex.size() != data.vertex_count)
    return Status::Error("glossy emitters: " + std::to_string(data.emitter_of_vertex.size()) +
                         " emitter indices for " + std::to_string(data.vertex_count) + " vertices");
  for (uint32_t e : data.emitter_of_vertex)
    if (e != kNotAnEmitter && e >= data.emitter_count())
      return Status::Error("glossy emitters: emitter index " + std::to_string(e) + " of " +
                           std::to_string(data.emitter_count()));
  return Status::Ok();
}

Status combine_glossy_emitters(const GlossyEmitterRadiance& data,
                               const std::vector<float>& colors_rgb, std::size_t v, float* out) {
  if (Status s = check_colors(data, colors_rgb); !s.ok()) return s;
  if (v >= data.vertex_count)
    return Status::Error("glossy emitters: vertex " + std::to_string(v) + " out of range");
  const std::size_t K = data.coefficient_count(), E = data.emitter_count();
  const float* g = &data.coefficients[v * E * 3 * K];
  for (int c = 0; c < 3; ++c)
    for (std::size_t i = 0; i < K; ++i) {
      double sum = 0;
      for (std::size_t e = 0; e < E; ++e)
        sum += double(colors_rgb[3 * e + c]) * double(g[(e * 3 + c) * K + i]);
      out[c * K + i] = static_cast<float>(sum);
    }
  return Status::Ok();
}

Status glossy_vertex_frame(const GlossyTransferData& d, std::size_t v, double rows[9]) {
  using brdf::Vec3;
  if (v >= d.vertex_count || d.normals.size() < 3 * (v + 1) || d.tangents.size() < 4 * (v + 1))
    return Status::Error("glossy emitters: vertex " + std::to_string(v) + " has no frame");
  Vec3 n{d.normals[3 * v], d.normals[3 * v + 1], d.normals[3 * v + 2]};
  Vec3 t{d.tangents[4 * v], d.tangents[4 * v + 1], d.tangents[4 * v + 2]};
  const double w = d.tangents[4 * v + 3] < 0.f ? -1.0 : 1.0;
  n = normalize(n);
  t = t - dot(t, n) * n;
  const bool degenerate = !(length(n) > 0.5) || !(length(t) > 1e-3);
  if (degenerate)
    return Status::Error("glossy emitters: vertex " + std::to_string(v) +
                         " has a degenerate or non-finite normal/tangent frame");
  t = normalize(t);
  const Vec3 b = w * Vec3{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
  const double r[9] = {t.x, t.y, t.z, b.x, b.y, b.z, n.x, n.y, n.z};
  for (int k = 0; k < 9; ++k) rows[k] = r[k];
  return Status::Ok();
}

Status shade_glossy_emitters(const GlossyEmitterRadiance& data,
                             const std::vector<float>& colors_rgb,
                             const GlossyTransferData& geometry,
                             const std::vector<BrdfProjection>& projections, const double eye[3],
                             std::size_t first, std::size_t count, float* out_rgb) {
  if (Status s = check_colors(data, colors_rgb); !s.ok()) return s;
  if (eye == nullptr || (count > 0 && out_rgb == nullptr))
    return Status::Error("glossy emitters: null pointer");
  if (geometry.vertex_count != data.vertex_count || first + count > data.vertex_count ||
      first + count < first)
    return Status::Error("glossy emitters: vertex range or count does not match the geometry");
  if (geometry.positions.size() != 3 * geometry.vertex_count ||
      geometry.material_of_vertex.size() != geometry.vertex_count)
    return Status::Error("glossy emitters: geometry arrays do not match its vertex count");
  const std::size_t K = data.coefficient_count();
  for (const BrdfProjection& p : projections)
    if (std::size_t(p.order()) * p.order() != K)
      return Status::Error("glossy emitters: a BRDF projection of order " +
                           std::to_string(p.order()) + " for radiance of order " +
                           std::to_string(data.order));
  std::vector<float> incident(3 * K);
  std::vector<double> b(3 * K);
  for (std::size_t v = first; v < first + count; ++v) {
    const uint32_t material = geometry.material_of_vertex[v];
    if (material >= projections.size())
      return Status::Error("glossy emitters: vertex " + std::to_string(v) +
                           " has no BRDF projection");
    double f[9];
    if (Status s = glossy_vertex_frame(geometry, v, f); !s.ok()) return s;
    const double d[3] = {eye[0] - geometry.positions[3 * v], eye[1] - geometry.positions[3 * v + 1],
                         eye[2] - geometry.positions[3 * v + 2]};
    const brdf::Vec3 wo{f[0] * d[0] + f[1] * d[1] + f[2] * d[2],
                        f[3] * d[0] + f[4] * d[1] + f[5] * d[2],
                        f[6] * d[0] + f[7] * d[1] + f[8] * d[2]};
    if (!(wo.z > 0.0) || !std::isfinite(wo.x) || !std::isfinite(wo.y)) continue;
    projections[material].evaluate(wo, b.data());
    if (Status s = combine_glossy_emitters(data, colors_rgb, v, incident.data()); !s.ok()) return s;
    float* out = out_rgb + 3 * (v - first);
    const uint32_t own =
        v < data.emitter_of_vertex.size() ? data.emitter_of_vertex[v] : kNotAnEmitter;
    for (int c = 0; c < 3; ++c) {
      double sum = own < data.emitter_count() ? double(colors_rgb[3 * own + c]) : 0.0;
      for (std::size_t i = 0; i < K; ++i) sum += b[c * K + i] * double(incident[c * K + i]);
      out[c] = static_cast<float>(double(out[c]) + sum);
    }
  }
  return Status::Ok();
}

}  // namespace prt
