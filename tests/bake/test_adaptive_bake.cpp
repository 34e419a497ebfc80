// Tests of `prt bake --auto` (bake/adaptive/adaptive_baker.h, bake/adaptive/scene_analysis.h,
// bake/adaptive/order_selection.h and the adaptive path of bake/transfer_baker.h).
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/adaptive/adaptive_baker.h"
#include "bake/adaptive/occlusion_bound.h"
#include "bake/adaptive/scene_analysis.h"
#include "bake/transfer_baker.h"
#include "report/ground_truth.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_map.h"
#include "sh/zonal.h"

using namespace prt::bake;
using namespace prt::scene;
using prt::report::compute_ground_truth;
using prt::report::GroundTruthOptions;
using prt::report::GroundTruthResult;

namespace {

using prt::sh::kPi;
using prt::sh::kSqrtFourPi;

// A ground quad (6 × 6, 24 × 24 cells) with a sphere of radius 0.7 resting on it.
Scene make_plane_with_sphere(glm::vec3 albedo) {
  Scene s =
      make_quad({-3.f, 0.f, 3.f}, {6.f, 0.f, 0.f}, {0.f, 0.f, -6.f}, 24, 24, albedo, "ground");
  append_scene(s, make_uv_sphere({0.f, 0.7f, 0.f}, 0.7f, 16, 32, false, albedo, "ball"));
  return s;
}

// Band-limited lighting (bands 0..5 only, stored at order 8): an ambient term plus a smooth lobe
// toward (0.4, 0.8, 0.45), tinted per channel. RGB, channel-major.
std::vector<double> make_band_limited_lighting(int order) {
  const int K = order * order;
  std::vector<double> zonal(order, 0.0), lobe(K), out(3 * K, 0.0);
  for (int l = 0; l < order && l < 6; ++l) zonal[l] = 1.5 * std::exp(-0.12 * l * (l + 1));
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.4, 0.8, 0.45));
  prt::sh::rotate_zonal(order, zonal.data(), d.x, d.y, d.z, lobe.data());
  const double tint[3] = {1.0, 0.8, 0.6};
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < K; ++k) out[c * K + k] = tint[c] * lobe[k];
    out[c * K] += 0.3 * kSqrtFourPi;
  }
  return out;
}

AutoBakeOptions quick_auto(double tolerance) {
  AutoBakeOptions o;
  o.tolerance = tolerance;
  o.pilot_vertices = 128;
  return o;
}

// Truncation error by order of a shadowed transfer under `lighting`, measured without the
// pilot, over every vertex: two independent bakes (seeds 101, 102) at order `order` with
// `samples` rays; e_A(n)·e_B(n) summed over vertices and channels estimates Σ e(n)² without the
// bakes' own noise (independent, unbiased halves), over Σ B_A·B_B for Σ B². Element n − 1 is
// the relative RMS truncation error at order n, for n = 1 .. order.
std::vector<double> measured_truncation(const Scene& scene, const std::vector<double>& lighting,
                                        int order, int samples) {
  const std::size_t V = scene.vertex_count();
  const int K = order * order;
  std::vector<std::vector<double>> halves;
  for (uint64_t seed : {101u, 102u}) {
    BakeOptions b;
    b.kind = prt::TransferKind::Shadowed;
    b.order = order;
    b.seed = seed;
    b.adaptive.enabled = true;
    b.adaptive.min_samples = b.adaptive.max_samples = samples;
    b.adaptive.cap_sampling = false;
    b.adaptive.compact_output = true;
    b.adaptive.vertex_mode.assign(V, kSkipVertex);
    std::fill(b.adaptive.vertex_mode.begin(), b.adaptive.vertex_mode.end(), kSampleVertex);
    const BakeResult r = bake_transfer(scene, b);
    REQUIRE(r.data.channels == 1);
    halves.emplace_back(r.data.coefficients.begin(), r.data.coefficients.end());
  }
  const std::size_t rows = halves[0].size() / K;
  std::vector<double> cross(order, 0.0);
  double total = 0.0;
  for (std::size_t i = 0; i < rows; ++i)
    for (int c = 0; c < 3; ++c) {
      double e[2][33] = {}, full[2] = {};
      for (int h = 0; h < 2; ++h) {
        // Suffix sums over bands: e[h][n] = Σ_{l ≥ n} Σ_m T_lm L_lm.
        for (int l = order - 1; l >= 0; --l) {
          double band = 0.0;
          for (int k = l * l; k < (l + 1) * (l + 1); ++k)
            band += halves[h][i * K + k] * lighting[c * K + k];
          e[h][l] = e[h][l + 1] + band;
        }
        full[h] = e[h][0];
      }
      total += full[0] * full[1];
      for (int n = 1; n <= order; ++n) cross[n - 1] += e[0][n] * e[1][n];
    }
  std::vector<double> out(order);
  for (int n = 1; n <= order; ++n) out[n - 1] = std::sqrt(std::max(0.0, cross[n - 1]) / total);
  return out;
}

}  // namespace

TEST_CASE("a convex mesh under --auto casts no rays and equals the unshadowed bake") {
  for (int shape = 0; shape < 2; ++shape) {
    const Scene scene =
        shape == 0 ? make_uv_sphere({0.3f, -0.2f, 1.f}, 2.f, 20, 40, false, glm::vec3(0.6f))
                   : make_box({-1.f, 0.f, -2.f}, {1.f, 0.5f, 2.f}, 6, false, glm::vec3(0.6f));
    CAPTURE(shape);
    AutoBakeOptions o = quick_auto(0.01);
    o.bake.order = 4;
    const AutoBakeResult a = bake_transfer_auto(scene, o);
    CHECK(a.bake.stats.rays == 0);
    CHECK(a.report.open_vertices == scene.vertex_count());
    CHECK(a.bake.data.kind == prt::TransferKind::Unshadowed);

    BakeOptions u;
    u.kind = prt::TransferKind::Unshadowed;
    u.order = 4;
    const BakeResult ref = bake_transfer(scene, u);
    REQUIRE(a.bake.data.channels == ref.data.channels);
    REQUIRE(a.bake.data.order == ref.data.order);
    // Bit-identical: the same analytic path, no Monte Carlo anywhere.
    CHECK(a.bake.data.coefficients == ref.data.coefficients);
    const auto meta = nlohmann::json::parse(a.bake.data.metadata_json);
    CHECK(meta.at("auto").at("open_vertices").get<std::size_t>() == scene.vertex_count());
    CHECK(meta.at("transfer").get<std::string>() == "unshadowed");
  }
}

// --auto honours the caller's memory limit as a fixed bake does: the coefficients (V × order² ×
// 4 bytes, about 30 KB here) are charged before they are allocated, so a 1 KB limit stops the
// bake with MemoryBudgetExceeded, and a generous one changes nothing.
TEST_CASE("bake_transfer_auto charges its bake to BakeOptions::memory_limit") {
  const Scene scene = make_uv_sphere({0.f, 0.f, 0.f}, 1.f, 20, 40, false, glm::vec3(0.6f));
  AutoBakeOptions o = quick_auto(0.01);
  o.bake.order = 4;
  o.bake.memory_limit = 1024;
  CHECK_THROWS_WITH(bake_transfer_auto(scene, o), Catch::Contains("the memory limit is 1.0 KB"));
  o.bake.memory_limit = uint64_t(1) << 30;
  CHECK(bake_transfer_auto(scene, o).bake.data.order == 4);
}

TEST_CASE("grey albedo gives one channel and coloured albedo gives three") {
  const Scene grey = make_plane_with_sphere(glm::vec3(0.5f));
  const glm::vec3 rgb(0.2f, 0.5f, 0.8f);
  const Scene coloured = make_plane_with_sphere(rgb);
  AutoBakeOptions o = quick_auto(0.02);
  o.bake.kind =
      prt::TransferKind::Shadowed;  // T_c = ρ_c·S exactly, so the channels can be compared
  const AutoBakeResult g = bake_transfer_auto(grey, o);
  const AutoBakeResult c = bake_transfer_auto(coloured, o);
  REQUIRE(g.bake.data.channels == 1);
  REQUIRE(c.bake.data.channels == 3);
  CHECK(g.bake.stats.rays > 0);
  // Same sample decisions (they do not depend on albedo), so channel c = (ρ_c / 0.5)·grey up
  // to float rounding of the two products (relative 1e-6, plus 1e-9 absolute near zero).
  const std::size_t K = g.bake.data.coefficients_per_channel();
  for (std::size_t v = 0; v < grey.vertex_count(); v += 7)
    for (int ch = 0; ch < 3; ++ch)
      for (std::size_t k = 0; k < K; ++k) {
        const double expect = g.bake.data.coefficients[v * K + k] * (rgb[ch] / 0.5);
        const double got = c.bake.data.coefficients[(v * 3 + ch) * K + k];
        REQUIRE(got == Approx(expect).epsilon(1e-6).margin(1e-9));
      }
}

TEST_CASE(
    "the chosen order meets the tolerance against a converged reference and the ground truth") {
  const Scene scene = make_plane_with_sphere(glm::vec3(0.6f));
  const int lighting_order = 8;
  const std::vector<double> lighting = make_band_limited_lighting(lighting_order);
  const double tolerance = 0.02;
  AutoBakeOptions o = quick_auto(tolerance);
  o.lighting = lighting;
  o.lighting_order = lighting_order;
  const AutoBakeResult a = bake_transfer_auto(scene, o);
  REQUIRE(a.report.order_chosen);
  CHECK(a.report.order_choice.met);
  CHECK_FALSE(a.report.order_choice.haar_recommended);
  CHECK(a.report.order <= 6);  // the lighting has no energy in bands ≥ 6
  CHECK(a.report.predicted_error <= tolerance);
  CHECK(a.bake.data.kind == prt::TransferKind::Interreflected);

  // Reference: the fixed recipe at order 8 (beyond the lighting's bands), 4096 samples, solved
  // to 1e-6. Its own Monte Carlo error is ~tolerance/10, so it can judge a 2% tolerance.
  BakeOptions r;
  r.kind = prt::TransferKind::Interreflected;
  r.order = lighting_order;
  r.samples = 4096;
  r.bounce_tolerance = 1e-6;
  const BakeResult ref = bake_transfer(scene, r);
  const std::vector<double> b_ref = exit_radiance(ref.data, lighting, lighting_order);
  const double measured =
      relative_rms_error(exit_radiance(a.bake.data, lighting, lighting_order), b_ref);
  // The truncation part alone, measured: the reference cut at the chosen order.
  prt::TransferData cut = ref.data;
  const int n = a.report.order, K8 = lighting_order * lighting_order;
  cut.order = static_cast<uint32_t>(n);
  cut.coefficients.clear();
  for (std::size_t v = 0; v < scene.vertex_count(); ++v)
    for (int k = 0; k < n * n; ++k) cut.coefficients.push_back(ref.data.coefficients[v * K8 + k]);
  const double truncation = relative_rms_error(exit_radiance(cut, lighting, lighting_order), b_ref);
  INFO("order " << n << ": predicted " << a.report.predicted_error << " (truncation "
                << a.report.predicted_truncation_error << ", sampling "
                << a.report.predicted_sampling_error << "); measured " << measured
                << " (truncation " << truncation << "); rays " << a.bake.stats.rays << " vs "
                << ref.stats.rays);
  CHECK(measured <= tolerance);
  // Honest prediction: the measured truncation stays within the predicted truncation budget
  // (tolerance/2), and the measured total within the predicted total plus the reference's
  // own noise (~0.002 at 4096 samples).
  CHECK(truncation <= 0.5 * tolerance);
  CHECK(measured <= a.report.predicted_error + 0.002);

  // The ground truth (report/ground_truth.h: path tracing against the lighting as a 128×64
  // lat-long map, no SH anywhere) on every 3rd vertex at 1% relative standard error; its own
  // noise is removed from the squared error (E[(b − g)²] = (b − t)² + Var g). Measured: 1.44%
  // against 1.06% from the converged reference; the difference is what no PRT bake sees: the
  // map's piecewise-constant texels and the mesh's interpolation of interreflected light at the
  // ball's contact (docs/adaptive/README.md). Both stay inside the 2% tolerance.
  prt::sh::EnvMap env;
  env.width = 128, env.height = 64;
  env.rgb.resize(3 * env.width * env.height);
  std::vector<double> y(K8);
  for (int row = 0; row < env.height; ++row)
    for (int col = 0; col < env.width; ++col) {
      double d[3];
      REQUIRE(prt::sh::texel_direction(env.layout, env.width, env.height, col, row, d));
      prt::sh::evaluate(lighting_order, d[0], d[1], d[2], y.data());
      for (int c = 0; c < 3; ++c) {
        double L = 0.0;
        for (int k = 0; k < K8; ++k) L += lighting[c * K8 + k] * y[k];
        env.rgb[3 * (row * env.width + col) + c] = static_cast<float>(L);
      }
    }
  GroundTruthOptions g;
  g.target_relative_se = 0.01;
  g.max_samples = 1 << 14;
  for (uint32_t v = 0; v < scene.vertex_count(); v += 3) g.vertices.push_back(v);
  const GroundTruthResult gt = compute_ground_truth(scene, env, g);
  REQUIRE(gt.reached_target);
  const std::vector<double> b_auto = exit_radiance(a.bake.data, lighting, lighting_order);
  double num = 0, se2 = 0, den = 0;
  for (uint32_t v : g.vertices)
    for (int c = 0; c < 3; ++c) {
      const double d = b_auto[3 * v + c] - gt.radiance[3 * v + c];
      num += d * d;
      se2 += gt.standard_error[3 * v + c] * gt.standard_error[3 * v + c];
      den += gt.radiance[3 * v + c] * gt.radiance[3 * v + c];
    }
  const double against_truth = std::sqrt(std::max(0.0, num - se2) / den);
  INFO("against the ground truth (" << g.vertices.size() << " vertices, s = " << gt.relative_rms_se
                                    << "): " << against_truth);
  CHECK(against_truth <= tolerance);
}

// A sun puts energy in every band. The pilot's prediction must follow the truncation error
// measured over the whole scene (measured_truncation: 2 × 2048 rays per vertex at order 32, its
// own noise removed), where a 256-sample pilot's noise used to dominate it (4× too high on
// data/demo.glb under data/sky.hdr) and evenly spaced pilot vertices aliased with the grid and
// the sphere's rings (0.57× the measured error at order 10 here). Bounds: 0.8–1.5× the
// measurement for orders 3–12 (measured 0.90–0.97×: an unbiased estimate from 128 vertices, plus
// the pilot's remaining noise, which only adds). At tolerance 0.005 no order ≤ 12 meets it
// (measured 0.0098 at order 12) and Haar is recommended; at 0.03 an order does, and it meets the
// truncation budget (tolerance/2) as measured, within the 10% by which 128 pilot vertices can
// misjudge a scene's RMS. (Not necessarily the smallest such order: the first pilot that meets
// the target ends the search, and its noise only raises the prediction.)
TEST_CASE("under a sun the predicted truncation follows the measured one, and picks the basis") {
  const Scene scene = make_plane_with_sphere(glm::vec3(0.6f));
  const int order = 32;
  std::vector<double> zonal(order, 1.0), lobe(order * order), lighting(3 * order * order);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, 0.9, 0.2));
  prt::sh::rotate_zonal(order, zonal.data(), d.x, d.y, d.z,
                        lobe.data());  // a delta, cut at band 31
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < order * order; ++k) lighting[c * order * order + k] = lobe[k];
  const std::vector<double> measured = measured_truncation(scene, lighting, order, 2048);
  AutoBakeOptions o = quick_auto(0.005);
  o.bake.kind = prt::TransferKind::Shadowed;
  o.lighting = lighting;
  o.lighting_order = order;
  const AutoBakeResult a = bake_transfer_auto(scene, o);
  CHECK(a.report.pilot_samples == o.max_pilot_samples);  // 256, 1024, 4096: none met it
  for (int n = 3; n <= o.max_order; ++n) {
    CAPTURE(n, measured[n - 1]);
    CHECK(a.report.order_choice.predicted_by_order[n - 1] >= 0.8 * measured[n - 1]);
    CHECK(a.report.order_choice.predicted_by_order[n - 1] <= 1.5 * measured[n - 1]);
  }
  CHECK(a.report.order_choice.haar_recommended);
  CHECK(a.report.order == o.max_order);
  CHECK(a.report.predicted_error > o.tolerance);

  o.tolerance = 0.03;
  const AutoBakeResult loose = bake_transfer_auto(scene, o);
  CHECK_FALSE(loose.report.order_choice.haar_recommended);
  CHECK(loose.report.order < o.max_order);
  CHECK(measured[loose.report.order - 1] <= 1.1 * 0.5 * o.tolerance);

  // When no order keeps its truncation within 80% of the tolerance, order 12 is baked and Haar
  // is recommended exactly when that bake's predicted total misses the tolerance (truncation
  // 0.0089 here: at 0.0095 the capped sampling leaves 0.0104, at 0.0105 it gets to 0.0093).
  int recommended = 0, not_recommended = 0;
  for (double t : {0.0095, 0.0105}) {
    o.tolerance = t;
    const AutoBakeResult b = bake_transfer_auto(scene, o);
    CAPTURE(t, b.report.predicted_error, b.report.predicted_truncation_error);
    REQUIRE_FALSE(b.report.order_choice.met);
    CHECK(b.report.order == o.max_order);
    CHECK(b.report.order_choice.haar_recommended == (b.report.predicted_error > t));
    const bool says_meets = std::any_of(
        b.report.left_out.begin(), b.report.left_out.end(),
        [](const std::string& l) { return l.find("the predicted total") != std::string::npos; });
    CHECK(says_meets == !b.report.order_choice.haar_recommended);
    (b.report.order_choice.haar_recommended ? recommended : not_recommended) += 1;
  }
  CHECK(recommended == 1);
  CHECK(not_recommended == 1);
}

TEST_CASE("adding an occluder turns shadow rays on for exactly the affected vertices") {
  Scene scene = make_uv_sphere({0.f, 0.f, 0.f}, 1.f, 18, 36, false, glm::vec3(0.5f));
  const std::size_t sphere_vertices = scene.vertex_count();
  AutoBakeOptions o = quick_auto(0.02);
  o.bake.kind = prt::TransferKind::Shadowed;
  REQUIRE(bake_transfer_auto(scene, o).bake.stats.rays == 0);

  append_scene(scene, make_box({1.3f, 0.2f, -0.3f}, {1.8f, 0.9f, 0.4f}, 2, false, glm::vec3(0.5f),
                               "occluder"));
  // Exactly: without the bounded skip (which may leave barely-affected vertices ray-free; tested
  // below), rays are on iff the vertex is affected.
  o.bounded_skip_share = 0.0;
  const AutoBakeResult a = bake_transfer_auto(scene, o);
  // Independently: a vertex must cast rays iff some scene vertex lies strictly above its
  // tangent plane (brute force, in double). Heights within 1e-3 of the plane would make the
  // comparison depend on the analysis' threshold τ (4e-5 × extent); the scene has none there
  // except the sphere's own neighbours (height ≤ 0) and coplanar box faces (height 0).
  std::size_t affected_sphere = 0, ambiguous = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    const glm::dvec3 p(scene.positions[v]), n(scene.normals[v]);
    double top = -1e30;
    for (const glm::vec3& q : scene.positions) top = std::max(top, glm::dot(glm::dvec3(q) - p, n));
    if (top > 0.0 && top < 1e-3) ++ambiguous;
    const bool affected = top >= 1e-3;
    CAPTURE(v, top);
    REQUIRE(affected == (a.bake.stats.vertex_samples[v] > 0));
    if (affected && v < sphere_vertices) ++affected_sphere;
  }
  CHECK(ambiguous == 0);
  // Non-trivial: the occluder affects some of the sphere, not all of it.
  CHECK(affected_sphere > 0);
  CHECK(affected_sphere < sphere_vertices / 2);
  CHECK(a.report.open_vertices == scene.vertex_count() - [&] {
    std::size_t n = 0;
    for (uint32_t s : a.bake.stats.vertex_samples) n += s > 0;
    return n;
  }());
}

TEST_CASE("the bounded skip: only affected vertices cast rays, and skipped ones stay in budget") {
  // A floor with a ball: far floor vertices see the ball as a speck near their horizon.
  Scene scene = make_quad({-8.f, 0.f, 8.f}, {16.f, 0.f, 0.f}, {0.f, 0.f, -16.f}, 32, 32,
                          glm::vec3(0.5f), "ground");
  append_scene(scene, make_uv_sphere({0.f, 0.7f, 0.f}, 0.7f, 12, 24, false, glm::vec3(0.5f)));
  AutoBakeOptions o = quick_auto(0.02);
  o.bake.kind = prt::TransferKind::Shadowed;
  const AutoBakeResult a = bake_transfer_auto(scene, o);
  const HemisphereAnalysis open = find_open_hemispheres(scene, compute_vertex_ray_starts(scene));
  const OcclusionBounds bounds =
      bound_occlusion(scene, compute_vertex_ray_starts(scene), 1e30, open.open);
  // Ray-free occluded fraction measured independently: 1 − AO of a fixed bake (cosine-weighted
  // AO is exactly 1 − G), 2048 scrambled Sobol' samples (error ≪ 2e-3 here).
  BakeOptions f;
  f.kind = prt::TransferKind::Shadowed;
  f.samples = 2048;
  f.ao = true;
  const BakeResult fixed = bake_transfer(scene, f);
  std::size_t skipped = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    const bool rays = a.bake.stats.vertex_samples[v] > 0;
    CAPTURE(v, bounds.bound[v]);
    if (open.open[v]) REQUIRE_FALSE(rays);
    if (rays || open.open[v]) continue;
    ++skipped;
    // A skipped vertex is one the bound covered (≤ cutoff), and the bound held.
    CHECK(bounds.bound[v] <= o.bounded_skip_cutoff);
    CHECK(1.0 - fixed.data.ao[v] <= bounds.bound[v] + 2e-3);
  }
  CHECK(skipped == a.report.bounded_skip_vertices);
  CHECK(skipped > 0);
  CHECK(a.report.predicted_skip_error > 0.0);
  CHECK(a.report.predicted_skip_error <= o.bounded_skip_share * o.tolerance);
  // The skipped vertices' actual error, against a converged bake, is within what was charged.
  const std::vector<double> light = make_band_limited_lighting(8);
  const std::vector<double> b_auto = exit_radiance(a.bake.data, light, 8);
  BakeOptions ref = f;
  ref.order = a.bake.data.order;
  const std::vector<double> b_ref = exit_radiance(bake_transfer(scene, ref).data, light, 8);
  double err2 = 0, den2 = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v)
    for (int c = 0; c < 3; ++c) {
      den2 += b_ref[3 * v + c] * b_ref[3 * v + c];
      if (a.bake.stats.vertex_samples[v] == 0 && !open.open[v])
        err2 += (b_auto[3 * v + c] - b_ref[3 * v + c]) * (b_auto[3 * v + c] - b_ref[3 * v + c]);
    }
  // The report's bound was made for a uniform sky (no --env); the ratio of the bound to the
  // error is what matters: the actual bias must not exceed it.
  CHECK(std::sqrt(err2 / den2) <= a.report.predicted_skip_error);
}

TEST_CASE("the open-hemisphere hierarchy agrees with the brute-force test") {
  const Scene scene = make_plane_with_sphere(glm::vec3(0.5f));
  const VertexRayStarts starts = compute_vertex_ray_starts(scene);
  const HemisphereAnalysis h = find_open_hemispheres(scene, starts);
  std::size_t open = 0;
  for (std::size_t v = 0; v < scene.vertex_count(); ++v) {
    REQUIRE(static_cast<bool>(h.open[v]) ==
            is_hemisphere_open_brute_force(scene, v, starts.unreachable_height[v]));
    open += h.open[v];
  }
  CHECK(open == h.open_count);
  CHECK(open > 0);                         // the top of the ball
  CHECK(open < scene.vertex_count() / 2);  // the ground sees the ball
}

TEST_CASE("samples adapt per vertex: few in the open, more near the contact, any thread count") {
  const Scene scene = make_plane_with_sphere(glm::vec3(0.5f));
  AutoBakeOptions o = quick_auto(0.01);
  o.bake.kind = prt::TransferKind::Shadowed;
  o.bake.threads = 1;
  const AutoBakeResult one = bake_transfer_auto(scene, o);
  o.bake.threads = 2;
  const AutoBakeResult two = bake_transfer_auto(scene, o);
  CHECK(one.bake.data.coefficients == two.bake.data.coefficients);
  CHECK(one.bake.stats.vertex_samples == two.bake.stats.vertex_samples);
  // Ground vertex 0 is the corner (−3, 0, 3): the ball covers a small solid angle there.
  // The ground vertex under the ball's edge, (0.75, 0, 0) → grid (i, j) = (15, 12) roughly,
  // sits in the crevice.
  const auto& n = one.bake.stats.vertex_samples;
  const std::size_t crevice = 12 * 25 + 15;
  CHECK(n[0] < n[crevice]);
  CHECK(n[crevice] > 64);
}

// With equal counts everywhere nothing was left out of the sample count, and the report must
// not claim an allocation: it says whether the counts met the tolerance or hit the cap.
TEST_CASE("equal sample counts are reported as such: met at the minimum, or short at the cap") {
  const Scene scene = make_plane_with_sphere(glm::vec3(0.5f));
  const auto line_with = [](const AutoBakeResult& a, const std::string& text) {
    for (const std::string& line : a.report.left_out)
      if (line.find(text) != std::string::npos) return true;
    return false;
  };
  AutoBakeOptions o = quick_auto(0.2);  // loose: 64 samples everywhere meet it
  o.bake.kind = prt::TransferKind::Shadowed;
  o.cap_sampling = false;  // capped vertices would start at fewer samples
  o.bounded_skip_share = 0.0;
  const AutoBakeResult met = bake_transfer_auto(scene, o);
  CHECK(met.bake.stats.allocation_budget_met);
  CHECK(line_with(met, "every sampled vertex took 64 samples, which meet"));
  CHECK_FALSE(line_with(met, "allocated to where the measured error is"));
  o.tolerance = 0.0005;  // tight: the cap of 64 is not enough
  o.max_samples = 64;
  const AutoBakeResult capped = bake_transfer_auto(scene, o);
  CHECK_FALSE(capped.bake.stats.allocation_budget_met);
  CHECK(line_with(capped, "every sampled vertex took the cap of 64 samples, short of"));
  o.tolerance = 0.01;  // room to allocate: the counts differ and the report says so
  o.max_samples = 1024;
  const AutoBakeResult adapted = bake_transfer_auto(scene, o);
  CHECK(line_with(adapted, "allocated to where the measured error is"));
}

// Scale: the analysis' thresholds, the caps and the ray offsets are relative to the scene's
// extent, so a scene in millimetres or in kilometres gets the same decisions as in metres, and
// the same sample counts. The transfer is dimensionless, so the exit radiance agrees too, within
// the float rounding of the scaled positions (measured 9e-9 relative RMS; bound 1e-6). A
// threshold in absolute units would instead change whole classes of vertices and move the
// result by the tolerance's order (1e-2).
TEST_CASE("a scene at any scale gets the same --auto decisions") {
  const Scene base = make_plane_with_sphere(glm::vec3(0.5f));
  AutoBakeOptions o = quick_auto(0.01);
  o.lighting_order = 8;
  o.lighting = make_band_limited_lighting(8);
  const AutoBakeResult ref = bake_transfer_auto(base, o);
  REQUIRE(ref.report.open_vertices > 0);
  REQUIRE(ref.bake.stats.cap_vertices > 0);
  for (const float scale : {1e-3f, 1e4f}) {
    Scene scene = base;
    for (glm::vec3& p : scene.positions) p *= scale;
    const AutoBakeResult a = bake_transfer_auto(scene, o);
    CAPTURE(scale);
    CHECK(a.report.order == ref.report.order);
    CHECK(a.report.open_vertices == ref.report.open_vertices);
    CHECK(a.report.bounded_skip_vertices == ref.report.bounded_skip_vertices);
    CHECK(a.bake.stats.cap_vertices == ref.bake.stats.cap_vertices);
    CHECK(a.report.mean_samples == ref.report.mean_samples);
    CHECK(relative_rms_error(exit_radiance(a.bake.data, o.lighting, 8),
                             exit_radiance(ref.bake.data, o.lighting, 8)) < 1e-6);
  }
}

TEST_CASE("interreflection is skipped when no surface sees another or the albedo is zero") {
  // Zero albedo: nothing is reflected, so no solve (and the stored kind says so).
  Scene black = make_plane_with_sphere(glm::vec3(0.f));
  const AutoBakeResult z = bake_transfer_auto(black, quick_auto(0.02));
  CHECK(z.bake.data.kind == prt::TransferKind::Shadowed);
  CHECK_FALSE(z.bake.stats.interreflection_solved);

  const AutoBakeResult lit =
      bake_transfer_auto(make_plane_with_sphere(glm::vec3(0.5f)), quick_auto(0.02));
  CHECK(lit.bake.stats.interreflection_solved);
  CHECK(lit.bake.data.kind == prt::TransferKind::Interreflected);
  // Bounces stopped by the rule: the last one added < tolerance/4 of max|D|.
  REQUIRE_FALSE(lit.bake.stats.bounce_energy.empty());
  CHECK(lit.bake.stats.jacobi_bounces < 20);
}

TEST_CASE("compact output holds exactly the rows of the bake's non-skipped vertices") {
  // The --auto pilot bakes a few hundred vertices of a possibly huge scene at order 16; with
  // compact output it allocates rows for those only. The rows must be the full bake's, bit for
  // bit, in vertex order.
  const Scene scene = make_plane_with_sphere(glm::vec3(0.5f));
  const std::size_t V = scene.vertex_count();
  BakeOptions b;
  b.kind = prt::TransferKind::Shadowed;
  b.order = 6;
  b.adaptive.enabled = true;
  b.adaptive.min_samples = b.adaptive.max_samples = 64;
  b.adaptive.vertex_mode.assign(V, kSkipVertex);
  std::vector<std::size_t> picked;
  for (std::size_t v = 3; v < V; v += 37) {
    b.adaptive.vertex_mode[v] = v % 2 ? kSampleVertex : kAnalyticVertex;
    picked.push_back(v);
  }
  const BakeResult full = bake_transfer(scene, b);
  b.adaptive.compact_output = true;
  const BakeResult compact = bake_transfer(scene, b);
  const std::size_t K = 36;
  REQUIRE(full.data.channels == 1);
  REQUIRE(full.data.coefficients.size() == V * K);
  REQUIRE(compact.data.coefficients.size() == picked.size() * K);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < picked.size(); ++i)
    for (std::size_t k = 0; k < K; ++k)
      mismatches +=
          compact.data.coefficients[i * K + k] != full.data.coefficients[picked[i] * K + k];
  CHECK(mismatches == 0);
  // Interreflected bakes keep the full layout (the solve needs every vertex): refused.
  b.kind = prt::TransferKind::Interreflected;
  CHECK_THROWS_AS(bake_transfer(scene, b), BakeError);
}

// The tail of bands ≥ the pilot order (bake/adaptive/order_selection.h) against its closed form: a
// vertex's unshadowed transfer is the clamped cosine about its normal n, S_lm = z_l·√(4π/(2l+1))
// ·Y_lm(n), and under a delta lobe L_lm = √(4π/(2l+1))·Y_lm(d) (cut at band 31) the bands ≥ 16
// add ρ Σ_{l=16..31} z_l P_l(n·d) to its exit radiance (addition theorem), evaluated here from
// the same coefficients. The stand-in must bound that error with the exact pilot (what an open
// pilot vertex gets: its odd bands l ≥ 3 are zero, so the former stand-in, the last band alone,
// gave no tail at all) and with a Monte Carlo pilot (256 cosine-weighted samples).
TEST_CASE("the tail bound beyond the pilot order bounds a sun's error, exact or noisy pilot") {
  const int np = 16, nl = 32, kp = np * np, kl = nl * nl;
  std::vector<double> zonal(nl), ones(nl, 1.0), light(kl), lighting(3 * kl);
  for (int l = 0; l < nl; ++l) zonal[l] = prt::sh::clamped_cosine_zonal_coefficient(l);
  const glm::dvec3 d = glm::normalize(glm::dvec3(0.3, 0.9, 0.2));
  prt::sh::rotate_zonal(nl, ones.data(), d.x, d.y, d.z, light.data());
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < kl; ++k) lighting[c * kl + k] = light[k];
  const int P = 64;
  std::vector<double> exact(P * kp), noisy(P * kp);
  std::vector<glm::vec3> albedo(P, glm::vec3(0.6f));
  double tail2 = 0.0, total2 = 0.0;
  uint32_t state = 12345u;
  auto uniform = [&] {
    state = state * 1664525u + 1013904223u;
    return (static_cast<double>(state >> 8) + 0.5) / 16777216.0;
  };
  std::vector<double> s_full(kl), y(kp);
  for (int v = 0; v < P; ++v) {
    const double t = (v + 0.5) / P, phi = 2.399963 * v;  // a spiral of normals
    const glm::dvec3 n(std::sqrt(1 - t * t) * std::cos(phi), t,
                       std::sqrt(1 - t * t) * std::sin(phi));
    prt::sh::rotate_zonal(nl, zonal.data(), n.x, n.y, n.z, s_full.data());
    double tail = 0.0, full = 0.0;
    for (int k = 0; k < kl; ++k) (k < kp ? full : tail) += 0.6 * s_full[k] * light[k];
    tail2 += 3.0 * tail * tail;
    total2 += 3.0 * full * full;
    for (int k = 0; k < kp; ++k) exact[v * kp + k] = s_full[k];
    // Monte Carlo: S ≈ (π/N) Σ Y(ω_i), ω_i cosine-distributed about n.
    const glm::dvec3 a = std::abs(n.x) < 0.9 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
    const glm::dvec3 tx = glm::normalize(glm::cross(a, n)), ty = glm::cross(n, tx);
    const int N = 256;
    for (int i = 0; i < N; ++i) {
      const double r = std::sqrt(uniform()), ph = 2.0 * kPi * uniform();
      const glm::dvec3 w =
          r * std::cos(ph) * tx + r * std::sin(ph) * ty + std::sqrt(std::max(0.0, 1.0 - r * r)) * n;
      prt::sh::evaluate(np, w.x, w.y, w.z, y.data());
      for (int k = 0; k < kp; ++k) noisy[v * kp + k] += kPi / N * y[k];
    }
  }
  const double true_tail = std::sqrt(tail2 / total2);
  const OrderChoice e = choose_order(exact, albedo, np, lighting, nl, 0.01, 12);
  const OrderChoice m = choose_order(noisy, albedo, np, lighting, nl, 0.01, 12);
  INFO("tail beyond band 15: true " << true_tail << ", stand-in exact pilot " << e.tail_bound
                                    << ", noisy pilot " << m.tail_bound);
  CHECK(e.tail_bound >= true_tail);
  CHECK(m.tail_bound >= true_tail);
}
