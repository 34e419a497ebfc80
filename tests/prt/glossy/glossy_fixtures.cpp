// Fixtures of the glossy runtime tests (glossy_fixtures.h).
#include "glossy_fixtures.h"

#include <cmath>

#include <catch2/catch.hpp>

#include "numerics/constants.h"
#include "numerics/rng.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/zonal.h"

namespace glossy_test {
namespace {

using prt::numerics::kPi;

}  // namespace

std::array<double, 9> frame_rows(const prt::GlossyTransferData& d, std::size_t v) {
  const double n[3] = {d.normals[3 * v], d.normals[3 * v + 1], d.normals[3 * v + 2]};
  const double t[3] = {d.tangents[4 * v], d.tangents[4 * v + 1], d.tangents[4 * v + 2]};
  const double b[3] = {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2],
                       n[0] * t[1] - n[1] * t[0]};
  return {t[0], t[1], t[2], b[0], b[1], b[2], n[0], n[1], n[2]};
}

prt::GlossyTransferData unshadowed_sphere(int order, std::size_t count,
                                          const prt::brdf::Material& material) {
  prt::GlossyTransferData d;
  d.order = uint32_t(order);
  d.vertex_count = count;
  d.materials = {material};
  d.material_of_vertex.assign(count, 0);
  const std::size_t n2 = std::size_t(order) * order;
  d.matrices.assign(count * n2 * n2, 0.f);
  for (std::size_t v = 0; v < count; ++v) {
    const double z = 1.0 - (2.0 * double(v) + 1.0) / double(count);
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z)),
                 phi = double(v) * kPi * (3.0 - std::sqrt(5.0));
    const double n[3] = {r * std::cos(phi), r * std::sin(phi), z};
    // Duff et al. 2017: a branchless orthonormal basis from the normal.
    const double s = std::copysign(1.0, n[2]), a = -1.0 / (s + n[2]), b = n[0] * n[1] * a;
    const double t[3] = {1.0 + s * n[0] * n[0] * a, s * b, -s * n[0]};
    for (int k = 0; k < 3; ++k) {
      d.positions.push_back(float(n[k]));
      d.normals.push_back(float(n[k]));
      d.tangents.push_back(float(t[k]));
    }
    d.tangents.push_back(1.f);
    const std::array<double, 9> f = frame_rows(d, v);
    const prt::sh::Rotation rotation(order, f);
    float* m = &d.matrices[v * n2 * n2];
    for (int l = 0; l < order; ++l) {
      const double* band = rotation.band_matrix(l);
      const int w = 2 * l + 1, o = l * l;
      for (int i = 0; i < w; ++i)
        for (int j = 0; j < w; ++j) m[std::size_t(o + i) * n2 + o + j] = float(band[i * w + j]);
    }
  }
  return d;
}

prt::ShLighting band_limited_lighting(int order, const std::array<double, 3>& towards,
                                      uint64_t seed) {
  const int n2 = order * order;
  std::vector<double> zonal(static_cast<std::size_t>(order)), lobe(static_cast<std::size_t>(n2));
  std::vector<double> rgb(3 * static_cast<std::size_t>(n2));
  for (int l = 0; l < order; ++l) zonal[l] = 3.0 * std::exp(-0.5 * l * (l + 1) / 12.0);
  const double len =
      std::sqrt(towards[0] * towards[0] + towards[1] * towards[1] + towards[2] * towards[2]);
  prt::sh::rotate_zonal(order, zonal.data(), towards[0] / len, towards[1] / len, towards[2] / len,
                        lobe.data());
  prt::numerics::SplitMix64 rng{seed};
  const double tint[3] = {1.0, 0.8, 0.6};
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < n2; ++k)
      rgb[std::size_t(c * n2 + k)] =
          tint[c] * lobe[std::size_t(k)] + 0.15 * (rng.uniform() - 0.5) + (k == 0 ? 1.5 : 0.0);
  prt::Result<prt::ShLighting> light = prt::ShLighting::from_coefficients(order, rgb.data());
  REQUIRE(light.ok());
  return light.value();
}

std::array<double, 3> monte_carlo_exit(const prt::GlossyTransferData& data,
                                       const prt::ShLighting& light, const double eye[3],
                                       std::size_t v, int strata, double* standard_error) {
  const std::array<double, 9> f = frame_rows(data, v);
  const double d[3] = {eye[0] - data.positions[3 * v], eye[1] - data.positions[3 * v + 1],
                       eye[2] - data.positions[3 * v + 2]};
  const prt::brdf::Vec3 wo = prt::brdf::normalize({f[0] * d[0] + f[1] * d[1] + f[2] * d[2],
                                                   f[3] * d[0] + f[4] * d[1] + f[5] * d[2],
                                                   f[6] * d[0] + f[7] * d[1] + f[8] * d[2]});
  auto made = prt::brdf::make_brdf(data.materials[data.material_of_vertex[v]]);
  REQUIRE(made.ok());
  const int order = light.order(), n2 = order * order;
  std::vector<double> y(static_cast<std::size_t>(n2));
  double sum[3] = {0, 0, 0}, sum2[3] = {0, 0, 0};
  prt::numerics::SplitMix64 rng{12345 + uint64_t(v)};
  for (int a = 0; a < strata; ++a)
    for (int b = 0; b < strata; ++b) {
      const double u1 = (a + rng.uniform()) / strata, u2 = (b + rng.uniform()) / strata;
      const prt::brdf::BrdfSample s = made.value()->sample(wo, u1, u2);
      if (!(s.pdf > 0.0) || wo.z <= 0.0) continue;
      const double g[3] = {f[0] * s.wi.x + f[3] * s.wi.y + f[6] * s.wi.z,
                           f[1] * s.wi.x + f[4] * s.wi.y + f[7] * s.wi.z,
                           f[2] * s.wi.x + f[5] * s.wi.y + f[8] * s.wi.z};
      prt::sh::evaluate(order, g[0], g[1], g[2], y.data());
      const double fc[3] = {s.f.r, s.f.g, s.f.b};
      for (int c = 0; c < 3; ++c) {
        double radiance = 0.0;
        const double* l = light.coefficients_double(c);
        for (int k = 0; k < n2; ++k) radiance += l[k] * y[std::size_t(k)];
        const double x = radiance * fc[c] * s.wi.z / s.pdf;
        sum[c] += x;
        sum2[c] += x * x;
      }
    }
  const double n = double(strata) * strata;
  std::array<double, 3> mean{};
  double worst = 0.0;
  for (int c = 0; c < 3; ++c) {
    mean[c] = sum[c] / n;
    worst = std::max(worst, std::sqrt(std::max(0.0, sum2[c] / n - mean[c] * mean[c]) / n));
  }
  if (standard_error) *standard_error = worst;
  return mean;
}

}  // namespace glossy_test
