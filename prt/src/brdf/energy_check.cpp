// The white-furnace check by deterministic quadrature (prt/brdf/energy_check.h).
#include "prt/brdf/energy_check.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>

#include "brdf/lobe_mix.h"
#include "numerics/constants.h"

namespace prt::brdf {
namespace {

constexpr int kCosineU = 32, kCosineV = 64;  // cosine grid
constexpr int kHalfT = 128, kHalfS = 64;     // half-vector grid
constexpr double kCosineCount = kCosineU * kCosineV;
constexpr double kHalfCount = kHalfT * kHalfS;

// Density of ωi under the half-vector grid (per solid angle of ωi), 0 where it cannot reach.
double half_vector_density(const Vec3& wo, const Vec3& wi) {
  const Vec3 sum = wi + wo;
  if (dot(sum, sum) <= 1e-24) return 0.0;
  const Vec3 h = normalize(sum);
  const double oh = dot(wo, h);
  if (h.z <= 0.0 || oh <= 0.0) return 0.0;
  const double theta = std::acos(std::min(1.0, h.z));
  const double t = std::sqrt(theta / numerics::kHalfPi);
  const double sin_theta = std::sin(theta);
  if (t <= 0.0 || sin_theta <= 0.0) return 0.0;
  return 1.0 / (2.0 * numerics::kPi * numerics::kPi * t * sin_theta) / (4.0 * oh);
}

double cosine_density(const Vec3& wi) {
  return wi.z > 0.0 ? wi.z * numerics::kInvPi : 0.0;
}

void add(const Brdf& brdf, const Vec3& wo, const Vec3& wi, double sum[3]) {
  if (wi.z <= 0.0) return;
  const double denominator =
      kCosineCount * cosine_density(wi) + kHalfCount * half_vector_density(wo, wi);
  if (!(denominator > 0.0)) return;
  const Rgb f = brdf.eval(wi, wo);
  const double w = wi.z / denominator;
  sum[0] += f.r * w;
  sum[1] += f.g * w;
  sum[2] += f.b * w;
}

// A spin lock on the MERL verdicts (the runtime has no <mutex>: it starts no threads, but a
// caller may check materials from several).
class SpinLock {
 public:
  explicit SpinLock(std::atomic_flag& flag) : flag_(flag) {
    while (flag_.test_and_set(std::memory_order_acquire)) {
    }
  }
  ~SpinLock() { flag_.clear(std::memory_order_release); }
  SpinLock(const SpinLock&) = delete;
  SpinLock& operator=(const SpinLock&) = delete;

 private:
  std::atomic_flag& flag_;
};

std::string angle_text(double degrees) {
  char text[32];
  std::snprintf(text, sizeof text, "%.0f°", degrees);
  return text;
}

}  // namespace

Rgb furnace_albedo(const Brdf& brdf, const Vec3& wo) {
  double sum[3] = {0, 0, 0};
  if (wo.z <= 0.0) return {};
  for (int i = 0; i < kCosineU; ++i)
    for (int j = 0; j < kCosineV; ++j)
      add(brdf, wo, detail::sample_cosine_direction((i + 0.5) / kCosineU, (j + 0.5) / kCosineV),
          sum);
  for (int i = 0; i < kHalfT; ++i) {
    const double t = (i + 0.5) / kHalfT;
    const double theta = numerics::kHalfPi * t * t;
    const double st = std::sin(theta), ct = std::cos(theta);
    for (int j = 0; j < kHalfS; ++j) {
      const double phi = numerics::kTwoPi * (j + 0.5) / kHalfS;
      const Vec3 h{st * std::cos(phi), st * std::sin(phi), ct};
      if (dot(wo, h) <= 0.0) continue;
      add(brdf, wo, reflect(wo, h), sum);
    }
  }
  return {sum[0], sum[1], sum[2]};
}

AlbedoPeak max_furnace_albedo(const Brdf& brdf, bool isotropic) {
  static const double kThetas[] = {0, 15, 30, 45, 55, 65, 70, 75, 80, 83, 85, 87, 89};
  static const double kPhis[] = {0, 45, 90, 135};
  AlbedoPeak peak;
  peak.albedo = -1.0;
  for (double phi : kPhis) {
    if (isotropic && phi != 0.0) break;
    for (double theta : kThetas) {
      const double t = theta * numerics::kPi / 180.0, p = phi * numerics::kPi / 180.0;
      const Vec3 wo{std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
      const Rgb a = furnace_albedo(brdf, wo);
      const double worst = std::max({a.r, a.g, a.b});
      if (worst > peak.albedo) peak = AlbedoPeak{worst, theta, phi};
    }
  }
  return peak;
}

Status check_energy_conservation(const Material& material) {
  if (material.model == MaterialModel::kGltf) return Status::Ok();  // the standard's own model
  if (material.lambertian()) return make_brdf(material).status();   // a = ρ ≤ 1 exactly
  static std::atomic_flag busy = ATOMIC_FLAG_INIT;
  static std::map<std::string, AlbedoPeak> merl_peaks;
  AlbedoPeak peak;
  bool cached = false;
  if (material.model == MaterialModel::kMerl) {
    const SpinLock lock(busy);
    const auto found = merl_peaks.find(material.merl_path);
    if (found != merl_peaks.end()) {
      peak = found->second;
      cached = true;
    }
  }
  if (!cached) {
    const Result<std::shared_ptr<const Brdf>> made = make_brdf(material);
    if (!made) return made.status();
    peak = max_furnace_albedo(*made.value(), material.isotropic());
    if (material.model == MaterialModel::kMerl) {
      const SpinLock lock(busy);
      merl_peaks[material.merl_path] = peak;
    }
  }
  if (peak.albedo <= 1.0 + kAlbedoTolerance) return Status::Ok();
  char ratio[32];
  std::snprintf(ratio, sizeof ratio, "%.3gx", peak.albedo);
  std::string where = angle_text(peak.theta_degrees);
  if (!material.isotropic()) where += " (azimuth " + angle_text(peak.phi_degrees) + ")";
  return Status::Error(describe(material) + " reflects " + ratio + " the light arriving at " +
                       where + ": directional albedo must not exceed 1");
}

}  // namespace prt::brdf
