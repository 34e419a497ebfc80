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
// Standard error, refine() and determinism: report/vertex_estimator.h (every sample an independent
// estimate of B_p; s = the relative RMS standard error over the integrated vertices and channels,
// the same RGB-norm RMS that report/report.h uses for errors; doubling until s ≤ target, a sample
// cap or a time budget). The random numbers of sample s of vertex v come from hash(seed, v, s)
// only, so the result is bit-identical for any thread count and any doubling schedule.
// Errors: bad inputs throw BakeError ("PATH: problem"), Embree errors std::runtime_error.
// References: [13] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "report/vertex_estimator.h"
#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::report {

// The sampling schedule (report/vertex_estimator.h) and the path length.
struct GroundTruthOptions : VertexEstimatorOptions {
  int max_bounces = 64;  // reflections after the vertex (0: direct lighting only)
};

// The inputs every per-vertex ground truth needs: throws BakeError ("LABEL: problem", LABEL the
// scene's; `kind` names the estimate, e.g. "ground truth") unless the scene has vertices and
// triangles, a normal and an albedo per vertex, every albedo channel in [0, 1),
// max_bounces >= 0 and the options pass VertexEstimator::check_options.
void check_ground_truth_inputs(const scene::Scene& scene, const VertexEstimatorOptions& options,
                               int max_bounces, const std::string& kind);

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

// B_p by the estimator above, refined by report/vertex_estimator.h's passes.
class GroundTruthIntegrator : public VertexEstimator {
 public:
  // The scene and map must outlive the integrator. Throws BakeError for an empty scene, albedo
  // outside [0, 1), a bad map or options.
  GroundTruthIntegrator(const scene::Scene& scene, const sh::EnvMap& env,
                        const GroundTruthOptions& options);
};

// One call: GroundTruthIntegrator + refine(options.target_relative_se).
GroundTruthResult compute_ground_truth(const scene::Scene& scene, const sh::EnvMap& env,
                                       const GroundTruthOptions& options,
                                       ProgressSink* progress = nullptr);

}  // namespace prt::report
