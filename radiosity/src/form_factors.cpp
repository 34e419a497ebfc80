#include "radiosity/form_factors.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "form_factor_rows.h"
#include "large_buffer.h"
#include "numerics/constants.h"
#include "numerics/hash.h"
#include "numerics/low_discrepancy.h"
#include "radiosity/hemicube.h"
#include "random.h"

namespace prt::radiosity {
namespace {

// The part of `polygon` on the side n·(y − x) ≥ 0 (Sutherland–Hodgman against one plane).
std::vector<glm::dvec3> clip_to_front(const glm::dvec3& x, const glm::dvec3& n,
                                      const std::vector<glm::dvec3>& polygon) {
  std::vector<glm::dvec3> out;
  const std::size_t m = polygon.size();
  for (std::size_t k = 0; k < m; ++k) {
    const glm::dvec3& a = polygon[k];
    const glm::dvec3& b = polygon[(k + 1) % m];
    const double ha = glm::dot(n, a - x), hb = glm::dot(n, b - x);
    if (ha >= 0.0) out.push_back(a);
    if ((ha >= 0.0) != (hb >= 0.0)) out.push_back(a + (b - a) * (ha / (ha - hb)));
  }
  return out;
}

glm::dvec3 newell_normal(const std::vector<glm::dvec3>& polygon) {
  glm::dvec3 n(0.0);
  for (std::size_t k = 0; k < polygon.size(); ++k)
    n += glm::cross(polygon[k], polygon[(k + 1) % polygon.size()]);
  const double length = glm::length(n);
  return length > 0.0 ? n / length : n;
}

}  // namespace

std::vector<glm::dvec3> detail::quadrature_points(const Patch& p, int count) {
  if (count == 1) return {p.centroid};
  const auto mix = [&](double a, double b, double c) {
    return p.corners[0] * a + p.corners[1] * b + p.corners[2] * c;
  };
  return {mix(4.0 / 6, 1.0 / 6, 1.0 / 6), mix(1.0 / 6, 4.0 / 6, 1.0 / 6),
          mix(1.0 / 6, 1.0 / 6, 4.0 / 6)};
}

detail::AnalyticSender::AnalyticSender(const std::vector<Patch>& patches,
                                       const scene::RayCaster& caster, uint32_t i, int points)
    : patches_(patches),
      caster_(caster),
      i_(i),
      points_(points),
      xs_(quadrature_points(patches[i], points)) {
  for (const glm::dvec3& x : xs_)
    origins_.push_back(caster.surface_origin(i, glm::vec3(x), glm::vec3(patches[i].normal)));
}

float detail::AnalyticSender::entry(uint32_t j) {
  const Patch& s = patches_[i_];
  const Patch& r = patches_[j];
  if (j == i_ || r.area <= 0.0) return 0.f;
  polygon_.assign(r.corners.begin(), r.corners.end());
  std::vector<glm::dvec3> ys;
  double sum = 0.0;
  for (int k = 0; k < points_; ++k) {
    // One-sided receivers: x must lie in front of patch j.
    if (glm::dot(r.normal, xs_[k] - r.centroid) <= 0.0) continue;
    const double f = point_polygon_form_factor(xs_[k], s.normal, polygon_);
    if (f <= 0.0) continue;
    if (ys.empty()) ys = quadrature_points(r, points_);
    const glm::vec3 target = caster_.surface_origin(j, glm::vec3(ys[k]), glm::vec3(r.normal));
    const glm::vec3 d = target - origins_[k];
    const float length = glm::length(d);
    if (!(length > 0.f) || !caster_.occluded(origins_[k], d / length, 0.f, length)) sum += f;
  }
  return static_cast<float>(sum / points_);
}

// Sampled visibility can let overlapping polygons (an occluder and the wall behind it) both
// count in full; a row may then sum above 1. It is scaled back to 1 so that no patch sends more
// power than it has.
void detail::normalise_row(float* row, std::size_t n) {
  double sum = 0.0;
  for (std::size_t j = 0; j < n; ++j) sum += row[j];
  if (sum > 1.0)
    for (std::size_t j = 0; j < n; ++j) row[j] = static_cast<float>(row[j] / sum);
}

namespace {

// The k-th 4-D sample of row i: a point on the sender and a cosine-distributed direction.
class RowSamples {
 public:
  RowSamples(const Patch& s, uint32_t i, const FormFactorOptions& options)
      : s_(s),
        random_(options.seed, i),
        sobol_seed_(numerics::hash_seed(options.seed, i)),
        independent_(options.sampling == RaySampling::Independent) {}

  void next(uint32_t k, glm::dvec3* p, glm::dvec3* d) {
    if (independent_) {
      *p = random_.point_on(s_);
      *d = random_.cosine_direction(s_.normal);
      return;
    }
    // Owen-scrambled Sobol' dimensions 0-3 of the row's sequence (numerics/low_discrepancy.h).
    // Dimensions 0 and 1 (the (0, m, 2)-net) go to the direction, which decides the hit more
    // than the point on a small patch does.
    double u[4];
    for (int dim = 0; dim < 4; ++dim) u[dim] = numerics::sobol_owen_double(k, dim, sobol_seed_);
    *d = detail::cosine_direction(s_.normal, u[0], u[1]);
    *p = detail::point_on(s_, u[2], u[3]);
  }

 private:
  const Patch& s_;
  detail::PatchRandom random_;
  uint64_t sobol_seed_;
  bool independent_;
};

// Row i by rays into `row` (n floats, zero on entry). Only the hit patches are written: the
// hits are collected, sorted and counted, so a row costs O(rays log rays), not O(n).
void ray_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
             const FormFactorOptions& options, float* row) {
  const Patch& s = patches[i];
  if (s.area <= 0.0) return;
  RowSamples samples(s, i, options);
  const int rays = detail::rays_of(s, options);
  std::vector<uint32_t> hits;
  hits.reserve(static_cast<std::size_t>(rays));
  const float inf = std::numeric_limits<float>::infinity();
  // Rays go to Embree as streams of 64 (rtcIntersect1M; ~25% more rays per CPU-second than
  // single rays on this access pattern, the same hits: docs/BENCHMARKS.md).
  constexpr int kStream = 64;
  std::array<glm::vec3, kStream> origins, directions;
  std::array<scene::RayCaster::Hit, kStream> found;
  for (int k0 = 0; k0 < rays; k0 += kStream) {
    const int count = std::min(kStream, rays - k0);
    for (int k = 0; k < count; ++k) {
      glm::dvec3 p, d;
      samples.next(static_cast<uint32_t>(k0 + k), &p, &d);
      origins[k] = caster.surface_origin(i, glm::vec3(p), glm::vec3(s.normal));
      directions[k] = glm::vec3(d);
    }
    caster.intersect_stream(origins.data(), directions.data(), count, inf, false, found.data());
    for (int k = 0; k < count; ++k)
      if (found[k].hit && found[k].front_face && found[k].triangle != i)
        hits.push_back(found[k].triangle);
  }
  std::sort(hits.begin(), hits.end());
  for (std::size_t a = 0; a < hits.size();) {
    std::size_t b = a;
    while (b < hits.size() && hits[b] == hits[a]) ++b;
    row[hits[a]] = static_cast<float>(double(b - a) / rays);
    a = b;
  }
}

// Row e of an emitter by reciprocity: F_ej = A_j · F_je / A_e with F_je the analytic entry of
// sender j (its quadrature points, one visibility ray each), then scaled to sum to at most 1.
void reciprocal_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t e,
                    int points, float* row) {
  const Patch& emitter = patches[e];
  if (emitter.area <= 0.0) return;
  for (uint32_t j = 0; j < patches.size(); ++j) {
    const Patch& r = patches[j];
    if (j == e || r.area <= 0.0) continue;
    // Receiver j sees nothing of e unless some of j lies in front of e (and e in front of j).
    bool facing = false;
    for (const glm::dvec3& c : r.corners)
      facing |= glm::dot(emitter.normal, c - emitter.centroid) > 0.0;
    if (!facing) continue;
    detail::AnalyticSender sender(patches, caster, j, points);
    row[j] = static_cast<float>(r.area * double(sender.entry(e)) / emitter.area);
  }
  detail::normalise_row(row, patches.size());
}

// Whether a reciprocal row's sum S_r matches the front-face hit fraction S_h of the emitter's
// own `rays` rays (the sum of its ray row): |S_r − S_h| ≤ max(0.1·S_h, 4·√(S_h(1 − S_h)/N)), the
// second term four standard errors of S_h with independent samples (Sobol' samples do better).
bool reciprocal_row_agrees(const float* reciprocal, const float* rays, std::size_t n, int count) {
  double s_r = 0.0, s_h = 0.0;
  for (std::size_t j = 0; j < n; ++j) {
    s_r += reciprocal[j];
    s_h += rays[j];
  }
  const double margin = std::max(0.1 * s_h, 4.0 * std::sqrt(s_h * (1.0 - s_h) / count));
  return std::abs(s_r - s_h) <= margin;
}

}  // namespace

void detail::row_into(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                      const FormFactorOptions& options, float* row) {
  if (options.method == FormFactorMethod::Analytic) {
    if (options.quadrature_points != 1 && options.quadrature_points != 3)
      throw std::invalid_argument("form factors: quadrature_points must be 1 or 3");
    AnalyticSender sender(patches, caster, i, options.quadrature_points);
    for (uint32_t j = 0; j < patches.size(); ++j) row[j] = sender.entry(j);
    normalise_row(row, patches.size());
  } else if (options.method == FormFactorMethod::Hemicube) {
    std::vector<float> hemicube;
    hemicube_row(patches, caster, i, options.hemicube_resolution, &hemicube);
    std::copy(hemicube.begin(), hemicube.end(), row);
  } else {
    if (options.rays_per_patch < 1 || options.emitter_rays_per_patch < 0)
      throw std::invalid_argument("form factors: rays_per_patch must be at least 1");
    const bool emits = patches[i].emission != glm::dvec3(0.0);
    if (emits && options.emitter_rows == EmitterRows::Reciprocal) {
      if (options.quadrature_points != 1 && options.quadrature_points != 3)
        throw std::invalid_argument("form factors: quadrature_points must be 1 or 3");
      reciprocal_row(patches, caster, i, options.quadrature_points, row);
      // The receivers' quadrature points can miss most of the light of an emitter close to
      // receivers far larger than that distance; the row is then the emitter's own rays.
      std::vector<float> rays(patches.size(), 0.f);
      ray_row(patches, caster, i, options, rays.data());
      if (!reciprocal_row_agrees(row, rays.data(), patches.size(),
                                 detail::rays_of(patches[i], options)))
        std::copy(rays.begin(), rays.end(), row);
    } else {
      ray_row(patches, caster, i, options, row);
    }
  }
}

double point_polygon_form_factor(const glm::dvec3& x, const glm::dvec3& n,
                                 const std::vector<glm::dvec3>& polygon) {
  const std::vector<glm::dvec3> q = clip_to_front(x, n, polygon);
  if (q.size() < 3) return 0.0;
  double sum = 0.0;
  for (std::size_t k = 0; k < q.size(); ++k) {
    const glm::dvec3 a = q[k] - x, b = q[(k + 1) % q.size()] - x;
    const glm::dvec3 c = glm::cross(a, b);
    const double length = glm::length(c);
    if (!(length > 0.0)) continue;  // an edge through x, or a zero-length edge
    const double beta = std::atan2(length, glm::dot(a, b));
    sum += beta * glm::dot(n, c) / length;
  }
  return std::clamp(std::abs(sum) / numerics::kTwoPi, 0.0, 1.0);
}

double polygon_polygon_form_factor(const std::vector<glm::dvec3>& a,
                                   const std::vector<glm::dvec3>& b, int quadrature_steps) {
  if (a.size() < 3 || b.size() < 3 || quadrature_steps < 1)
    throw std::invalid_argument("polygon_polygon_form_factor: polygons need 3 corners, m ≥ 1");
  const glm::dvec3 n = newell_normal(a);
  const int m = quadrature_steps;
  double weighted = 0.0, area = 0.0;
  for (std::size_t k = 1; k + 1 < a.size(); ++k) {
    const glm::dvec3 o = a[0], e1 = a[k] - a[0], e2 = a[k + 1] - a[0];
    const double cell = 0.5 * glm::length(glm::cross(e1, e2)) / (double(m) * m);
    for (int j = 0; j < m; ++j) {
      for (int i = 0; i + j < m; ++i) {
        weighted += cell * point_polygon_form_factor(
                               o + e1 * ((i + 1.0 / 3) / m) + e2 * ((j + 1.0 / 3) / m), n, b);
        if (i + j < m - 1)
          weighted += cell * point_polygon_form_factor(
                                 o + e1 * ((i + 2.0 / 3) / m) + e2 * ((j + 2.0 / 3) / m), n, b);
      }
    }
    area += cell * double(m) * m;
  }
  return area > 0.0 ? weighted / area : 0.0;
}

void form_factor_row(const std::vector<Patch>& patches, const scene::RayCaster& caster, uint32_t i,
                     const FormFactorOptions& options, std::vector<float>* row) {
  row->assign(patches.size(), 0.f);
  detail::row_into(patches, caster, i, options, row->data());
}

double FormFactorMatrix::row_sum(std::size_t i) const {
  double sum = 0.0;
  for (std::size_t j = 0; j < size; ++j) sum += f[i * size + j];
  return sum;
}

FormFactorMatrix compute_form_factors(const std::vector<Patch>& patches,
                                      const scene::RayCaster& caster,
                                      const FormFactorOptions& options) {
  FormFactorMatrix m;
  m.size = patches.size();
  detail::assign_zeroed_large(&m.f, m.size * m.size);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, m.size, 8),
                    [&](const tbb::blocked_range<std::size_t>& range) {
                      for (std::size_t i = range.begin(); i != range.end(); ++i)
                        detail::row_into(patches, caster, static_cast<uint32_t>(i), options,
                                         m.f.data() + i * m.size);
                    });
  if (options.method == FormFactorMethod::Hemicube) combine_hemicube_estimates(patches, &m.f);
  return m;
}

double escape_fraction(const std::vector<Patch>& patches, const scene::RayCaster& caster,
                       int rays_per_patch, uint64_t seed) {
  std::vector<double> escaped(patches.size(), 0.0);
  const float inf = std::numeric_limits<float>::infinity();
  tbb::parallel_for(std::size_t(0), patches.size(), [&](std::size_t i) {
    const Patch& s = patches[i];
    if (s.area <= 0.0) return;
    detail::PatchRandom random(seed, i);
    int count = 0;
    for (int k = 0; k < rays_per_patch; ++k) {
      const glm::dvec3 p = random.point_on(s);
      const glm::dvec3 d = random.cosine_direction(s.normal);
      const glm::vec3 o =
          caster.surface_origin(static_cast<uint32_t>(i), glm::vec3(p), glm::vec3(s.normal));
      if (!caster.intersect(o, glm::vec3(d), 0.f, inf).hit) ++count;
    }
    escaped[i] = s.area * count / rays_per_patch;
  });
  double total = 0.0, area = 0.0;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    total += escaped[i];
    area += patches[i].area;
  }
  return area > 0.0 ? total / area : 0.0;
}

}  // namespace prt::radiosity
