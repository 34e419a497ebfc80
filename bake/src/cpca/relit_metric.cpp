// relit_metric.cpp — the relit-error metric for CPCA; see bake/cpca/relit_metric.h.
#include "bake/cpca/relit_metric.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "numerics/constants.h"
#include "pca.h"
#include "prt/glossy/brdf_projection.h"

namespace prt {
namespace {

using numerics::kPi;

// Adds count · E_ωo[b_c(ω_o) b_c(ω_o)ᵀ] of one material to second[c·n⁴ + i·n² + k].
Status add_material(const brdf::Material& material, int order, double count,
                    const RelitMetricOptions& o, std::vector<double>* second) {
  Result<BrdfProjection> projection = BrdfProjection::create(material, order);
  if (!projection.ok()) return projection.status();
  const std::size_t n2 = std::size_t(order) * order;
  std::vector<double> b(3 * n2), sum(3 * n2 * n2, 0.0);
  for (int t = 0; t < o.view_theta; ++t) {
    const double cos_theta = (t + 0.5) / o.view_theta;
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    for (int p = 0; p < o.view_phi; ++p) {
      const double phi = 2.0 * kPi * (p + 0.5) / o.view_phi;
      projection->evaluate({sin_theta * std::cos(phi), sin_theta * std::sin(phi), cos_theta},
                           b.data());
      for (std::size_t c = 0; c < 3; ++c) {
        const double* bc = b.data() + c * n2;
        double* sc = sum.data() + c * n2 * n2;
        for (std::size_t i = 0; i < n2; ++i) {
          for (std::size_t k = 0; k < n2; ++k) sc[i * n2 + k] += bc[i] * bc[k];
        }
      }
    }
  }
  const double scale = count / (double(o.view_theta) * o.view_phi);
  for (std::size_t e = 0; e < sum.size(); ++e) (*second)[e] += scale * sum[e];
  return Status::Ok();
}

}  // namespace

Result<std::vector<double>> cpca_relit_metric(const GlossyTransferData& data,
                                              const RelitMetricOptions& o) {
  if (o.view_theta < 1 || o.view_theta > 4096 || o.view_phi < 1 || o.view_phi > 4096 ||
      !(o.floor > 0.0 && o.floor <= 1.0)) {
    return Status::Error("cpca metric: view grid outside [1, 4096] or floor outside (0, 1]");
  }
  if (data.materials.empty() || data.vertex_count == 0 ||
      data.material_of_vertex.size() != data.vertex_count) {
    return Status::Error("cpca metric: the transfer has no vertices or no materials");
  }
  if (data.channels != 1 && data.channels != 3) {
    return Status::Error("cpca metric: channel count is not 1 or 3");
  }
  std::vector<double> count(data.materials.size(), 0.0);
  for (uint32_t m : data.material_of_vertex) {
    if (m >= count.size()) {
      return Status::Error("cpca metric: material index " + std::to_string(m) + " out of range");
    }
    count[m] += 1.0;
  }
  const int order = static_cast<int>(data.order);
  const std::size_t n2 = std::size_t(order) * order, block = n2 * n2;
  std::vector<double> second(3 * block, 0.0);
  for (std::size_t m = 0; m < count.size(); ++m) {
    if (count[m] == 0.0) continue;
    Status s = add_material(data.materials[m], order, count[m], o, &second);
    if (!s.ok()) return s;
  }
  // Grey transport sees the three channels of b: their average.
  std::vector<double> metric(data.channels * block);
  for (std::size_t c = 0; c < data.channels; ++c) {
    for (std::size_t e = 0; e < block; ++e) {
      metric[c * block + e] = data.channels == 3
                                  ? second[c * block + e]
                                  : (second[e] + second[block + e] + second[2 * block + e]) / 3.0;
    }
  }
  // Per channel: C / λ_max(C) + floor² I (I alone when C is 0: black materials).
  for (std::size_t c = 0; c < data.channels; ++c) {
    double* gc = metric.data() + c * block;
    std::vector<double> a(gc, gc + block), values, vectors;
    detail::jacobi_eigen(n2, a, values, vectors);
    const double top = values.front() > 0.0 ? values.front() : 0.0;
    for (std::size_t e = 0; e < block; ++e) gc[e] = top > 0.0 ? gc[e] / top : 0.0;
    for (std::size_t i = 0; i < n2; ++i) gc[i * n2 + i] += o.floor * o.floor;
  }
  return metric;
}

}  // namespace prt
