// The approximations' common part, Lambert with R_total and mesh-space diffusion (see
// bake/subsurface_approx/subsurface_approximations.h).
#include "bake/subsurface_approx/subsurface_approximations.h"

#include <stdexcept>

#include "approximation_common.h"
#include "bake/subsurface/subsurface_baker.h"
#include "bake/subsurface_approx/surface_blur.h"

namespace prt::bake {
namespace detail {

prt::TransferData lambert_transfer(const SubsurfaceApproximationInputs& in) {
  const prt::TransferData& s = *in.shadowed;
  const std::size_t n = s.vertex_count, kc = s.coefficients_per_channel();
  prt::TransferData out;
  out.kind = prt::TransferKind::Shadowed;
  out.order = s.order;
  out.channels = 3;
  out.storage = prt::Precision::F32;
  out.albedo_folded = true;
  out.vertex_count = s.vertex_count;
  out.fingerprint = s.fingerprint;
  out.primitives = s.primitives;
  out.positions = s.positions;
  out.normals = s.normals;
  out.coefficients.resize(n * 3 * kc);
  for (std::size_t v = 0; v < n; ++v)
    for (int c = 0; c < 3; ++c) {
      const double rho =
          in.group[v] >= 0 ? in.material.channels[c].total() : double(in.scene->albedo[v][c]);
      for (std::size_t k = 0; k < kc; ++k)
        out.coefficients[(v * 3 + c) * kc + k] =
            static_cast<float>(rho * s.coefficients[v * kc + k]);
    }
  return out;
}

void set_translucent_rows(const SubsurfaceApproximationInputs& in, const std::vector<double>& rows,
                          prt::TransferData& out) {
  const std::size_t kc = out.coefficients_per_channel();
  for (std::size_t v = 0; v < out.vertex_count; ++v)
    if (in.group[v] >= 0)
      for (std::size_t i = 0; i < 3 * kc; ++i)
        out.coefficients[v * 3 * kc + i] = static_cast<float>(rows[v * 3 * kc + i]);
}

}  // namespace detail

namespace {

void check_inputs(const SubsurfaceApproximationInputs& in) {
  if (!in.scene || !in.shadowed || !in.caster)
    throw std::invalid_argument("subsurface approximation: scene, caster and transfer required");
  const prt::TransferData& s = *in.shadowed;
  if (s.vertex_count != in.scene->positions.size() || in.group.size() != s.vertex_count)
    throw std::invalid_argument("subsurface approximation: vertex counts differ");
  if (s.channels != 1 || s.albedo_folded)
    throw std::invalid_argument(
        "subsurface approximation: the shadowed transfer must be grey with the albedo kept apart");
}

// Σ_i w_i,c · blur_{v_i}(S): one blur per Gaussian serves the three channels.
prt::TransferData mesh_diffusion_transfer(const SubsurfaceApproximationInputs& in) {
  prt::TransferData out = detail::lambert_transfer(in);
  const GaussianSum fit = fit_gaussian_sum(in.material, in.gaussians);
  const prt::TransferData& s = *in.shadowed;
  const std::size_t n = s.vertex_count, kc = s.coefficients_per_channel();
  const std::vector<double> areas = vertex_areas(*in.scene);
  const std::vector<double> values(s.coefficients.begin(), s.coefficients.end());
  std::vector<double> rows(n * 3 * kc, 0.0);
  for (std::size_t i = 0; i < fit.variances.size(); ++i) {
    const auto& w = fit.weights[i];
    if (w[0] == 0 && w[1] == 0 && w[2] == 0) continue;
    const std::vector<double> blurred = blur_over_surface(
        *in.scene, areas, in.group, values, static_cast<int>(kc), std::sqrt(fit.variances[i]));
    for (std::size_t v = 0; v < n; ++v)
      for (int c = 0; c < 3; ++c)
        for (std::size_t k = 0; k < kc; ++k)
          rows[(v * 3 + c) * kc + k] += w[c] * blurred[v * kc + k];
  }
  detail::set_translucent_rows(in, rows, out);
  return out;
}

}  // namespace

const char* approximation_name(SubsurfaceApproximation a) {
  switch (a) {
    case SubsurfaceApproximation::kLambert:
      return "lambert-rtotal";
    case SubsurfaceApproximation::kNormalBlur:
      return "normal-blur";
    case SubsurfaceApproximation::kMeshDiffusion:
      return "mesh-diffusion";
    case SubsurfaceApproximation::kDepthMap:
      return "depth-map";
  }
  return "unknown";
}

std::vector<int32_t> translucent_groups(const scene::Scene& scene,
                                        const std::vector<std::string>& names) {
  std::vector<int32_t> group(scene.positions.size(), -1);
  for (std::size_t p = 0; p < scene.primitives.size(); ++p) {
    const scene::ScenePrimitive& prim = scene.primitives[p];
    bool chosen = names.empty();
    for (const std::string& name : names)
      chosen = chosen || name == prim.name || name == prim.material || name == "*";
    if (!chosen) continue;
    for (uint32_t v = prim.first_vertex; v < prim.first_vertex + prim.vertex_count; ++v)
      group[v] = static_cast<int32_t>(p);
  }
  return group;
}

prt::TransferData approximate_subsurface(const SubsurfaceApproximationInputs& in,
                                         SubsurfaceApproximation which) {
  check_inputs(in);
  prt::TransferData out;
  switch (which) {
    case SubsurfaceApproximation::kLambert:
      out = detail::lambert_transfer(in);
      break;
    case SubsurfaceApproximation::kNormalBlur:
      out = detail::normal_blur_transfer(in);
      break;
    case SubsurfaceApproximation::kMeshDiffusion:
      out = mesh_diffusion_transfer(in);
      break;
    case SubsurfaceApproximation::kDepthMap:
      out = detail::depth_map_transfer(in);
      break;
  }
  out.metadata_json = std::string("{\"subsurface_approximation\":\"") + approximation_name(which) +
                      "\",\"albedo_folded\":true}";
  return out;
}

}  // namespace prt::bake
