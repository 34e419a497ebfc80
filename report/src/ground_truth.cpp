// report/src/ground_truth.cpp — the Monte Carlo reference of report/ground_truth.h.
#include "report/ground_truth.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "numerics/hash.h"
#include "numerics/rng.h"
#include "numerics/sampling.h"
#include "scene/ray_caster.h"

#include "scene/scene_label.h"
#include "sh/constants.h"

namespace prt::report {
namespace {

using bake::BakeError;
using bake::build_orthonormal_basis;
using numerics::hash_seed;

using sh::kPi;
constexpr int kRouletteFromDepth = 2;  // path vertices 0 and 1 never roulette
constexpr std::size_t kVertexBlock = 32;

double luminance(const double rgb[3]) {
  return 0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2];
}

using SampleRng = numerics::SplitMix64;

// Face direction of the cube layouts (sh/env_map.h): face index in +X, −X, +Y, −Y, +Z, −Z order.
void cube_face_direction(int face, double a, double b, bool faces_layout, double d[3]) {
  switch (face) {
    case 0:
      d[0] = 1, d[1] = -b, d[2] = a;
      break;  // +X
    case 1:
      d[0] = -1, d[1] = -b, d[2] = -a;
      break;  // −X
    case 2:
      d[0] = a, d[1] = 1, d[2] = -b;
      break;  // +Y
    case 3:
      d[0] = a, d[1] = -1, d[2] = b;
      break;  // −Y
    case 4:   // +Z
      if (faces_layout)
        d[0] = -a, d[1] = -b, d[2] = 1;
      else
        d[0] = a, d[1] = b, d[2] = 1;
      break;
    default:
      d[0] = a, d[1] = -b, d[2] = -1;
      break;  // −Z
  }
}

// Cell (col, row) of the vertical cross → face index, or −1 for the empty cells.
int cross_face(int cell_col, int cell_row) {
  if (cell_col == 1 && cell_row == 0) return 2;
  if (cell_row == 1) return cell_col == 0 ? 1 : cell_col == 1 ? 5 : 0;
  if (cell_col == 1 && cell_row == 2) return 3;
  if (cell_col == 1 && cell_row == 3) return 4;
  return -1;
}

// A triangle's geometric normal, oriented to the side its vertex normals point to.
glm::vec3 oriented_face_normal(const scene::Scene& s, uint32_t tri) {
  const glm::uvec3 t = s.triangles[tri];
  glm::vec3 ng =
      glm::cross(s.positions[t.y] - s.positions[t.x], s.positions[t.z] - s.positions[t.x]);
  const float len = glm::length(ng);
  if (!(len > 0.f)) return glm::vec3(0.f);
  ng /= len;
  if (glm::dot(ng, s.normals[t.x] + s.normals[t.y] + s.normals[t.z]) < 0.f) ng = -ng;
  return ng;
}

}  // namespace

bool image_point_direction(sh::EnvLayout layout, int w, int h, double x, double y, double dir[3],
                           double* jacobian) noexcept {
  if (w <= 0 || h <= 0 || !(x >= 0 && x <= w && y >= 0 && y <= h)) return false;
  switch (layout) {
    case sh::EnvLayout::LatLong: {
      const double phi = 2.0 * kPi * (x / w - 0.5), theta = kPi * y / h;
      const double st = std::sin(theta);
      dir[0] = st * std::cos(phi), dir[1] = std::cos(theta), dir[2] = st * std::sin(phi);
      *jacobian = st * 2.0 * kPi * kPi / (static_cast<double>(w) * h);
      return *jacobian > 0;
    }
    case sh::EnvLayout::Angular: {
      const double u = 2.0 * x / w - 1.0, v = 1.0 - 2.0 * y / h;
      const double r = std::sqrt(u * u + v * v);
      if (r >= 1.0) return false;
      const double theta = kPi * r;
      const double sinc = r > 0 ? std::sin(theta) / theta : 1.0;
      const double s_over_r = kPi * sinc;  // sin θ / r
      dir[0] = s_over_r * u, dir[1] = s_over_r * v, dir[2] = -std::cos(theta);
      *jacobian = kPi * kPi * sinc * (2.0 / w) * (2.0 / h);
      return *jacobian > 0;
    }
    case sh::EnvLayout::Cross:
    case sh::EnvLayout::Faces: {
      const bool faces = layout == sh::EnvLayout::Faces;
      const int s = faces ? w : w / 3;
      if (s <= 0) return false;
      const int cc = std::min(static_cast<int>(x / s), faces ? 0 : 2);
      const int cr = std::min(static_cast<int>(y / s), faces ? 5 : 3);
      const int face = faces ? cr : cross_face(cc, cr);
      if (face < 0) return false;
      const double a = 2.0 * (x - cc * s) / s - 1.0, b = 2.0 * (y - cr * s) / s - 1.0;
      double d[3];
      cube_face_direction(face, a, b, faces, d);
      const double r2 = a * a + b * b + 1.0, inv = 1.0 / std::sqrt(r2);
      for (int i = 0; i < 3; ++i) dir[i] = d[i] * inv;
      *jacobian = (2.0 / s) * (2.0 / s) / (r2 * std::sqrt(r2));
      return true;
    }
  }
  return false;
}

EnvironmentSampler::EnvironmentSampler(const sh::EnvMap& env) : env_(&env) {
  std::string why;
  if (env.width <= 0 || env.height <= 0 ||
      env.rgb.size() != 3ull * env.width * static_cast<std::size_t>(env.height))
    throw BakeError("environment: empty map or pixel count does not match its size");
  if (env.layout != sh::EnvLayout::LatLong &&
      !sh::validate_layout(env.layout, env.width, env.height, &why))
    throw BakeError("environment: " + why);
  const std::vector<double> omega = sh::texel_solid_angles(env.layout, env.width, env.height);
  cdf_.resize(omega.size());
  double sum = 0;
  for (std::size_t t = 0; t < omega.size(); ++t) {
    const float* p = &env.rgb[3 * t];
    double rgb[3] = {p[0], p[1], p[2]};
    double weight = 0;
    if (std::isfinite(rgb[0]) && std::isfinite(rgb[1]) && std::isfinite(rgb[2]) && rgb[0] >= 0 &&
        rgb[1] >= 0 && rgb[2] >= 0) {
      // Luminance, but never 0 for a coloured texel (pure blue has luminance 0.07·b).
      weight = std::max(luminance(rgb), (rgb[0] + rgb[1] + rgb[2]) * 1e-3) * omega[t];
    } else if (omega[t] > 0) {
      ++skipped_;
    }
    sum += weight;
    cdf_[t] = sum;
  }
  total_weight_ = sum;
}

void EnvironmentSampler::evaluate(const double dir[3], double rgb[3], double* pdf) const {
  rgb[0] = rgb[1] = rgb[2] = 0;
  *pdf = 0;
  double x, y;
  if (!sh::direction_to_texel(env_->layout, env_->width, env_->height, dir, &x, &y)) return;
  const int col = std::clamp(static_cast<int>(std::floor(x)), 0, env_->width - 1);
  const int row = std::clamp(static_cast<int>(std::floor(y)), 0, env_->height - 1);
  const std::size_t t = static_cast<std::size_t>(row) * env_->width + col;
  const double weight = cdf_[t] - (t > 0 ? cdf_[t - 1] : 0.0);
  if (!(weight > 0)) return;  // black or skipped texel: radiance 0 too
  for (int c = 0; c < 3; ++c) rgb[c] = env_->rgb[3 * t + c];
  double d[3], jac;
  if (!image_point_direction(env_->layout, env_->width, env_->height, x, y, d, &jac)) return;
  *pdf = weight / total_weight_ / jac;
}

bool EnvironmentSampler::sample(double u0, double u1, double u2, double dir[3], double rgb[3],
                                double* pdf) const {
  if (black()) return false;
  const double target = u0 * total_weight_;
  std::size_t t =
      static_cast<std::size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), target) - cdf_.begin());
  t = std::min(t, cdf_.size() - 1);
  const double weight = cdf_[t] - (t > 0 ? cdf_[t - 1] : 0.0);
  if (!(weight > 0)) return false;
  const int col = static_cast<int>(t % env_->width), row = static_cast<int>(t / env_->width);
  double jac;
  if (!image_point_direction(env_->layout, env_->width, env_->height, col + u1, row + u2, dir,
                             &jac))
    return false;
  for (int c = 0; c < 3; ++c) rgb[c] = env_->rgb[3 * t + c];
  *pdf = weight / total_weight_ / jac;
  return true;
}

namespace {

// The paths of the header's estimator: what one sample of B_p needs.
struct DiffusePaths {
  const scene::Scene& scene;
  GroundTruthOptions options;
  EnvironmentSampler light;
  scene::RayCaster caster;

  DiffusePaths(const scene::Scene& s, const sh::EnvMap& env, const GroundTruthOptions& o)
      : scene(s), options(o), light(env), caster(s) {}

  // One sample of B_v (RGB) into out; returns the rays cast.
  uint32_t sample_vertex(uint32_t v, uint64_t sample_index, double out[3]) const;
};

uint32_t DiffusePaths::sample_vertex(uint32_t v, uint64_t sample_index, double out[3]) const {
  SampleRng rng{hash_seed(hash_seed(options.seed, v), sample_index)};
  out[0] = out[1] = out[2] = 0;
  uint32_t cast = 0;
  glm::vec3 origin = caster.vertex_origin(v);
  glm::vec3 normal = glm::normalize(scene.normals[v]);
  double beta[3] = {scene.albedo[v].x, scene.albedo[v].y, scene.albedo[v].z};
  const float far = 1e30f;
  for (int depth = 0;; ++depth) {
    // Light sample, weighted by the balance heuristic against the cosine sample.
    double ld[3], lrgb[3], lpdf;
    const double u0 = rng.uniform(), u1 = rng.uniform(), u2 = rng.uniform();
    if (light.sample(u0, u1, u2, ld, lrgb, &lpdf)) {
      const glm::vec3 d(static_cast<float>(ld[0]), static_cast<float>(ld[1]),
                        static_cast<float>(ld[2]));
      const double cosine = glm::dot(normal, d);
      if (cosine > 0 && lpdf > 0) {
        ++cast;
        if (!caster.occluded(origin, d, 0.f, far)) {
          const double cpdf = cosine / kPi;
          const double w = cosine / kPi / (lpdf + cpdf);  // w_l · cos/(π p_l)
          for (int c = 0; c < 3; ++c) out[c] += beta[c] * w * lrgb[c];
        }
      }
    }
    // Cosine sample: escape → weighted map radiance; front hit → continue the path.
    glm::vec3 t, b;
    build_orthonormal_basis(normal, t, b);
    // (glm::vec2's constructor: the two draws in the compiler's argument order, as before.)
    const glm::vec2 u(static_cast<float>(rng.uniform()), static_cast<float>(rng.uniform()));
    const glm::vec3 local = bake::to_glm(numerics::sample_cosine_hemisphere(bake::to_numerics(u)));
    glm::vec3 d = glm::normalize(local.x * t + local.y * b + local.z * normal);
    const double cosine = glm::dot(normal, d);
    if (!(cosine > 0)) break;
    ++cast;
    const scene::RayCaster::Hit hit = caster.intersect(origin, d, 0.f, far);
    if (!hit.hit) {
      const double dd[3] = {d.x, d.y, d.z};
      double rgb[3], lpdf_at;
      light.evaluate(dd, rgb, &lpdf_at);
      const double cpdf = cosine / kPi;
      const double w = cpdf / (cpdf + lpdf_at);
      for (int c = 0; c < 3; ++c) out[c] += beta[c] * w * rgb[c];
      break;
    }
    if (depth >= options.max_bounces) break;
    const glm::vec3 ng = oriented_face_normal(scene, hit.triangle);
    if (!(glm::dot(ng, d) < 0.f)) break;  // back face (or degenerate): occludes, reflects nothing
    const glm::uvec3 tri = scene.triangles[hit.triangle];
    const float w0 = 1.f - hit.u - hit.v;
    const glm::vec3 albedo = scene.albedo_at(hit.triangle, hit.u, hit.v);
    glm::vec3 ns =
        w0 * scene.normals[tri.x] + hit.u * scene.normals[tri.y] + hit.v * scene.normals[tri.z];
    const float ns_len = glm::length(ns);
    ns = ns_len > 0.f ? ns / ns_len : ng;
    if (glm::dot(ns, ng) <= 0.f) ns = ng;
    beta[0] *= albedo.x, beta[1] *= albedo.y, beta[2] *= albedo.z;
    if (depth + 1 >= kRouletteFromDepth) {
      const double survive =
          std::clamp<double>(std::max({albedo.x, albedo.y, albedo.z}), 0.05, 0.99);
      if (rng.uniform() >= survive) break;
      for (double& x : beta) x /= survive;
    }
    const glm::vec3 p = w0 * scene.positions[tri.x] + hit.u * scene.positions[tri.y] +
                        hit.v * scene.positions[tri.z];
    origin = caster.surface_origin(hit.triangle, p, ng);
    normal = ns;
  }
  return cast;
}

// Checks the inputs (before the ray caster is built), then the sampler over DiffusePaths.
VertexSampler diffuse_sampler(const scene::Scene& scene, const sh::EnvMap& env,
                              const GroundTruthOptions& o) {
  check_ground_truth_inputs(scene, o, o.max_bounces, "ground truth");
  auto paths = std::make_shared<const DiffusePaths>(scene, env, o);
  return make_vertex_sampler(paths, "ground truth", kVertexBlock, paths->light.skipped_texels());
}

}  // namespace

void check_ground_truth_inputs(const scene::Scene& scene, const VertexEstimatorOptions& options,
                               int max_bounces, const std::string& kind) {
  const std::string name = scene::scene_label(scene);
  if (scene.vertex_count() == 0 || scene.triangles.empty())
    throw BakeError(name + ": the scene has no vertices or no triangles");
  if (scene.normals.size() != scene.vertex_count() || scene.albedo.size() != scene.vertex_count())
    throw BakeError(name + ": normals or albedo do not match the vertex count");
  for (const glm::vec3& a : scene.albedo)
    for (int c = 0; c < 3; ++c)
      if (!(a[c] >= 0.f && a[c] < 1.f))
        throw BakeError(name + ": albedo " + std::to_string(a[c]) + " is outside [0, 1)");
  if (max_bounces < 0) throw BakeError(name + ": " + kind + " needs max_bounces >= 0");
  VertexEstimator::check_options(scene.vertex_count(), options, name + ": " + kind);
}

GroundTruthIntegrator::GroundTruthIntegrator(const scene::Scene& scene, const sh::EnvMap& env,
                                             const GroundTruthOptions& o)
    : VertexEstimator(scene.vertex_count(), o, diffuse_sampler(scene, env, o),
                      scene::scene_label(scene) + ": ground truth") {}

GroundTruthResult compute_ground_truth(const scene::Scene& scene, const sh::EnvMap& env,
                                       const GroundTruthOptions& options, ProgressSink* progress) {
  GroundTruthIntegrator integrator(scene, env, options);
  integrator.refine(options.target_relative_se, progress);
  return integrator.result();
}

}  // namespace prt::report
