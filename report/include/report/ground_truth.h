// report/ground_truth.h — an independent reference for per-vertex exit radiance: Monte Carlo
// integration against the actual environment map (not its SH projection), with visibility and
// diffuse interreflection by path tracing. It shares no code with the SH or wavelet paths; the
// report (report/report.h) measures every PRT setting against it.
//
// Frame: glTF's (+Y up); map layouts and texel solid angles of sh/env_map.h; radiance in the
// map's units. The map is taken as piecewise constant over texels (nearest texel, no filtering).
// Surfaces are Lambertian with albedo ρ: the receiving vertex's own (Scene::albedo), and at hit
// points Scene::albedo_at (interpolated vertex albedo, or the texture read bilinearly), and,
// as in the baker (bake/transfer_baker.h), back faces occlude but reflect nothing; the front side
// is the one the vertex normals point to.
//
// Estimator for B_p = (ρ_p/π) ∫_H L_in(ω) cos θ dω, per path vertex (Veach & Guibas, "Optimally
// Combining Sampling Techniques for Monte Carlo Rendering", SIGGRAPH 1995; Veach's thesis §9):
//   * light sample: a texel t drawn with probability P_t ∝ luminance_t · Ω_t (Rec. 709 luminance
//     of the texel, Ω_t its exact solid angle), then a point uniform in the texel's image square,
//     mapped to a direction; its pdf in solid angle is P_t / J(x, y), J = dω/d(image area) of the
//     layout at that point (lat-long sin θ·2π²/(WH); angular π² sinc(πr)·(2/W)²; cube faces
//     (2/s)²/(1 + a² + b²)^{3/2});
//   * cosine sample: pdf cos θ/π (bake/sampling.h's Malley mapping);
//   * both weighted by the balance heuristic (one sample of each), the light sample tested with a
//     shadow ray, the cosine sample traced with a closest-hit ray: an escape adds the map's
//     radiance, a front-face hit continues the path (throughput × ρ_hit), a back face ends it.
// Path length: Russian roulette from the third path vertex on (survival = max channel of ρ_hit,
// clamped to [0.05, 0.99]; the throughput is divided by it), hard cap `max_bounces` reflections
// after the vertex (0 = direct lighting only). The cap's truncation is the only bias: at most
// ρ_max^(cap+1)/(1 − ρ_max) of B relative (ρ_max^65 ≈ 5e-7 for ρ_max = 0.8 and the default 64).
//
// Standard error: every sample is an independent estimate of B_p (RGB); SE_p,c = the sample
// standard deviation / √N. The summary statistic is the relative RMS standard error
//     s = √(Σ_p Σ_c SE_p,c²) / √(Σ_p Σ_c B_p,c²),
// the same RGB-norm RMS that report/report.h uses for errors. refine() doubles the samples per
// vertex until s ≤ target (or a sample cap), and says what it reached.
// Determinism: the random numbers of sample s of vertex v come from hash(seed, v, s) only, so the
// result is bit-identical for any thread count and any doubling schedule.
// Errors: bad inputs throw BakeError ("PATH: problem"), Embree errors std::runtime_error.
// References: [13] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::scene {
class RayCaster;
}  // namespace prt::scene

namespace prt::bake {
class ProgressSink;
}  // namespace prt::bake

namespace prt::report {

using bake::ProgressSink;

struct GroundTruthOptions {
  int max_bounces = 64;              // reflections after the vertex (0: direct lighting only)
  int initial_samples = 64;          // samples per vertex of the first pass
  int max_samples = 1 << 16;         // refine() stops doubling here
  double target_relative_se = 0.01;  // refine() target for s (see header)
  uint64_t seed = 1;
  int threads = 0;  // 0 = all hardware threads
  // Only these vertices are integrated (empty: all). The others keep radiance and standard
  // error 0, so s covers the subset; a spot check of a large scene costs what the subset costs.
  std::vector<uint32_t> vertices;
};

struct GroundTruthResult {
  std::vector<double> radiance;        // 3 per vertex: B_p (RGB)
  std::vector<double> standard_error;  // 3 per vertex: SE of B_p per channel
  int samples_per_vertex = 0;
  double relative_rms_se = 0;  // s of the header
  double target_relative_se = 0;
  bool reached_target = false;
  uint64_t rays = 0;            // total rays cast so far (shadow + closest-hit)
  double seconds = 0;           // wall time of all passes so far
  uint64_t skipped_texels = 0;  // NaN, Inf or negative texels (treated as black)

  double mrays_per_second() const {
    return seconds > 0 ? static_cast<double>(rays) / seconds * 1e-6 : 0.0;
  }
};

// A direction inside an environment map's image: image point (x, y) (continuous coordinates,
// texel (c, r) covering [c, c+1) × [r, r+1)) → unit direction and J = dω/d(image area).
// Returns false for points not on the sphere (outside the angular disc, empty cross cells).
bool image_point_direction(sh::EnvLayout layout, int width, int height, double x, double y,
                           double dir[3], double* jacobian) noexcept;

// Importance sampling of an environment map by luminance × solid angle (see header).
class EnvironmentSampler {
 public:
  // Throws BakeError when the map is empty or its size does not fit its layout.
  explicit EnvironmentSampler(const sh::EnvMap& env);

  // Picks a direction from two uniforms in [0, 1) (texel by u0, point in texel by u1, u2).
  // False when the map is black (nothing to sample) or the point falls off the sphere.
  bool sample(double u0, double u1, double u2, double dir[3], double rgb[3], double* pdf) const;
  // Radiance of the texel containing direction dir (unit) and the light pdf there.
  void evaluate(const double dir[3], double rgb[3], double* pdf) const;

  bool black() const { return total_weight_ <= 0; }
  uint64_t skipped_texels() const { return skipped_; }

 private:
  const sh::EnvMap* env_;
  std::vector<double> cdf_;  // inclusive prefix sums of the texel weights
  double total_weight_ = 0;
  uint64_t skipped_ = 0;
};

class GroundTruthIntegrator {
 public:
  // The scene and map must outlive the integrator. Throws BakeError for an empty scene, albedo
  // outside [0, 1), a bad map or options.
  GroundTruthIntegrator(const scene::Scene& scene, const sh::EnvMap& env,
                        const GroundTruthOptions& options);
  ~GroundTruthIntegrator();
  GroundTruthIntegrator(const GroundTruthIntegrator&) = delete;
  GroundTruthIntegrator& operator=(const GroundTruthIntegrator&) = delete;

  // Adds samples until every vertex has `total_samples` (no-op when it has that many already).
  void add_samples_up_to(int total_samples, ProgressSink* progress = nullptr);
  // Doubles the samples per vertex (from initial_samples) until s ≤ target_relative_se or the
  // next pass would exceed max_samples.
  void refine(double target_relative_se, ProgressSink* progress = nullptr);

  GroundTruthResult result() const;
  int samples_per_vertex() const { return samples_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  int samples_ = 0;
};

// One call: GroundTruthIntegrator + refine(options.target_relative_se).
GroundTruthResult compute_ground_truth(const scene::Scene& scene, const sh::EnvMap& env,
                                       const GroundTruthOptions& options,
                                       ProgressSink* progress = nullptr);

}  // namespace prt::report
