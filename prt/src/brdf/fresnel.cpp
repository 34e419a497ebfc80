// Fresnel reflectance.
#include "prt/brdf/fresnel.h"

#include <algorithm>
#include <cmath>

namespace prt::brdf {

double fresnel_dielectric(double cos_i, double eta) {
  cos_i = std::clamp(cos_i, 0.0, 1.0);
  const double sin2_t = (1.0 - cos_i * cos_i) / (eta * eta);  // Snell
  if (sin2_t >= 1.0) return 1.0;                              // total internal reflection
  const double cos_t = std::sqrt(1.0 - sin2_t);
  const double rs = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
  const double rp = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
  return 0.5 * (rs * rs + rp * rp);
}

double fresnel_f0(double eta) {
  const double r = (eta - 1.0) / (eta + 1.0);
  return r * r;
}

double fresnel_schlick(double cos_i, double f0) {
  const double m = 1.0 - std::clamp(cos_i, 0.0, 1.0);
  const double m2 = m * m;
  return f0 + (1.0 - f0) * m2 * m2 * m;
}

}  // namespace prt::brdf
