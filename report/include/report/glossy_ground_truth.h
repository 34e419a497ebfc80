// report/glossy_ground_truth.h — an independent reference for the per-vertex exit radiance of
// GLOSSY surfaces toward an eye point: Monte Carlo path tracing against the actual environment
// map (not its SH projection), with each surface's own BRDF (prt/brdf/*.h) at the vertex and at
// every bounce. It shares no code with the SH paths (no projection, no transfer matrices, no b
// tables); the BRDF classes are shared and tested on their own (tests/prt/brdf).
//
// Quantity (the convention of prt/glossy/relighter.h): for vertex p with tangent frame
// (t, b = w·n × t, n) (scene/tangent_frames.h, the tangent Gram–Schmidt-orthonormalised against
// the vertex normal once), ω_o = normalize(eye − p) in that frame, and
//     L_o(p, ω_o) = ∫_{H+} f_p(ω_i, ω_o) L_in(p, ω_i) cos θ_i dω_i      (RGB, map units),
// L_in the map's radiance where the ray escapes, else the exit radiance of the surface it hits
// (recursively, toward the hit's own ω_o = −ray direction). A vertex seen from below its tangent
// plane (n·(eye − p) ≤ 0), at the eye point, or with a non-finite eye has L_o = 0, as in the
// relighter (the BRDFs are one-sided).
//
// Surfaces: a primitive with ScenePrimitive::brdf uses that material (make_brdf); one without is
// Lambert with the albedo of the point (Scene::albedo at the vertex, Scene::albedo_at at hits:
// interpolated, or the texture), as report/ground_truth.h does. So a Lambert-only scene gives
// that integrator's B_p. (The glossy bake's materials use a Lambert primitive's flat albedo; the
// two agree on untextured scenes.) At hit points the frame is the interpolated shading normal
// (the geometric normal where it turns away) and the barycentric blend of the hit triangle's
// vertex tangents, projected off that normal; where the blend nearly cancels (frames of
// neighbours flipped, below 0.5 long) the tangent of the vertex with the largest barycentric
// weight is used, and its handedness w throughout. Back faces occlude but reflect nothing; a
// hit whose ω_o is below its shading horizon reflects nothing (one-sided BRDF). Emission is
// ignored (light comes from the map only).
//
// Estimator per path vertex (Veach & Guibas 1995, [13] of docs/REFERENCES.md; Veach's thesis
// §9): one light sample (texel by luminance × solid angle, report/ground_truth.h's
// EnvironmentSampler) tested with a shadow ray, and one BRDF sample (Brdf::sample; Lambert:
// cosine-weighted) traced with a closest-hit ray, combined by the balance heuristic
//     light: f cos θ_i L / (p_light + p_brdf),   BRDF escape: f cos θ_i L / (p_brdf + p_light).
// A BRDF sample with pdf 0 ("no sample", prt/brdf/brdf.h) ends the path; that is unbiased
// because pdf() is the density of the kept samples. A front-face hit continues the path with
// throughput × f cos θ_i / p_brdf. Russian roulette from the third path vertex on (survival =
// the largest channel of f cos θ_i / p_brdf at the last bounce, clamped to [0.05, 0.99]), hard
// cap max_bounces reflections after the vertex (0: direct lighting only).
//
// Standard error, refine() and determinism: report/vertex_estimator.h, as for
// report/ground_truth.h (s over the integrated vertices and channels; sample s of vertex v from
// hash(seed, v, s) only, bit-identical for any thread count).
// Errors: bad inputs throw BakeError ("LABEL: problem"), Embree errors std::runtime_error.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "report/ground_truth.h"
#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::report {

// The sampling schedule (report/vertex_estimator.h), the path length and the eye.
struct GlossyGroundTruthOptions : VertexEstimatorOptions {
  std::array<double, 3> eye{0.0, 0.0, 0.0};  // scene frame, scene units
  int max_bounces = 64;                      // reflections after the vertex
};

// L_o toward the eye by the estimator above, refined by report/vertex_estimator.h's passes;
// result().radiance holds L_o per vertex (RGB).
class GlossyGroundTruthIntegrator : public VertexEstimator {
 public:
  // The scene and map must outlive the integrator. Throws BakeError for an empty scene, normals
  // or albedo that do not match the vertices, a material make_brdf refuses, a bad map or options.
  GlossyGroundTruthIntegrator(const scene::Scene& scene, const sh::EnvMap& env,
                              const GlossyGroundTruthOptions& options);
};

// One call: GlossyGroundTruthIntegrator + refine(options.target_relative_se).
GroundTruthResult compute_glossy_ground_truth(const scene::Scene& scene, const sh::EnvMap& env,
                                              const GlossyGroundTruthOptions& options,
                                              ProgressSink* progress = nullptr);

}  // namespace prt::report
