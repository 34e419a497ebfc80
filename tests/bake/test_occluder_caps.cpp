// Tests of bake/adaptive/occluder_caps.h (per-vertex cones holding every blockable direction, found
// without rays) and bake/adaptive/cap_sampling.h (mixture sampling over a union of such cones).
#include <catch2/catch.hpp>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <tbb/parallel_for.h>

#include "bake/adaptive/cap_sampling.h"
#include "bake/adaptive/occluder_caps.h"
#include "bake/adaptive/scene_analysis.h"
#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "sh/basis.h"
#include "sh/constants.h"

using namespace prt::bake;
using namespace prt::scene;

namespace {

using prt::sh::kHalfPi;  // the baker's default max_cap_solid_angle
using prt::sh::kPi;

// An 8×8 floor (40 segments, +Y up) with a sphere, a box and a thin rug on it. Vertices
// [0, kFloorVertices) are the floor's.
constexpr uint32_t kFloorVertices = 41 * 41;
Scene plane_with_objects() {
  Scene s = make_quad({-4.f, 0.f, 4.f}, {8.f, 0.f, 0.f}, {0.f, 0.f, -8.f}, 40, 40, glm::vec3(0.5f),
                      "ground");
  append_scene(s, make_uv_sphere({-1.5f, 0.6f, 0.f}, 0.6f, 16, 32, false, glm::vec3(0.5f), "ball"));
  append_scene(s, make_box({1.f, 0.f, -0.5f}, {2.f, 1.f, 0.5f}, 4, false, glm::vec3(0.5f), "box"));
  // A thin rug, 4 mm high (≈ 9τ, τ ≈ 0.45 mm here): probes the "within τ of the tangent plane"
  // culling near its threshold (rays from the floor at height ε ≈ 1.1 mm graze its sides).
  append_scene(s,
               make_box({-3.f, 0.f, -3.f}, {-2.f, 0.004f, -2.f}, 2, false, glm::vec3(0.5f), "rug"));
  return s;
}

// Two spheres with a gap of 0.8 between them: each sees the other one only.
Scene two_spheres() {
  Scene s = make_uv_sphere({0.f, 0.f, 0.f}, 1.f, 16, 32, false, glm::vec3(0.5f), "a");
  append_scene(s, make_uv_sphere({2.6f, 0.f, 0.f}, 0.8f, 16, 32, false, glm::vec3(0.5f), "b"));
  return s;
}

glm::dvec3 unit(const glm::vec3& d) {
  return glm::normalize(glm::dvec3(d));
}

// How far ω lies outside the nearest cap, in 1 − cos units (≤ 0: inside one of them).
double excess(const DirectionCap* caps, std::size_t count, const glm::dvec3& w) {
  double best = INFINITY;
  for (std::size_t j = 0; j < count; ++j) {
    const glm::dvec3 d = w - caps[j].axis;
    best = std::min(best, 0.5 * glm::dot(d, d) - caps[j].one_minus_cos);
  }
  return best;
}

bool in_some_cap(const DirectionCap* caps, std::size_t count, const glm::dvec3& w) {
  for (std::size_t j = 0; j < count; ++j)
    if (caps[j].contains(w)) return true;
  return false;
}

struct ContainmentStats {
  std::size_t covered = 0, rays = 0, hits = 0, violations = 0;
  double worst_excess = -INFINITY;  // of the violating hits (1 − cos units)
};

// For every covered vertex: rays from caster.vertex_origin(v) (tfar = ∞) in
//   - 4096 cosine-weighted scrambled Sobol' directions (the baker's own distribution),
//   - 1024 uniform random hemisphere directions (more weight near the horizon),
//   - the direction of every vertex of the `target` primitives above the tangent plane (the
//     silhouettes: the extreme directions toward the objects),
// and every direction that hits anything must lie in one of the vertex's caps.
ContainmentStats check_containment(const Scene& scene, const OccluderCaps& caps,
                                   uint32_t target_first_vertex) {
  const RayCaster caster(scene);
  std::atomic<std::size_t> covered{0}, rays{0}, hits{0}, violations{0};
  std::vector<double> worst(scene.vertex_count(), -INFINITY);
  tbb::parallel_for(uint32_t(0), static_cast<uint32_t>(scene.vertex_count()), [&](uint32_t v) {
    if (!caps.covered[v]) return;
    ++covered;
    const glm::vec3 n = glm::normalize(scene.normals[v]);
    const glm::vec3 o = caster.vertex_origin(v);
    std::vector<glm::vec3> dirs(4096);
    generate_cosine_directions(n, 77, v, 0, 4096, dirs.data());
    std::mt19937 rng(v);
    std::normal_distribution<float> g;
    for (int i = 0; i < 1024; ++i) {
      glm::vec3 d(g(rng), g(rng), g(rng));
      if (glm::dot(d, n) < 0.f) d = -d;
      dirs.push_back(glm::normalize(d));
    }
    for (uint32_t q = target_first_vertex; q < scene.vertex_count(); ++q) {
      const glm::vec3 d = scene.positions[q] - o;
      if (q != v && glm::dot(d, n) > 0.f) dirs.push_back(glm::normalize(d));
    }
    std::size_t local_hits = 0, local_violations = 0;
    bool occ[kPacketSize];
    for (std::size_t first = 0; first < dirs.size(); first += kPacketSize) {
      const int count = static_cast<int>(std::min<std::size_t>(kPacketSize, dirs.size() - first));
      caster.occluded_packet(o, &dirs[first], count, INFINITY, occ);
      for (int i = 0; i < count; ++i) {
        if (!occ[i]) continue;
        ++local_hits;
        const glm::dvec3 w = unit(dirs[first + i]);
        if (!in_some_cap(caps.of(v), caps.count(v), w)) {
          ++local_violations;
          worst[v] = std::max(worst[v], excess(caps.of(v), caps.count(v), w));
        }
      }
    }
    rays += dirs.size();
    hits += local_hits;
    violations += local_violations;
  });
  ContainmentStats s;
  s.covered = covered, s.rays = rays, s.hits = hits, s.violations = violations;
  for (double x : worst) s.worst_excess = std::max(s.worst_excess, x);
  return s;
}

// Checks the limits every covered vertex must meet; an uncovered vertex has no caps.
void check_limits(const OccluderCaps& caps, std::size_t V, int max_caps, double max_solid_angle) {
  REQUIRE(caps.covered.size() == V);
  REQUIRE(caps.first.size() == V + 1);
  REQUIRE(caps.first[V] == caps.caps.size());
  for (std::size_t v = 0; v < V; ++v) {
    CAPTURE(v);
    if (!caps.covered[v]) {
      REQUIRE(caps.count(v) == 0);
      continue;
    }
    REQUIRE(caps.count(v) <= static_cast<std::size_t>(max_caps));
    double total = 0.0;
    for (std::size_t j = 0; j < caps.count(v); ++j) {
      const DirectionCap& c = caps.of(v)[j];
      REQUIRE(std::abs(glm::length(c.axis) - 1.0) < 1e-12);
      REQUIRE(c.one_minus_cos > 0.0);
      total += c.solid_angle();
    }
    REQUIRE(total <= max_solid_angle);
  }
}

// (1/π) ∫_cap max(ω·n, 0) f(ω) dω by the midpoint rule on an M×M (θ, φ) grid in the cap's
// frame (dω = sin θ dθ dφ). Independent of the sampler: no mixture, no Sobol'.
template <class F>
double quadrature_over_cap(const DirectionCap& cap, const glm::dvec3& n, int M, F f) {
  const double alpha = 2.0 * std::asin(std::sqrt(0.5 * cap.one_minus_cos));
  const glm::dvec3 helper = std::abs(cap.axis.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  const glm::dvec3 t = glm::normalize(glm::cross(helper, cap.axis));
  const glm::dvec3 b = glm::cross(cap.axis, t);
  const double dt = alpha / M, dp = 2.0 * kPi / M;
  double sum = 0.0;
  for (int i = 0; i < M; ++i) {
    const double th = (i + 0.5) * dt, st = std::sin(th), ct = std::cos(th);
    double ring = 0.0;
    for (int k = 0; k < M; ++k) {
      const double ph = (k + 0.5) * dp;
      const glm::dvec3 w = st * (std::cos(ph) * t + std::sin(ph) * b) + ct * cap.axis;
      ring += std::max(glm::dot(w, n), 0.0) * f(w);
    }
    sum += ring * st;
  }
  return sum * dt * dp / kPi;
}

// (1/π) ∫_{union of caps} cos⁺θ f(ω) dω by brute force: an M×M midpoint grid over the
// hemisphere of n = +Y in (cos θ, φ), cells of equal solid angle 2π/M², each cell counted once
// when its centre lies in any cap (membership only: no overlap bookkeeping).
template <class F>
double quadrature_over_union(const std::vector<DirectionCap>& caps, int M, F f) {
  const double dz = 1.0 / M, dp = 2.0 * kPi / M;
  double sum = 0.0;
  for (int i = 0; i < M; ++i) {
    const double z = (i + 0.5) * dz, s = std::sqrt(1.0 - z * z);
    for (int k = 0; k < M; ++k) {
      const double ph = (k + 0.5) * dp;
      const glm::dvec3 w(s * std::cos(ph), z, s * std::sin(ph));
      if (in_some_cap(caps.data(), caps.size(), w)) sum += z * f(w);
    }
  }
  return sum * dz * dp / kPi;
}

DirectionCap cap_around(const glm::dvec3& axis, double half_angle) {
  DirectionCap c;
  c.axis = glm::normalize(axis);
  const double s = std::sin(0.5 * half_angle);
  c.one_minus_cos = 2.0 * s * s;
  return c;
}

// Direction at polar angle θ from +Y and azimuth φ (from +X toward +Z).
glm::dvec3 polar(double theta, double phi) {
  return {std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi)};
}

struct Estimate {
  double mean_w = 0.0;       // (1/N) Σ w f
  double mean_w_no_k = 0.0;  // the same with k(ω) ignored: w·k
  double in_caps = 0.0;      // fraction of directions in some cap
};

// (1/N) Σ w(ω_s) f(ω_s) over N points of generate_cap_directions.
template <class F>
Estimate estimate(const std::vector<DirectionCap>& caps, const glm::vec3& n, uint64_t seed, int N,
                  F f) {
  std::vector<glm::vec3> dirs(N);
  std::vector<double> w(N);
  generate_cap_directions(caps.data(), static_cast<int>(caps.size()), n, seed, 5, 0, N, dirs.data(),
                          w.data());
  Estimate e;
  for (int i = 0; i < N; ++i) {
    const glm::dvec3 d = unit(dirs[i]);
    int k = 0;
    for (const DirectionCap& c : caps) k += c.contains(d);
    e.mean_w += w[i] * f(d);
    e.mean_w_no_k += w[i] * std::max(k, 1) * f(d);
    e.in_caps += k > 0;
  }
  e.mean_w /= N, e.mean_w_no_k /= N, e.in_caps /= N;
  return e;
}

double one(const glm::dvec3&) {
  return 1.0;
}

}  // namespace

TEST_CASE("occluder caps: every direction that hits something lies in a cap (floor scene)") {
  const Scene scene = plane_with_objects();
  const VertexRayStarts starts = compute_vertex_ray_starts(scene);
  const OccluderCaps caps = find_occluder_caps(scene, starts, {}, kDefaultMaxCaps, kHalfPi);
  check_limits(caps, scene.vertex_count(), kDefaultMaxCaps, kHalfPi);

  const ContainmentStats s = check_containment(scene, caps, kFloorVertices);
  CAPTURE(s.covered, s.rays, s.hits, s.worst_excess);
  // A proof, not a statistic: not one hit outside the caps.
  CHECK(s.violations == 0);
  // The rays did reach the objects (else the check above says nothing).
  CHECK(s.hits > 100000);

  // The finder must not give up everywhere: most of the floor is far from the objects, and a
  // covered floor vertex sees both objects above its horizon, so it holds at least one cap.
  std::size_t floor_covered = 0;
  for (uint32_t v = 0; v < kFloorVertices; ++v) {
    if (!caps.covered[v]) continue;
    ++floor_covered;
    CHECK(caps.count(v) >= 1);
  }
  CAPTURE(floor_covered);
  CHECK(floor_covered > kFloorVertices / 2);
  // The top pole of the ball sees nothing: covered with no cap at all.
  const uint32_t ball_top = kFloorVertices;
  CHECK(caps.covered[ball_top] == 1);
  CHECK(caps.count(ball_top) == 0);
}

TEST_CASE("occluder caps: every direction that hits something lies in a cap (two spheres)") {
  const Scene scene = two_spheres();
  const VertexRayStarts starts = compute_vertex_ray_starts(scene);
  // More caps allowed here: a vertex facing the other sphere from 0.8 away needs several.
  const int max_caps = 16;
  const double max_solid = 2.0 * kPi;
  const OccluderCaps caps = find_occluder_caps(scene, starts, {}, max_caps, max_solid);
  check_limits(caps, scene.vertex_count(), max_caps, max_solid);
  std::size_t with_caps = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v)
    with_caps += caps.covered[v] && caps.count(v) > 0;

  // Rays toward every vertex of both spheres (each one sees the other's silhouette).
  const ContainmentStats s = check_containment(scene, caps, 0);
  CAPTURE(s.covered, with_caps, s.rays, s.hits, s.worst_excess);
  CHECK(s.violations == 0);
  CHECK(s.hits > 50000);
  // Half of each sphere faces away from the other (covered with no cap); of the facing half a
  // good share must be covered with caps too.
  CHECK(s.covered > scene.vertex_count() / 2);
  CHECK(with_caps > scene.vertex_count() / 8);
}

TEST_CASE("occluder caps: a vertex whose caps break the limits is not covered") {
  const Scene scene = plane_with_objects();
  const VertexRayStarts starts = compute_vertex_ray_starts(scene);
  // Floor vertex (i, j) sits at (−4 + 0.2 i, 0, 4 − 0.2 j). The box spans x ∈ [1, 2],
  // y ∈ [0, 1], z ∈ [−0.5, 0.5]: vertex (24, 20) = (0.8, 0, 0) is 0.2 from its −X face,
  // vertex (25, 20) = (1, 0, 0) lies on the bottom edge of that face (a vertex of its
  // triangles), vertex (27, 20) = (1.4, 0, 0) is under the box, shut in by it.
  const uint32_t near_box = 20 * 41 + 24, on_box = 20 * 41 + 25, under_box = 20 * 41 + 27;
  REQUIRE(scene.positions[near_box] == glm::vec3(0.8f, 0.f, 0.f));
  REQUIRE(scene.positions[on_box] == glm::vec3(1.f, 0.f, 0.f));

  // No limits: how many caps, of which total solid angle, the vertex next to the box gets (the
  // sum of the caps' solid angles, overlaps counted twice: it exceeds 4π here).
  const OccluderCaps loose = find_occluder_caps(scene, starts, {}, 255, INFINITY);
  REQUIRE(loose.covered[near_box] == 1);
  const std::size_t m = loose.count(near_box);
  double total = 0.0;
  for (std::size_t j = 0; j < m; ++j) total += loose.of(near_box)[j].solid_angle();
  CAPTURE(m, total);
  REQUIRE(m >= 2);
  // The box face fills most of the sky toward +X: far more than π/2 sr.
  CHECK(total > kHalfPi);

  // The same limits exactly: still covered, the same caps.
  const OccluderCaps exact = find_occluder_caps(scene, starts, {}, static_cast<int>(m), total);
  CHECK(exact.covered[near_box] == 1);
  CHECK(exact.count(near_box) == m);
  // One cap fewer, or a solid angle a little smaller: not covered, no caps.
  const OccluderCaps few = find_occluder_caps(scene, starts, {}, static_cast<int>(m) - 1, INFINITY);
  CHECK(few.covered[near_box] == 0);
  CHECK(few.count(near_box) == 0);
  const OccluderCaps small = find_occluder_caps(scene, starts, {}, 255, 0.99 * total);
  CHECK(small.covered[near_box] == 0);
  CHECK(small.count(near_box) == 0);
  // The baker's defaults (8 caps, π/2 sr): not covered.
  const OccluderCaps def = find_occluder_caps(scene, starts, {}, kDefaultMaxCaps, kHalfPi);
  CHECK(def.covered[near_box] == 0);
  CHECK(def.count(near_box) == 0);

  // On the box's edge the vertex lies inside its triangles' balls: never covered, whatever the
  // limits.
  CHECK(loose.covered[on_box] == 0);
  CHECK(loose.count(on_box) == 0);

  // Under the box, without limits, the caps must hold the whole hemisphere (every ray hits the
  // box from inside; its bottom face, at height 0 ≤ τ, is rightly dropped): check with rays.
  REQUIRE(loose.covered[under_box] == 1);
  {
    const RayCaster caster(scene);
    const glm::vec3 n = glm::normalize(scene.normals[under_box]);
    std::vector<glm::vec3> dirs(4096);
    generate_cosine_directions(n, 77, under_box, 0, 4096, dirs.data());
    int hits = 0, outside = 0;
    for (const glm::vec3& d : dirs) {
      if (!caster.occluded(caster.vertex_origin(under_box), d, 0.f, INFINITY)) continue;
      ++hits;
      outside += !in_some_cap(loose.of(under_box), loose.count(under_box), unit(d));
    }
    CAPTURE(loose.count(under_box));
    CHECK(hits == 4096);
    CHECK(outside == 0);
  }

  // Vertices not wanted get nothing; the wanted ones get what they get without the mask.
  std::vector<uint8_t> wanted(scene.vertex_count(), 0);
  wanted[near_box] = 1;
  const OccluderCaps only = find_occluder_caps(scene, starts, wanted, 255, INFINITY);
  CHECK(only.covered[near_box] == 1);
  CHECK(only.count(near_box) == m);
  CHECK(std::count(only.covered.begin(), only.covered.end(), uint8_t{1}) == 1);
  CHECK(only.caps.size() == m);
}

TEST_CASE("cap_of_ball: half-angle asin(r/d) to 1e-12, none from inside the ball") {
  // Reference: 1 − cos(asin s) = 2 sin²(asin(s)/2) in long double (no cancellation, and a path
  // independent of the code's sin²α/(1 + cos α)).
  const glm::dvec3 dirs[] = {{0, 0, 1}, glm::normalize(glm::dvec3(0.3, -0.7, 0.2))};
  for (const glm::dvec3& dir : dirs)
    for (double d : {1e-3, 1.0, 37.0, 1e5})
      for (double lg = -6.0; lg <= std::log10(0.99) + 1e-9; lg += 0.25) {
        const double s = std::min(std::pow(10.0, lg), 0.99);
        const glm::dvec3 to_center = d * dir;
        const double r = s * d;
        DirectionCap cap;
        REQUIRE(cap_of_ball(to_center, r, cap));
        const long double dl = std::sqrt(static_cast<long double>(to_center.x) * to_center.x +
                                         static_cast<long double>(to_center.y) * to_center.y +
                                         static_cast<long double>(to_center.z) * to_center.z);
        const long double half = std::asin(static_cast<long double>(r) / dl) / 2;
        const long double expected = 2 * std::sin(half) * std::sin(half);
        const double rel = static_cast<double>(
            std::abs((static_cast<long double>(cap.one_minus_cos) - expected) / expected));
        CAPTURE(d, s, cap.one_minus_cos, static_cast<double>(expected));
        CHECK(rel < 1e-12);
        CHECK(glm::length(cap.axis - glm::normalize(to_center)) < 1e-15);
        // The cap holds the ball's tangent directions, not more: a direction at the half-angle
        // (minus a hair) is in, one a hair beyond is out.
        const double a = std::asin(s);
        const glm::dvec3 t = glm::normalize(glm::cross(cap.axis, glm::dvec3(1, 0, 0)));
        CHECK(cap.contains(std::cos(a * (1 - 1e-6)) * cap.axis + std::sin(a * (1 - 1e-6)) * t));
        CHECK_FALSE(
            cap.contains(std::cos(a * (1 + 1e-6)) * cap.axis + std::sin(a * (1 + 1e-6)) * t));
      }
  DirectionCap cap;
  CHECK_FALSE(cap_of_ball({0, 0, 2}, 2.0, cap));  // d = r: on the sphere
  CHECK_FALSE(cap_of_ball({0, 0, 1}, 2.0, cap));  // inside
  CHECK_FALSE(cap_of_ball({0, 0, 0}, 0.5, cap));  // at the centre
  CHECK_FALSE(cap_of_ball({0, 0, 0}, 0.0, cap));  // d = r = 0
}

TEST_CASE("DirectionCap: contains and solid angle") {
  const DirectionCap c = cap_around({0, 1, 0}, 0.3);
  CHECK(c.solid_angle() == Approx(2 * kPi * (1 - std::cos(0.3))).epsilon(1e-14));
  CHECK(c.contains(polar(0.3 - 1e-9, 1.0)));
  CHECK_FALSE(c.contains(polar(0.3 + 1e-9, 1.0)));
  const DirectionCap tiny = cap_around({0, 1, 0}, 1e-6);
  CHECK(tiny.contains(polar(0.999e-6, 2.0)));
  CHECK_FALSE(tiny.contains(polar(1.001e-6, 2.0)));
}

TEST_CASE("cap sampling: one cap around the normal integrates cos/π to sin²α") {
  // Single cap around n: w = cos θ·Ω/π with 1 − cos θ = u₀(1 − cos α), so
  //   (1/N)Σw − sin²α = −(Ω/π)(1 − cos α)·((1/N)Σu₀ − ½)
  // and the first coordinate of 4096 scrambled Sobol' points is a (0,12,1)-net: one point in
  // each interval [i/4096, (i+1)/4096), so |(1/N)Σu₀ − ½| ≤ 1/(2N) = 1.2e-4, i.e. a relative
  // error ≤ 2(1 − cos α)/(1 + cos α) · 1.2e-4 < 2e-4 for α ≤ 1.4 (measured: ≤ 2.4e-6).
  // Tolerance 5e-4 relative: a bound, not a statistic.
  const glm::vec3 n(0.f, 1.f, 0.f);
  for (double alpha : {0.05, 0.3, 0.8, 1.4}) {
    const std::vector<DirectionCap> caps{cap_around({0, 1, 0}, alpha)};
    const double exact = std::sin(alpha) * std::sin(alpha);
    for (uint64_t seed : {1u, 2u, 3u}) {
      const Estimate e = estimate(caps, n, seed, 4096, one);
      CAPTURE(alpha, seed, e.mean_w, exact, e.in_caps);
      CHECK(std::abs(e.mean_w / exact - 1.0) < 5e-4);
      CHECK(e.in_caps == 1.0);
    }
  }
}

TEST_CASE("cap sampling: a cap straddling the horizon matches quadrature") {
  // Axis 75° from the normal, half-angle 30°: about a third of the cap lies below the horizon
  // (weight 0 there). Reference: 2000×2000 midpoint quadrature over the cap of max(cos, 0)/π
  // (kink at the horizon: 4e-9 relative to 4000×4000). The QMC estimate has a kinked integrand
  // and 4096 points: its error over 200 seeds is ≤ 6.9e-5; tolerance 5e-4 relative.
  const glm::vec3 n(0.f, 1.f, 0.f);
  const double alpha = 30.0 * kPi / 180.0;
  const std::vector<DirectionCap> caps{cap_around(polar(75.0 * kPi / 180.0, 0.4), alpha)};
  const double ref = quadrature_over_cap(caps[0], glm::dvec3(n), 2000, one);
  REQUIRE(ref > 0.01);
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Estimate e = estimate(caps, n, seed, 4096, one);
    CAPTURE(seed, e.mean_w, ref);
    CHECK(std::abs(e.mean_w / ref - 1.0) < 5e-4);
  }
}

TEST_CASE("cap sampling: two overlapping caps are unbiased on their union (k correction)") {
  // Two caps of half-angles 0.45 and 0.35 whose axes are 0.39 apart (both above the horizon):
  // their lens holds ~25% of the union's cos-weighted measure. Reference: brute-force
  // membership quadrature over the hemisphere, 3000×3000 equal-area cells (boundary error
  // 7.6e-6 relative, measured against 6000×6000). The QMC error (the integrand jumps at the
  // lens' edge, where k changes) is ≤ 1.5e-3 over 200 seeds: tolerance 3e-3 relative. An
  // estimator that ignores the overlap (k = 1) is off by the lens' share, 0.253 — 84× that.
  const glm::vec3 n(0.f, 1.f, 0.f);
  const std::vector<DirectionCap> caps{cap_around(polar(0.5, 0.0), 0.45),
                                       cap_around(polar(0.7, 0.6), 0.35)};
  const double ref = quadrature_over_union(caps, 3000, one);
  // Inclusion–exclusion with the per-cap quadrature: the lens' share.
  const double sum_caps = quadrature_over_cap(caps[0], glm::dvec3(n), 1000, one) +
                          quadrature_over_cap(caps[1], glm::dvec3(n), 1000, one);
  const double lens_share = sum_caps / ref - 1.0;
  CAPTURE(ref, sum_caps, lens_share);
  REQUIRE(lens_share > 0.1);
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Estimate e = estimate(caps, n, seed, 4096, one);
    CAPTURE(seed, e.mean_w, e.mean_w_no_k);
    CHECK(std::abs(e.mean_w / ref - 1.0) < 3e-3);
    CHECK(e.in_caps == 1.0);
    // The test has teeth: without k the estimate is off by far more than the tolerance.
    CHECK(std::abs(e.mean_w_no_k / ref - 1.0) > 0.05);
  }
}

TEST_CASE("cap sampling: a non-constant integrand (SH Y_2,1) over a union of caps") {
  // f = Y_{2,1}(ω) = 1.092548·x·z (prt::sh::evaluate), over three caps: two overlapping and one
  // straddling the horizon. Reference: the same brute-force membership quadrature. The error
  // is judged against S = (1/π)∫_union |f| cos⁺θ (f changes sign in the union); over 200 seeds
  // it is ≤ 2.4e-3·S (quadrature: 4e-5·S against 6000×6000): tolerance 5e-3·S. Ignoring the
  // overlap is off by 0.17·S, 35× that.
  const glm::vec3 n(0.f, 1.f, 0.f);
  const std::vector<DirectionCap> caps{cap_around(polar(0.6, 0.7), 0.4),
                                       cap_around(polar(0.8, 1.2), 0.3),
                                       cap_around(polar(1.4, 3.5), 0.5)};
  auto y21 = [](const glm::dvec3& w) {
    double y[9];
    prt::sh::evaluate(3, w.x, w.y, w.z, y);
    return y[prt::sh::index(2, 1)];
  };
  auto abs_y21 = [&](const glm::dvec3& w) { return std::abs(y21(w)); };
  const double ref = quadrature_over_union(caps, 3000, y21);
  const double scale = quadrature_over_union(caps, 1000, abs_y21);
  REQUIRE(std::abs(ref) > 0.2 * scale);
  for (uint64_t seed : {1u, 2u, 3u}) {
    const Estimate e = estimate(caps, n, seed, 4096, y21);
    CAPTURE(seed, e.mean_w, e.mean_w_no_k, ref, scale);
    CHECK(std::abs(e.mean_w - ref) < 5e-3 * scale);
    CHECK(std::abs(e.mean_w_no_k - ref) > 0.03 * scale);
  }
}

TEST_CASE("cap sampling: tiny caps (1e-4 rad) stay accurate") {
  // For a cap wholly above the horizon, (1/π)∫_cap ω·n dω = (a·n) sin²α exactly, and Ω(a·n)/π
  // differs from it by the factor (1 + cos α)/2 = 1 − 2.5e-9. The weight varies by ~α = 1e-4
  // across the cap and its linear part averages out over φ: QMC error ≪ 1e-6. Tolerance 1e-6.
  const glm::vec3 n = glm::normalize(glm::vec3(0.2f, 1.f, -0.1f));
  const glm::dvec3 nd = unit(n);
  const double alpha = 1e-4;
  const std::vector<DirectionCap> caps{cap_around({0.5, 0.7, 0.3}, alpha)};
  const double expected = caps[0].solid_angle() * glm::dot(caps[0].axis, nd) / kPi;
  const Estimate e = estimate(caps, n, 9, 4096, one);
  CAPTURE(e.mean_w, expected);
  CHECK(std::abs(e.mean_w / expected - 1.0) < 1e-6);

  // Every sampled direction (in double, as sample_cap_union returns it) lies in the cap, and
  // they do spread over it (not collapsed to the axis by rounding).
  const double total = total_solid_angle(caps.data(), 1);
  const uint64_t vs = hash_seed(9, 5);
  int outside = 0;
  double max_angle = 0.0;
  for (uint32_t i = 0; i < 4096; ++i) {
    const CapSample s =
        sample_cap_union(caps.data(), 1, total, nd, glm::dvec2(sample_sobol_2d(i, vs)));
    outside += !caps[0].contains(s.direction);
    const glm::dvec3 d = s.direction - caps[0].axis;
    max_angle = std::max(max_angle, std::sqrt(glm::dot(d, d)));
  }
  CAPTURE(outside, max_angle);
  CHECK(outside == 0);
  CHECK(max_angle > 0.95 * alpha);

  // Two tiny caps far apart (Ω₂ = 4Ω₁): cap j gets N_j points with |N_j − N·Ω_j/Ω| ≤ 1 (one
  // point per 1/N interval of the first coordinate), and each cap's mean weight is
  // Ω(a_j·n)/π to ~1e-9. So (1/N)Σw = Σ_j Ω_j(a_j·n)/π up to |w̄₁ − w̄₂|/N from the split,
  // and 1e-6 relative beyond that.
  const std::vector<DirectionCap> pair{cap_around({0.5, 0.7, 0.3}, alpha),
                                       cap_around({-0.4, 0.5, -0.2}, 2.0 * alpha)};
  const double total2 = total_solid_angle(pair.data(), 2);
  const double expected2 = (pair[0].solid_angle() * glm::dot(pair[0].axis, nd) +
                            pair[1].solid_angle() * glm::dot(pair[1].axis, nd)) /
                           kPi;
  const Estimate e2 = estimate(pair, n, 9, 4096, one);
  std::vector<glm::vec3> d2(4096);
  std::vector<double> w2(4096);
  generate_cap_directions(pair.data(), 2, n, 9, 5, 0, 4096, d2.data(), w2.data());
  int in_first = 0, in_second = 0;
  for (const glm::vec3& d : d2) {
    in_first += pair[0].contains(unit(d));
    in_second += pair[1].contains(unit(d));
  }
  CHECK(in_first + in_second == 4096);
  CHECK(std::abs(in_first - 4096.0 * pair[0].solid_angle() / total2) <= 1.0);
  const double split =
      total2 * std::abs(glm::dot(pair[0].axis, nd) - glm::dot(pair[1].axis, nd)) / kPi / 4096.0;
  CAPTURE(e2.mean_w, expected2, in_first, split);
  CHECK(std::abs(e2.mean_w - expected2) < split + 1e-6 * expected2);
}

TEST_CASE("occluder caps: more than 255 caps are kept, not wrapped") {
  // 300 small boxes on a ring of radius 1 around a floor vertex, in golden-angle order: boxes
  // adjacent in index are far apart on the ring, so no group of two is accepted and each box
  // needs its own cap. With max_caps = 300 the vertex is covered by ≥ 256 caps; a per-vertex
  // count kept in 8 bits would wrap and drop most of them (the walk still says "covered").
  Scene s = make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f}, 4, 4, glm::vec3(0.5f),
                      "ground");
  const uint32_t center = 2 * 5 + 2;
  REQUIRE(s.positions[center] == glm::vec3(0.f));
  std::vector<glm::vec3> box_centers;
  for (int i = 0; i < 300; ++i) {
    const float a = 2.39996323f * static_cast<float>(i);
    const glm::vec3 c(std::cos(a), 0.01f, std::sin(a));
    box_centers.push_back(c);
    append_scene(
        s, make_box(c - glm::vec3(0.01f), c + glm::vec3(0.01f), 1, false, glm::vec3(0.5f), "box"));
  }
  std::vector<uint8_t> wanted(s.vertex_count(), 0);
  wanted[center] = 1;
  const OccluderCaps caps =
      find_occluder_caps(s, compute_vertex_ray_starts(s), wanted, 300, INFINITY);
  REQUIRE(caps.covered[center] == 1);
  CHECK(caps.count(center) >= 256);
  CHECK(caps.count(center) <= 300);
  // Every box centre's direction lies in a cap.
  int outside = 0;
  for (const glm::vec3& c : box_centers)
    outside += !in_some_cap(caps.of(center), caps.count(center), unit(c));
  CHECK(outside == 0);
}

TEST_CASE("occluder caps: a vertex without a usable normal is not covered") {
  // A zero normal (normalises to NaN) has no hemisphere to prove anything about: like
  // find_open_hemispheres, the finder must leave it uncovered instead of dropping every cap as
  // "below the horizon" (NaN comparisons are false) and calling it open.
  Scene scene = plane_with_objects();
  const uint32_t v = 5 * 41 + 5;
  scene.normals[v] = glm::vec3(0.f);
  const OccluderCaps caps =
      find_occluder_caps(scene, compute_vertex_ray_starts(scene), {}, kDefaultMaxCaps, kHalfPi);
  CHECK(caps.covered[v] == 0);
  CHECK(caps.count(v) == 0);
  // Its neighbour, with its normal, is covered by caps toward the objects.
  CHECK(caps.covered[v + 1] == 1);
  CHECK(caps.count(v + 1) >= 1);
}

// ---------------------------------------------------------------------------------------------
// End-to-end: the adaptive bake (bake/transfer_baker.h) with cap sampling.
// ---------------------------------------------------------------------------------------------

namespace {

// An 8×8 floor (40 segments) with a sphere of radius 0.7 and a box standing on it, grey 0.5.
Scene cap_bake_scene() {
  Scene s = make_quad({-4.f, 0.f, 4.f}, {8.f, 0.f, 0.f}, {0.f, 0.f, -8.f}, 40, 40, glm::vec3(0.5f),
                      "ground");
  append_scene(s, make_uv_sphere({-1.5f, 0.7f, 0.f}, 0.7f, 16, 32, false, glm::vec3(0.5f), "ball"));
  append_scene(s,
               make_box({0.8f, 0.f, -0.6f}, {1.8f, 1.2f, 0.6f}, 4, false, glm::vec3(0.5f), "box"));
  return s;
}

// The adaptive bake at a fixed N samples per vertex: min = max = min_cap = N and a loose error
// target, so no allocation round runs. Jacobi bounces to 1e-6 × max|D| (the default 0.0025
// would add a truncation error of the order of the sampling error being compared).
BakeOptions fixed_adaptive(prt::TransferKind kind, int N, bool cap_sampling, uint64_t seed = 1) {
  BakeOptions o;
  o.kind = kind;
  o.order = 3;
  o.seed = seed;
  o.ao = o.bent_normals = true;
  o.adaptive.enabled = true;
  o.adaptive.min_samples = o.adaptive.max_samples = o.adaptive.min_cap_samples = N;
  o.adaptive.rms_error = 1.0;
  o.adaptive.bounce_tolerance = 1e-6;
  o.adaptive.cap_sampling = cap_sampling;
  return o;
}

// The scene, its vertices as the baker classifies them (find_occluder_caps with the baker's
// parameters: every vertex wanted, since vertex_mode is empty), the unshadowed bake and the
// references, built once per process (the 8192-sample references are the expensive part).
struct CapBakeFixture {
  Scene scene = cap_bake_scene();
  OccluderCaps caps;
  std::vector<uint32_t> capped;  // covered by ≥ 1 cap: sampled inside them
  std::vector<uint32_t> open;    // covered by no cap: analytic
  BakeResult unshadowed;
  BakeResult reference[2];  // Shadowed, Interreflected

  CapBakeFixture() {
    caps =
        find_occluder_caps(scene, compute_vertex_ray_starts(scene), {}, kDefaultMaxCaps, kHalfPi);
    for (uint32_t v = 0; v < scene.vertex_count(); ++v)
      if (caps.covered[v]) (caps.count(v) > 0 ? capped : open).push_back(v);
    BakeOptions u;
    u.kind = prt::TransferKind::Unshadowed;
    u.order = 3;
    unshadowed = bake_transfer(scene, u);
  }

  // The fixed recipe (no control variate, no caps) at 8192 samples with another seed, solved
  // to 1e-7: its own error is ≈ √(64/8192) ≈ 0.09× the 64-sample hemisphere bake's.
  const BakeResult& ref(prt::TransferKind kind) {
    BakeResult& r = reference[kind == prt::TransferKind::Interreflected ? 1 : 0];
    if (r.data.coefficients.empty()) {
      BakeOptions o;
      o.kind = kind;
      o.order = 3;
      o.samples = 8192;
      o.seed = 2;
      o.bounce_tolerance = 1e-7;
      o.ao = o.bent_normals = true;
      r = bake_transfer(scene, o);
    }
    return r;
  }
};

CapBakeFixture& cap_fixture() {
  static CapBakeFixture f;
  return f;
}

// Errors of a bake (one channel) against a reference over a set of vertices.
struct BakeErrors {
  double rms = 0.0;           // RMS over the vertices and all K coefficients (absolute)
  double rel_k0 = 0.0;        // √(Σ(T₀ − R₀)² / ΣR₀²)
  double rel_occluded = 0.0;  // √(Σ(T₀ − R₀)² / Σ(U₀ − R₀)²): against the occluded part
  double bias = 0.0;  // Σ(T₀ − R₀) / Σ(U₀ − R₀): signed, against the occluded part
  double rms_ao = 0.0;
  double max_ao = 0.0;
  double bias_ao = 0.0;       // Σ(A − A_ref) / Σ(1 − A_ref): signed, against the occlusion
  double rms_bent_deg = 0.0;  // RMS angle between the bent normals
};

BakeErrors bake_errors(const BakeResult& b, const BakeResult& ref, const BakeResult& unshadowed,
                       const std::vector<uint32_t>& vertices) {
  const std::size_t K = b.data.coefficients_per_channel();
  REQUIRE(b.data.channels == 1);
  REQUIRE(ref.data.channels == 1);
  REQUIRE(ref.data.coefficients_per_channel() == K);
  REQUIRE(b.data.ao.size() == b.data.vertex_count);
  REQUIRE(ref.data.bent_normals.size() == 3 * ref.data.vertex_count);
  double sum2 = 0.0, err0 = 0.0, ref0 = 0.0, occ0 = 0.0, sum0 = 0.0, sum_occ0 = 0.0;
  double ao2 = 0.0, ao_sum = 0.0, ao_occ = 0.0, bent2 = 0.0;
  BakeErrors e;
  for (uint32_t v : vertices) {
    const float* t = &b.data.coefficients[v * K];
    const float* r = &ref.data.coefficients[v * K];
    for (std::size_t k = 0; k < K; ++k) sum2 += (double(t[k]) - r[k]) * (double(t[k]) - r[k]);
    const double d0 = double(t[0]) - r[0], o0 = double(unshadowed.data.coefficients[v * K]) - r[0];
    err0 += d0 * d0, ref0 += double(r[0]) * r[0], occ0 += o0 * o0;
    sum0 += d0, sum_occ0 += o0;
    const double da = double(b.data.ao[v]) - ref.data.ao[v];
    ao2 += da * da, ao_sum += da, ao_occ += 1.0 - ref.data.ao[v];
    e.max_ao = std::max(e.max_ao, std::abs(da));
    const float* x = &b.data.bent_normals[3 * v];
    const float* y = &ref.data.bent_normals[3 * v];
    const double c = glm::dot(unit({x[0], x[1], x[2]}), unit({y[0], y[1], y[2]}));
    const double deg = std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / kPi;
    bent2 += deg * deg;
  }
  const auto n = static_cast<double>(vertices.size());
  e.rms = std::sqrt(sum2 / (n * static_cast<double>(K)));
  e.rel_k0 = std::sqrt(err0 / ref0);
  e.rel_occluded = std::sqrt(err0 / occ0);
  e.bias = sum0 / sum_occ0;
  e.rms_ao = std::sqrt(ao2 / n);
  e.bias_ao = ao_sum / ao_occ;
  e.rms_bent_deg = std::sqrt(bent2 / n);
  return e;
}

uint64_t total_samples(const BakeStatistics& st) {
  uint64_t n = 0;
  for (uint32_t s : st.vertex_samples) n += s;
  return n;
}

}  // namespace

TEST_CASE("cap-sampled bake: unbiased, and more accurate than hemisphere sampling") {
  // Measured (seeds 1..6 of the bakes against the one reference, capped vertices, N = 64):
  //                       caps              hemisphere
  //   relative RMS of T₀  0.14–0.16%        1.12–1.17%     (shadowed)
  //   against occlusion   3.8–4.4%          30–31%
  //   signed bias         −0.03…−0.20%      −1.5…+1.1%     (of the occluded part)
  //   RMS, all 9 coeffs   2.1–2.3e-4        1.62–1.70e-3   (ratio 0.13–0.14)
  //   AO: RMS / max       0.0014 / ≤ 0.016  0.011 / ≤ 0.048
  //   bent normal RMS     0.11–0.13°        0.95–0.99°
  // (interreflected: relative RMS of T₀ 0.08–0.10% (its T₀ is larger), the rest within 10%). The
  // reference's own error (≈ 0.09× the hemisphere bake's if i.i.d.) is a good part of the caps'
  // figures. Tolerances sit 1.4–2× above the worst seed; the bias bound (1%) catches a weight off
  // by 2% (the signed bias is the weight's relative error: a 5% error reads −5%).
  CapBakeFixture& f = cap_fixture();
  REQUIRE(f.capped.size() > 1000);  // most of the floor (1379 of 2313 vertices)
  for (prt::TransferKind kind : {prt::TransferKind::Shadowed, prt::TransferKind::Interreflected}) {
    CAPTURE(transfer_kind_name(kind));
    const BakeResult& ref = f.ref(kind);
    const BakeResult caps = bake_transfer(f.scene, fixed_adaptive(kind, 64, true));
    const BakeResult hemi = bake_transfer(f.scene, fixed_adaptive(kind, 64, false));
    // The baker capped exactly the vertices find_occluder_caps covers with caps.
    REQUIRE(caps.stats.cap_vertices == f.capped.size());
    REQUIRE(caps.stats.cap_open_vertices == f.open.size());
    REQUIRE(caps.stats.allocation_rounds == 0);
    REQUIRE(hemi.stats.cap_vertices == 0);
    for (uint32_t v : f.capped) REQUIRE(caps.stats.vertex_samples[v] == 64);

    const BakeErrors c = bake_errors(caps, ref, f.unshadowed, f.capped);
    const BakeErrors h = bake_errors(hemi, ref, f.unshadowed, f.capped);
    CAPTURE(c.rms, c.rel_k0, c.rel_occluded, c.bias, c.rms_ao, c.max_ao, c.bias_ao, c.rms_bent_deg);
    CAPTURE(h.rms, h.rel_k0, h.rel_occluded, h.bias, h.rms_ao, h.max_ao, h.bias_ao, h.rms_bent_deg);
    // (a) Small in absolute terms: T₀ to 0.25% (brief: ≤ 1%; measured ≤ 0.16%), and the
    // occluded part itself to 6% RMS (measured ≤ 4.4%).
    CHECK(c.rel_k0 < 0.0025);
    CHECK(c.rel_occluded < 0.06);
    // Unbiased: summed over 1379 vertices the random errors cancel to ≤ 0.2% of the occluded
    // part; a systematic error in the weights does not.
    CHECK(std::abs(c.bias) < 0.01);
    // (b) At least as accurate as hemisphere sampling at the same N over all coefficients:
    // required ≤ 1.1×; measured 0.13–0.14×, asserted ≤ 0.25×.
    CHECK(c.rms <= 1.1 * h.rms);
    CHECK(c.rms <= 0.25 * h.rms);
    // AO and bent normals (controls 1 and (2/3)·n): AO to 0.003 RMS / 0.03 max and unbiased to
    // 1% of the occlusion, bent normals to 0.25° RMS; all below the hemisphere bake's.
    CHECK(c.rms_ao < 0.003);
    CHECK(c.max_ao < 0.03);
    CHECK(std::abs(c.bias_ao) < 0.01);
    CHECK(c.rms_ao < h.rms_ao);
    CHECK(c.rms_bent_deg < 0.25);
    CHECK(c.rms_bent_deg < h.rms_bent_deg);
  }
}

TEST_CASE("cap-sampled bake: samples below the horizon cast no ray, fewer rays than hemisphere") {
  // Measured on this scene at N = 64: hemisphere 148032 rays (= 2313 × 64); caps 131630 rays
  // for 145472 samples (18.6% of the capped vertices' samples fall below their horizon; the
  // 40 open vertices are analytic), i.e. 0.889× the rays. With min_cap_samples = 16 (the
  // default) capped vertices take 16 samples (32 on audit vertices) and the bake casts 0.528×
  // the hemisphere bake's rays (seeds 1..4), while its capped vertices stay far more accurate
  // than hemisphere sampling at 64: RMS over all coefficients 0.36–0.37×, relative to the
  // occluded part 0.098–0.106 against 0.309.
  CapBakeFixture& f = cap_fixture();
  const auto kind = prt::TransferKind::Shadowed;
  const BakeResult caps = bake_transfer(f.scene, fixed_adaptive(kind, 64, true));
  const BakeResult hemi = bake_transfer(f.scene, fixed_adaptive(kind, 64, false));
  const uint64_t cap_samples = total_samples(caps.stats);
  const uint64_t hemi_samples = total_samples(hemi.stats);
  CAPTURE(caps.stats.rays, cap_samples, hemi.stats.rays, hemi_samples);
  // Hemisphere sampling casts one ray per sample, on every vertex.
  CHECK(hemi.stats.rays == hemi_samples);
  CHECK(hemi_samples == 64 * f.scene.vertex_count());
  // Caps: every vertex not open takes its 64 samples, but fewer rays are cast (measured 90%).
  CHECK(cap_samples == 64 * (f.scene.vertex_count() - f.open.size()));
  CHECK(caps.stats.rays < cap_samples);
  CHECK(static_cast<double>(caps.stats.rays) < 0.95 * static_cast<double>(cap_samples));
  CHECK(static_cast<double>(caps.stats.rays) < 0.92 * static_cast<double>(hemi.stats.rays));

  // The saving that matters: capped vertices at 16 samples.
  BakeOptions o = fixed_adaptive(kind, 64, true);
  o.adaptive.min_cap_samples = 16;
  const BakeResult few = bake_transfer(f.scene, o);
  const BakeErrors e_few = bake_errors(few, f.ref(kind), f.unshadowed, f.capped);
  const BakeErrors e_hemi = bake_errors(hemi, f.ref(kind), f.unshadowed, f.capped);
  CAPTURE(few.stats.rays, e_few.rel_occluded, e_hemi.rel_occluded);
  for (uint32_t v : f.capped) REQUIRE(few.stats.vertex_samples[v] <= 32);
  CHECK(static_cast<double>(few.stats.rays) < 0.6 * static_cast<double>(hemi.stats.rays));
  CHECK(e_few.rms < 0.5 * e_hemi.rms);
  CHECK(e_few.rel_occluded < 0.5 * e_hemi.rel_occluded);
}

TEST_CASE("cap-sampled bake: bit-identical for 1 and 2 threads, with allocation rounds") {
  // Interreflected (rows of H gathered in every round), AO and bent normals, default
  // min_cap_samples (16) and an error target that takes rounds of allocation: measured 5
  // rounds, capped vertices between 16 and 96 samples, others up to 448, 297135 rays.
  CapBakeFixture& f = cap_fixture();
  BakeOptions o;
  o.kind = prt::TransferKind::Interreflected;
  o.order = 3;
  o.ao = o.bent_normals = true;
  o.adaptive.enabled = true;
  o.adaptive.min_samples = 64;
  o.adaptive.max_samples = 512;
  o.adaptive.rms_error = 0.005;
  o.threads = 1;
  const BakeResult one = bake_transfer(f.scene, o);
  o.threads = 2;
  const BakeResult two = bake_transfer(f.scene, o);
  CAPTURE(one.stats.allocation_rounds, one.stats.rays, one.stats.cap_vertices);
  REQUIRE(one.stats.cap_vertices == f.capped.size());
  REQUIRE(one.stats.allocation_rounds > 0);
  CHECK(one.stats.allocation_budget_met);
  // The rounds gave some capped vertices more than their first samples (16, 32 on audit
  // vertices), not all: the allocation really chose between them.
  uint32_t min_capped = UINT32_MAX, max_capped = 0;
  for (uint32_t v : f.capped) {
    min_capped = std::min(min_capped, one.stats.vertex_samples[v]);
    max_capped = std::max(max_capped, one.stats.vertex_samples[v]);
  }
  CAPTURE(min_capped, max_capped);
  CHECK(max_capped > 32);
  CHECK(min_capped < max_capped);
  CHECK(one.stats.rays == two.stats.rays);
  CHECK(one.stats.vertex_samples == two.stats.vertex_samples);
  CHECK(one.data.coefficients == two.data.coefficients);
  CHECK(one.data.ao == two.data.ao);
  CHECK(one.data.bent_normals == two.data.bent_normals);
}

TEST_CASE("cap-sampled bake: a vertex whose caps all lie below its horizon is analytic") {
  // On this scene the finder covers 40 vertices with no cap at all (15 around the sphere's top,
  // the 25 of the box's top face: everything else lies below their tangent planes): the baker
  // must cast no ray for them and store the unshadowed transfer exactly, with AO 1 and the
  // normal as bent normal. A cap is dropped only when its ball (which holds its triangles) lies
  // below the horizon, so such a vertex is also provably open by bake/adaptive/scene_analysis.h (47
  // here; the finder leaves the other 7 uncovered): checked too.
  CapBakeFixture& f = cap_fixture();
  REQUIRE(!f.open.empty());
  const HemisphereAnalysis analysis =
      find_open_hemispheres(f.scene, compute_vertex_ray_starts(f.scene));
  for (uint32_t v : f.open) CHECK(analysis.open[v] == 1);
  for (prt::TransferKind kind : {prt::TransferKind::Shadowed, prt::TransferKind::Interreflected}) {
    CAPTURE(transfer_kind_name(kind));
    const BakeResult b = bake_transfer(f.scene, fixed_adaptive(kind, 64, true));
    CHECK(b.stats.cap_open_vertices == f.open.size());
    CHECK(b.stats.analytic_vertices == f.open.size());
    const std::size_t K = b.data.coefficients_per_channel();
    REQUIRE(b.data.channels == 1);
    for (uint32_t v : f.open) {
      CAPTURE(v);
      CHECK(b.stats.vertex_samples[v] == 0);
      for (std::size_t k = 0; k < K; ++k)
        CHECK(b.data.coefficients[v * K + k] == f.unshadowed.data.coefficients[v * K + k]);
      CHECK(b.data.ao[v] == 1.f);
      const glm::vec3 n = glm::normalize(f.scene.normals[v]);
      for (int a = 0; a < 3; ++a) CHECK(b.data.bent_normals[3 * v + a] == n[a]);
    }
  }
}
