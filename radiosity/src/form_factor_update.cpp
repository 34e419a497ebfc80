#include "radiosity/form_factor_update.h"

#include <algorithm>
#include <atomic>
#include <memory>
#include <stdexcept>

#include <tbb/parallel_for.h>

#include "form_factor_rows.h"

namespace prt::radiosity {
namespace {

struct Box {
  glm::dvec3 lo{1e300}, hi{-1e300};
  void add(const glm::dvec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
};

// Does the segment a → b meet the box (slab test, closed)?
bool segment_meets(const glm::dvec3& a, const glm::dvec3& b, const Box& box) {
  double t0 = 0.0, t1 = 1.0;
  for (int k = 0; k < 3; ++k) {
    const double d = b[k] - a[k];
    if (d == 0.0) {
      if (a[k] < box.lo[k] || a[k] > box.hi[k]) return false;
      continue;
    }
    double u = (box.lo[k] - a[k]) / d, v = (box.hi[k] - a[k]) / d;
    if (u > v) std::swap(u, v);
    t0 = std::max(t0, u);
    t1 = std::min(t1, v);
    if (t0 > t1) return false;
  }
  return true;
}

// Does any corner of the box lie on or in front of the plane of patch p?
bool in_front(const Patch& p, const Box& box) {
  for (int c = 0; c < 8; ++c) {
    const glm::dvec3 q((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y,
                       (c & 4) ? box.hi.z : box.lo.z);
    if (glm::dot(p.normal, q - p.centroid) >= 0.0) return true;
  }
  return false;
}

bool same_corners(const Patch& a, const Patch& b) {
  return a.corners[0] == b.corners[0] && a.corners[1] == b.corners[1] &&
         a.corners[2] == b.corners[2];
}

}  // namespace

FormFactorUpdate update_form_factors(const std::vector<Patch>& before,
                                     const std::vector<Patch>& after,
                                     const scene::RayCaster& caster,
                                     const FormFactorOptions& options, FormFactorMatrix* f) {
  const std::size_t n = after.size();
  if (before.size() != n || f->size != n || f->f.size() != n * n)
    throw std::invalid_argument("update_form_factors: the same patches before and after needed");
  std::vector<char> moved(n, 0);
  Box region_before, region_after, scene_box;
  FormFactorUpdate update;
  for (std::size_t i = 0; i < n; ++i) {
    for (const glm::dvec3& c : after[i].corners) scene_box.add(c);
    if (same_corners(before[i], after[i])) continue;
    moved[i] = 1;
    ++update.moved_patches;
    for (const glm::dvec3& c : before[i].corners) region_before.add(c);
    for (const glm::dvec3& c : after[i].corners) region_after.add(c);
  }
  if (update.moved_patches == 0) return update;
  // Visibility rays start and end ε off the surfaces (scene/ray_offset.h), far below this pad.
  const glm::dvec3 pad(1e-3 * glm::length(scene_box.hi - scene_box.lo));
  for (Box* b : {&region_before, &region_after}) {
    b->lo -= pad;
    b->hi += pad;
  }
  const auto meets = [&](const glm::dvec3& a, const glm::dvec3& b) {
    return segment_meets(a, b, region_before) || segment_meets(a, b, region_after);
  };

  if (options.method == FormFactorMethod::Hemicube) {  // each entry needs two hemicubes
    *f = compute_form_factors(after, caster, options);
    update.rows_recomputed = n;
    return update;
  }
  const bool analytic = options.method == FormFactorMethod::Analytic;
  std::vector<std::vector<glm::dvec3>> points(analytic ? n : 0);
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = detail::quadrature_points(after[i], options.quadrature_points);
  std::atomic<std::size_t> rows{0}, entries{0};
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t i) {
    float* row = f->f.data() + i * n;
    const auto recompute_row = [&] {
      std::fill(row, row + n, 0.f);
      detail::row_into(after, caster, static_cast<uint32_t>(i), options, row);
      ++rows;
    };
    if (!analytic) {
      if (moved[i] || in_front(after[i], region_before) || in_front(after[i], region_after))
        recompute_row();
      return;
    }
    double sum = 0.0;
    for (std::size_t j = 0; j < n; ++j) sum += row[j];
    if (moved[i] || sum >= 1.0 - 1e-6) {
      recompute_row();
      return;
    }
    const std::vector<glm::dvec3>& xs = points[i];
    std::unique_ptr<detail::AnalyticSender> sender;
    std::size_t patched = 0;
    for (std::size_t j = 0; j < n; ++j) {
      bool affected = moved[j] != 0;
      if (!affected) {
        const std::vector<glm::dvec3>& ys = points[j];
        for (std::size_t k = 0; k < xs.size() && !affected; ++k) affected = meets(xs[k], ys[k]);
      }
      if (!affected) continue;
      if (!sender)
        sender = std::make_unique<detail::AnalyticSender>(after, caster, static_cast<uint32_t>(i),
                                                          options.quadrature_points);
      row[j] = sender->entry(static_cast<uint32_t>(j));
      ++patched;
    }
    detail::normalise_row(row, n);
    entries += patched;
  });
  update.rows_recomputed = rows;
  update.entries_recomputed = entries;
  return update;
}

}  // namespace prt::radiosity
