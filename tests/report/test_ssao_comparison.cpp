// The per-pixel truth of `prt report --ssao` (report/ssao_comparison.h) against the AO closed
// form beside a wall, obscurance beyond its distance, nearest hits and thickness; and the error
// regions on a synthetic capture whose errors are known.
#include <cmath>
#include <limits>

#include <catch2/catch.hpp>

#include "report/ssao_comparison.h"
#include "scene/procedural_mesh.h"

using namespace prt::report;

namespace {

// A capture of `points` (front side, normal +Y), one row.
AoCapture floor_capture(const std::vector<glm::vec3>& points) {
  AoCapture c;
  c.width = static_cast<int>(points.size());
  c.height = 1;
  for (const glm::vec3& p : points) {
    c.position.insert(c.position.end(), {p.x, p.y, p.z, 1.f});
    c.normal.insert(c.normal.end(), {0.f, 1.f, 0.f, 1.f});
  }
  return c;
}

}  // namespace

TEST_CASE("ssao truth: per-pixel AO beside a wall, obscurance beyond D, nearest hit, thickness") {
  // Floor y = 0 facing +Y, a wall z = 1 of height 1 (x ∈ [−20, 20]) and a plate 0.05 below the
  // floor facing down (the floor's thickness).
  prt::scene::Scene scene =
      prt::scene::make_quad({-3.f, 0, -3.f}, {0, 0, 4}, {6, 0, 0}, 4, 4, glm::vec3(0.5f), "floor");
  prt::scene::append_scene(scene, prt::scene::make_quad({-20.f, 0, 1.f}, {40, 0, 0}, {0, 1, 0}, 8,
                                                        1, glm::vec3(0.5f), "wall"));
  prt::scene::append_scene(scene, prt::scene::make_quad({-3.f, -0.05f, -3.f}, {6, 0, 0}, {0, 0, 4},
                                                        2, 2, glm::vec3(0.5f), "under"));
  const prt::scene::RayCaster caster(scene);
  const std::vector<double> distances = {0.5, 1.0, 2.0};
  std::vector<glm::vec3> points;
  for (double d : distances) points.emplace_back(0.f, 0.f, static_cast<float>(1.0 - d));
  const AoCapture capture = floor_capture(points);
  PixelTruthOptions o;
  o.rays = 4096;
  o.obscurance = {1.5, prt::bake::ObscuranceFalloff::Constant};
  const PixelTruth t = trace_pixel_truth(scene, caster, capture, o);
  REQUIRE(t.rays == 4096);
  for (std::size_t i = 0; i < distances.size(); ++i) {
    const double d = distances[i];
    INFO("d = " << d);
    const double occluded = 0.5 * (1.0 - d / std::sqrt(d * d + 1.0));
    // 4σ of 4096 samples (scrambled nets do no worse than e × the independent variance) plus
    // the ray offset (2e-4 × the scene's diagonal ≈ 8e-3 lowers the wall: < 2e-3 here).
    const double bound = 4.0 * std::sqrt(std::exp(1.0) * occluded * (1 - occluded) / 4096) + 2e-3;
    CHECK(1.0 - t.ao[i] == Approx(occluded).margin(bound));
    // The nearest hit: the wall is at least d away, and rays near the horizon reach it close to d.
    CHECK(t.nearest[i] >= d * 0.999);
    CHECK(t.nearest[i] < d * 1.2);
    CHECK(t.thickness[i] == Approx(0.05).margin(0.01));
    // Constant falloff at D = 1.5: the wall at d = 2 no longer occludes; nearer, AO within D.
    if (d > 1.5)
      CHECK(t.obscurance[i] == 1.f);
    else
      CHECK(t.obscurance[i] < 1.f);
    CHECK(t.obscurance[i] >= t.ao[i]);
  }
}

TEST_CASE("ssao error regions: known errors land in the edge band, contact, thin and bins") {
  AoCapture c;
  c.width = 40;
  c.height = 20;
  c.eye = glm::vec3(0.f);
  const std::size_t n = 800;
  std::vector<float> truth(n, 0.5f);
  PixelTruth traced;
  traced.nearest.assign(n, 10.f);
  traced.thickness.assign(n, std::numeric_limits<float>::infinity());
  c.estimates.emplace_back(4 * n, 0.f);
  c.estimate_names.emplace_back("test");
  RegionRule rule;
  rule.radius = 1;
  rule.edge_fraction = 0.1;  // a band of 2 pixels
  std::size_t edge = 0;
  for (int y = 0; y < c.height; ++y)
    for (int x = 0; x < c.width; ++x) {
      const std::size_t px = static_cast<std::size_t>(y) * c.width + x;
      // Eye distance x + 1: bins of width 10 over [1, 41).
      c.position.insert(c.position.end(), {0.f, 0.f, static_cast<float>(x + 1), 1.f});
      c.normal.insert(c.normal.end(), {0.f, 0.f, -1.f, 1.f});
      const bool band = x < 2 || y < 2 || x >= 38 || y >= 18;
      edge += band;
      c.estimates[0][4 * px] = band ? 0.6f : 0.5f;
      if (x == 20 && y == 10) traced.nearest[px] = 0.05f;   // contact (< 0.1 R)
      if (x == 21 && y == 10) traced.thickness[px] = 0.1f;  // thin (< 0.25 R)
    }
  c.position[4 * (10 * 40 + 22) + 3] = 2.f;  // the back side of a surface: not measured
  RegionErrors e;
  e.distance.resize(4);
  accumulate_errors(c, 0, truth, traced, rule, 1.0, 41.0, e);
  CHECK(e.all.n == n - 1);
  CHECK(e.edge.n == edge);
  CHECK(e.interior.n == n - 1 - edge);
  CHECK(e.edge.stats().rms == Approx(0.1).epsilon(1e-5));
  CHECK(e.edge.stats().bias == Approx(0.1).epsilon(1e-5));
  CHECK(e.interior.stats().rms == 0.0);
  CHECK(e.contact.n == 1);
  CHECK(e.thin.n == 1);
  // Relative RMS: √(Σe²/Σt²) = √(edge · 0.01 / ((n − 1) · 0.25)).
  CHECK(e.all.stats().relative_rms ==
        Approx(std::sqrt(static_cast<double>(edge) * 0.01 / (static_cast<double>(n - 1) * 0.25)))
            .epsilon(1e-5));
  uint64_t binned = 0;
  for (const ErrorAccumulator& b : e.distance) {
    CHECK(b.n > 0);
    binned += b.n;
  }
  CHECK(binned == n - 1);
  CHECK(e.distance[0].n == 10 * 20);  // x = 0..9 → distances 1..10
  double lo = 0, hi = 0;
  eye_distance_range(c, lo, hi);
  CHECK(lo == Approx(1.0));
  CHECK(hi == Approx(40.0));
}
