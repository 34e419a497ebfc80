// Obscurance (bake/obscurance_falloff.h): the falloffs themselves, the AO closed forms at a huge
// obscurance distance, a closed room against the falloff's integral by quadrature, and a wall
// whose contribution vanishes once it is farther than the obscurance distance.
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/obscurance_falloff.h"
#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"

using prt::bake::bake_transfer;
using prt::bake::BakeOptions;
using prt::bake::obscurance_weight;
using prt::bake::ObscuranceFalloff;

namespace {

constexpr double kPi = 3.14159265358979323846;
const ObscuranceFalloff kFalloffs[] = {ObscuranceFalloff::Linear, ObscuranceFalloff::Exponential,
                                       ObscuranceFalloff::Smoothstep, ObscuranceFalloff::Constant};

BakeOptions obscurance_options(int samples, double distance, ObscuranceFalloff falloff) {
  BakeOptions o;
  o.order = 1;
  o.samples = samples;
  o.ao = true;
  o.bent_normals = true;
  o.obscurance.distance = distance;
  o.obscurance.falloff = falloff;
  return o;
}

// Mean and variance of ρ(d(ω)) under the cosine-weighted distribution of the hemisphere around +Y,
// by the midpoint rule in (u = sin²θ, φ), where cos θ dω / π = du dφ / 2π. `distance` returns the
// hit distance along a unit direction (∞ when the ray escapes).
struct Moments {
  double mean = 0, variance = 0;
};
Moments cosine_quadrature(const std::function<double(const glm::dvec3&)>& distance,
                          ObscuranceFalloff falloff, double D, int n) {
  double sum = 0, sum2 = 0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n, s = std::sqrt(u), c = std::sqrt(1.0 - u);
    for (int j = 0; j < n; ++j) {
      const double phi = 2.0 * kPi * (j + 0.5) / n;
      const double rho =
          obscurance_weight(falloff, distance({s * std::cos(phi), c, s * std::sin(phi)}), D);
      sum += rho;
      sum2 += rho * rho;
    }
  }
  const double count = static_cast<double>(n) * n;
  Moments m;
  m.mean = sum / count;
  m.variance = std::max(0.0, sum2 / count - m.mean * m.mean);
  return m;
}

// The error bound of a bake with N Owen-scrambled Sobol' samples: the variance of a scrambled
// (0, m, 2)-net in base 2 is at most e·σ²/N (Owen 1997), and we allow 4 standard deviations.
double sampling_bound(double variance, int samples) {
  return 4.0 * std::sqrt(std::exp(1.0) * variance / samples);
}

std::size_t find_vertex(const prt::scene::Scene& s, glm::vec3 p, glm::vec3 n) {
  for (std::size_t v = 0; v < s.positions.size(); ++v)
    if (glm::length(s.positions[v] - p) < 1e-5f && glm::dot(s.normals[v], n) > 0.999f) return v;
  return s.positions.size();
}

}  // namespace

TEST_CASE("obscurance falloffs rise from 0 at d = 0 to 1 at the obscurance distance") {
  const double D = 2.5;
  for (const ObscuranceFalloff f : kFalloffs) {
    INFO(prt::bake::obscurance_falloff_name(f));
    CHECK(obscurance_weight(f, 0.0, D) == 0.0);
    CHECK(obscurance_weight(f, D, D) == 1.0);
    CHECK(obscurance_weight(f, 7.0 * D, D) == 1.0);
    CHECK(obscurance_weight(f, std::numeric_limits<double>::infinity(), D) == 1.0);
    double last = 0.0;
    for (int i = 1; i <= 100; ++i) {  // monotone, within [0, 1]
      const double rho = obscurance_weight(f, D * i / 100.0, D);
      CHECK(rho >= last);
      CHECK(rho <= 1.0);
      last = rho;
    }
    REQUIRE(prt::bake::parse_obscurance_falloff(prt::bake::obscurance_falloff_name(f)) == f);
  }
  CHECK(obscurance_weight(ObscuranceFalloff::Linear, 0.5 * D, D) == Approx(0.5));
  CHECK(obscurance_weight(ObscuranceFalloff::Smoothstep, 0.5 * D, D) == Approx(0.5));
  CHECK(obscurance_weight(ObscuranceFalloff::Smoothstep, 0.25 * D, D) == Approx(0.15625));
  // (1 − e^−2)/(1 − e^−4) = 0.880797
  CHECK(obscurance_weight(ObscuranceFalloff::Exponential, 0.5 * D, D) == Approx(0.880797));
  CHECK(obscurance_weight(ObscuranceFalloff::Constant, 0.999 * D, D) == 0.0);
  CHECK_FALSE(prt::bake::parse_obscurance_falloff("quadratic").has_value());
}

TEST_CASE("obscurance at a huge distance is AO: the wall and the well closed forms") {
  // The wall of test_transfer_ao.cpp: floor rows at d = 2 (i = 0) and d = 1 (i = 1) from a wall
  // z = 1 of height 1; x = −2 + 0.2 j. At D = 1e6 every hit (d ≤ 41) weighs ρ ≤ 4.1·41/1e6 <
  // 2e-4 (the exponential falloff's slope at 0 is 4/(1 − e^−4) = 4.07 per D), so W equals the
  // visible fraction to 2e-4; the bound below is the AO test's (4σ of 21 × 4096 samples plus
  // the ray offset's 1e-3) and the same directions are drawn, so W − AO ∈ [0, 2e-4] too.
  prt::scene::Scene scene =
      prt::scene::make_quad({-2.f, 0, -1.f}, {0, 0, 1}, {4, 0, 0}, 1, 20, glm::vec3(0.5f), "floor");
  prt::scene::append_scene(scene, prt::scene::make_quad({-20.f, 0, 1.f}, {40, 0, 0}, {0, 1, 0}, 8,
                                                        1, glm::vec3(0.5f), "wall"));
  const int samples = 4096;
  BakeOptions plain = obscurance_options(samples, 0.0, ObscuranceFalloff::Linear);
  const auto ao = bake_transfer(scene, plain);
  for (const ObscuranceFalloff f : kFalloffs) {
    INFO(prt::bake::obscurance_falloff_name(f));
    const auto w = bake_transfer(scene, obscurance_options(samples, 1e6, f));
    for (int row = 0; row < 2; ++row) {
      const double d = row == 1 ? 1.0 : 2.0;
      const double occluded = 0.5 * (1.0 - d / std::sqrt(d * d + 1.0));
      double mean = 0;
      for (int j = 0; j <= 20; ++j) {
        const std::size_t v = static_cast<std::size_t>(j * 2 + row);
        mean += 1.0 - w.data.ao[v];
        CHECK(w.data.ao[v] - ao.data.ao[v] >= -1e-6f);
        CHECK(w.data.ao[v] - ao.data.ao[v] <= 2e-4f);
      }
      mean /= 21;
      const double sigma = 4.0 * std::sqrt(occluded * (1 - occluded) / (21.0 * samples));
      CHECK(mean == Approx(occluded).margin(sigma + 1e-3));
    }
  }
  // The well's bottom centre sees the opening: R²/(R² + h²) of the disc (the 64-gon is 0.1%
  // smaller); hits are ≤ 2.5 away, ρ ≤ 1e-5.
  const float R = 1.f, h = 1.5f;
  const prt::scene::Scene well = prt::scene::make_well(R, h, 64, 4, glm::vec3(0.5f));
  const std::size_t centre = find_vertex(well, {0.f, -h, 0.f}, {0, 1, 0});
  REQUIRE(centre < well.positions.size());
  const auto wb = bake_transfer(well, obscurance_options(samples, 1e6, ObscuranceFalloff::Linear));
  const double visible = R * R / (R * R + h * h);
  CHECK(wb.data.ao[centre] ==
        Approx(visible).margin(4.0 * std::sqrt(visible * (1 - visible) / samples) + 1e-3));
}

TEST_CASE("obscurance at the centre of a closed cubic room matches the falloff's integral") {
  // Room [−1, 1] × [0, 2] × [−1, 1], normals inward: plain AO is 0 everywhere. From the floor's
  // centre the first hit along ω is the ceiling at 2/ω_y or a wall at 1/|ω_x|, 1/|ω_z|, so
  // distances run from 1 (walls, at the horizon) to √6 = 2.449 (the top corners).
  const prt::scene::Scene room =
      prt::scene::make_box({-1.f, 0.f, -1.f}, {1.f, 2.f, 1.f}, 4, true, glm::vec3(0.5f));
  const std::size_t centre = find_vertex(room, {0.f, 0.f, 0.f}, {0, 1, 0});
  REQUIRE(centre < room.positions.size());
  const auto distance = [](const glm::dvec3& w) {
    double t = 2.0 / w.y;
    if (w.x != 0) t = std::min(t, 1.0 / std::fabs(w.x));
    if (w.z != 0) t = std::min(t, 1.0 / std::fabs(w.z));
    return t;
  };
  const int samples = 4096;
  const auto ao = bake_transfer(room, obscurance_options(samples, 0.0, ObscuranceFalloff::Linear));
  CHECK(ao.data.ao[centre] == 0.f);
  for (const double D : {1.5, 2.2, 3.0}) {
    for (const ObscuranceFalloff f : kFalloffs) {
      INFO("D = " << D << ", " << prt::bake::obscurance_falloff_name(f));
      // 2000² midpoints: the integrand is continuous but for the constant falloff's step, whose
      // rule error is about its jump line's share of cells, < 1e-3.
      const Moments m = cosine_quadrature(distance, f, D, 2000);
      const auto w = bake_transfer(room, obscurance_options(samples, D, f));
      // Tolerance: 4σ of the scrambled net (≤ 0.05 for σ ≤ 0.5), plus 1e-3 for the quadrature
      // and for the ray offset (ε ≈ 3e-4 moves every distance by ≤ ε; ρ' ≤ 4.1/D).
      CHECK(w.data.ao[centre] == Approx(m.mean).margin(sampling_bound(m.variance, samples) + 1e-3));
      if (f != ObscuranceFalloff::Constant) CHECK(w.data.ao[centre] > 0.f);
      // The room is symmetric about the vertical through the vertex: the bent normal is +Y.
      CHECK(w.data.bent_normals[3 * centre + 1] == Approx(1.0).margin(2e-3));
    }
  }
}

TEST_CASE("a wall's contribution to obscurance vanishes once it is farther than the distance") {
  // Floor rows at d = 2 (i = 0) and d = 1 (i = 1) from a wall z = 1 of height 1 (as above).
  prt::scene::Scene scene =
      prt::scene::make_quad({-2.f, 0, -1.f}, {0, 0, 1}, {4, 0, 0}, 1, 20, glm::vec3(0.5f), "floor");
  prt::scene::append_scene(scene, prt::scene::make_quad({-20.f, 0, 1.f}, {40, 0, 0}, {0, 1, 0}, 8,
                                                        1, glm::vec3(0.5f), "wall"));
  const int samples = 4096;
  const double D = 1.5;
  for (const ObscuranceFalloff f : kFalloffs) {
    INFO(prt::bake::obscurance_falloff_name(f));
    const auto w = bake_transfer(scene, obscurance_options(samples, D, f));
    // d = 2 > D: every hit is at least d away, ρ = 1: W is exactly 1 and the bent normal is the
    // unoccluded one (the mean of the cosine-weighted directions, ≈ +Y).
    for (int j = 0; j <= 20; ++j) {
      const std::size_t v = static_cast<std::size_t>(j * 2);
      CHECK(w.data.ao[v] == 1.f);
      CHECK(w.data.bent_normals[3 * v + 1] == Approx(1.0).margin(2e-3));
    }
    // d = 1 < D: the wall still counts; the vertex at x = 0 (j = 10) against quadrature of
    // the wall z = 1, 0 ≤ y ≤ 1, |x| ≤ 20 seen from (0, 0, 0).
    const auto distance = [](const glm::dvec3& w_dir) {
      if (w_dir.z <= 0) return std::numeric_limits<double>::infinity();
      const double t = 1.0 / w_dir.z;
      if (t * w_dir.y > 1.0 || std::fabs(t * w_dir.x) > 20.0)
        return std::numeric_limits<double>::infinity();
      return t;
    };
    const Moments m = cosine_quadrature(distance, f, D, 2000);
    const std::size_t v = 10 * 2 + 1;
    CHECK(m.mean < 1.0 - 1e-3);
    CHECK(w.data.ao[v] == Approx(m.mean).margin(sampling_bound(m.variance, samples) + 1e-3));
    CHECK(w.data.ao[v] < 1.f);
  }
}
