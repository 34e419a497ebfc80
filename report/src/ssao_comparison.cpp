// report/src/ssao_comparison.cpp — the ray-traced per-pixel truth and the error regions of
// screen-space AO (ssao_comparison.h).
#include "report/ssao_comparison.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "bake/sampling.h"

namespace prt::report {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

// One pixel's rays: AO, obscurance and the nearest hit.
void trace_pixel(const scene::RayCaster& caster, const PixelTruthOptions& o, float offset,
                 std::size_t pixel, const glm::vec3& p, const glm::vec3& n, PixelTruth& t) {
  glm::vec3 dirs[bake::kPacketSize];
  scene::RayCaster::Hit hits[bake::kPacketSize];
  const glm::vec3 origin = p + offset * n;
  double open = 0, obscured = 0;
  float nearest = kInf;
  for (int first = 0; first < t.rays; first += bake::kPacketSize) {
    bake::generate_cosine_directions(n, o.seed, pixel, static_cast<uint32_t>(first),
                                     bake::kPacketSize, dirs);
    caster.intersect_packet(origin, dirs, bake::kPacketSize, kInf, hits);
    for (int i = 0; i < bake::kPacketSize; ++i) {
      open += hits[i].hit ? 0.0 : 1.0;
      if (hits[i].hit) nearest = std::min(nearest, hits[i].t);
      if (o.obscurance.enabled())
        obscured += hits[i].hit ? bake::obscurance_weight(o.obscurance.falloff, hits[i].t,
                                                          o.obscurance.distance)
                                : 1.0;
    }
  }
  t.ao[pixel] = static_cast<float>(open / t.rays);
  if (o.obscurance.enabled()) t.obscurance[pixel] = static_cast<float>(obscured / t.rays);
  t.nearest[pixel] = nearest;
  // Thickness: from just below the surface, along −n, to the first surface.
  const scene::RayCaster::Hit below = caster.intersect(p - offset * n, -n, 0.f, kInf);
  t.thickness[pixel] = below.hit ? below.t : kInf;
}

}  // namespace

PixelTruth trace_pixel_truth(const scene::Scene& scene, const scene::RayCaster& caster,
                             const AoCapture& c, const PixelTruthOptions& o) {
  const std::size_t pixels = static_cast<std::size_t>(c.width) * c.height;
  PixelTruth t;
  t.rays = (std::max(1, o.rays) + bake::kPacketSize - 1) / bake::kPacketSize * bake::kPacketSize;
  t.ao.assign(pixels, -1.f);
  if (o.obscurance.enabled()) t.obscurance.assign(pixels, -1.f);
  t.nearest.assign(pixels, kInf);
  t.thickness.assign(pixels, kInf);
  const float offset = 2e-4f * scene.extent();
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, pixels, 256),
      [&](const tbb::blocked_range<std::size_t>& range) {
        for (std::size_t px = range.begin(); px != range.end(); ++px) {
          if (!c.front(px)) continue;
          const glm::vec3 p(c.position[4 * px], c.position[4 * px + 1], c.position[4 * px + 2]);
          const glm::vec3 n(c.normal[4 * px], c.normal[4 * px + 1], c.normal[4 * px + 2]);
          const float len = glm::length(n);
          if (len > 0.5f) trace_pixel(caster, o, offset, px, p, n / len, t);
        }
      });
  return t;
}

void ErrorAccumulator::add(double estimate, double truth) {
  const double e = estimate - truth;
  sum_e2 += e * e;
  sum_t2 += truth * truth;
  sum_e += e;
  sum_t += truth;
  ++n;
}

void ErrorAccumulator::merge(const ErrorAccumulator& o) {
  sum_e2 += o.sum_e2;
  sum_t2 += o.sum_t2;
  sum_e += o.sum_e;
  sum_t += o.sum_t;
  n += o.n;
}

ErrorStats ErrorAccumulator::stats() const {
  ErrorStats s;
  s.pixels = n;
  if (n == 0) return s;
  s.relative_rms = sum_t2 > 0 ? std::sqrt(sum_e2 / sum_t2) : 0.0;
  s.rms = std::sqrt(sum_e2 / static_cast<double>(n));
  s.bias = sum_e / static_cast<double>(n);
  s.truth_mean = sum_t / static_cast<double>(n);
  return s;
}

void RegionErrors::merge(const RegionErrors& o) {
  all.merge(o.all);
  contact.merge(o.contact);
  thin.merge(o.thin);
  edge.merge(o.edge);
  interior.merge(o.interior);
  if (distance.size() < o.distance.size()) distance.resize(o.distance.size());
  for (std::size_t i = 0; i < o.distance.size(); ++i) distance[i].merge(o.distance[i]);
}

void eye_distance_range(const AoCapture& c, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = 0;
  for (std::size_t px = 0; px < static_cast<std::size_t>(c.width) * c.height; ++px) {
    if (!c.front(px)) continue;
    const glm::vec3 p(c.position[4 * px], c.position[4 * px + 1], c.position[4 * px + 2]);
    const double d = glm::length(p - c.eye);
    lo = std::min(lo, d);
    hi = std::max(hi, d);
  }
}

void accumulate_errors(const AoCapture& c, int estimate, const std::vector<float>& truth,
                       const PixelTruth& traced, const RegionRule& rule, double d_lo, double d_hi,
                       RegionErrors& out) {
  const std::vector<float>& est = c.estimates[static_cast<std::size_t>(estimate)];
  const int band = std::max(1, static_cast<int>(std::lround(rule.edge_fraction * c.height)));
  const std::size_t bins = out.distance.size();
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const std::size_t px = static_cast<std::size_t>(y) * c.width + x;
      if (!c.front(px) || truth[px] < 0.f) continue;
      const double e = est[4 * px], t = truth[px];
      out.all.add(e, t);
      if (traced.nearest[px] < rule.contact_fraction * rule.radius) out.contact.add(e, t);
      if (traced.thickness[px] < rule.thin_fraction * rule.radius) out.thin.add(e, t);
      const bool edge = x < band || y < band || x >= c.width - band || y >= c.height - band;
      (edge ? out.edge : out.interior).add(e, t);
      if (bins == 0) continue;
      const glm::vec3 p(c.position[4 * px], c.position[4 * px + 1], c.position[4 * px + 2]);
      const double f = (glm::length(p - c.eye) - d_lo) / std::max(d_hi - d_lo, 1e-30);
      const auto bin = static_cast<std::size_t>(
          std::clamp(f * static_cast<double>(bins), 0.0, static_cast<double>(bins) - 1.0));
      out.distance[bin].add(e, t);
    }
}

}  // namespace prt::report
