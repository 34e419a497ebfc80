// report/src/sun_study.cpp — the numerics of report/sun_study.h: the sun disc, its exact exit
// radiance, the runtime path's error over a sphere of normals, the normal-incidence series, the
// decay fit and the memory of a transfer matrix.
#include "report/sun_study.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "numerics/constants.h"
#include "numerics/gauss_legendre.h"
#include "prt/glossy/brdf_projection.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"
#include "sh/zonal.h"

namespace prt::report {
namespace {

using brdf::Rgb;
using brdf::Vec3;
using numerics::kPi;

double dot3(const Vec3& a, const Vec3& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
Vec3 cross3(const Vec3& a, const Vec3& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
Vec3 normalized(const Vec3& a) {
  const double n = std::sqrt(dot3(a, a));
  return {a.x / n, a.y / n, a.z / n};
}
double channel(const Rgb& c, int k) {
  return k == 0 ? c.r : (k == 1 ? c.g : c.b);
}

// Panels on [0, π/2]: geometric near 0 (1e-4 · 2^k up to `uniform`), then uniform of width
// `uniform`; 8 nodes each. Resolves lobes centred at 0 and P_l up to l ≈ 1/uniform.
void graded_polar_rule(double uniform, std::vector<double>* x, std::vector<double>* w) {
  std::vector<double> edges{0.0};
  for (double e = 1e-4; e < uniform; e *= 2.0) edges.push_back(e);
  for (double e = uniform; e < kPi / 2 - 1e-12; e += uniform) edges.push_back(e);
  edges.push_back(kPi / 2);
  for (std::size_t k = 0; k + 1 < edges.size(); ++k)
    if (edges[k + 1] > edges[k]) numerics::append_gauss_legendre(8, edges[k], edges[k + 1], x, w);
}

// Legendre P_0..P_{n−1}(t) into p.
void legendre(int n, double t, double* p) {
  p[0] = 1.0;
  if (n > 1) p[1] = t;
  for (int l = 2; l < n; ++l) p[l] = ((2.0 * l - 1.0) * t * p[l - 1] - (l - 1.0) * p[l - 2]) / l;
}

// Accumulates squared errors and peaks per order.
struct ErrorSums {
  explicit ErrorSums(int orders) : err2(std::size_t(orders), 0.0), peak(std::size_t(orders), 0.0) {}
  void add_exact(double e, double weight) {
    exact2 += weight * e * e;
    exact_peak = std::max(exact_peak, std::fabs(e));
  }
  void add(int order_index, double diff, double weight) {
    err2[std::size_t(order_index)] += weight * diff * diff;
    peak[std::size_t(order_index)] = std::max(peak[std::size_t(order_index)], std::fabs(diff));
  }
  std::vector<OrderError> result() const {
    std::vector<OrderError> out;
    for (std::size_t k = 0; k < err2.size(); ++k)
      out.push_back({int(k) + 1, exact2 > 0 ? std::sqrt(err2[k] / exact2) : 0.0,
                     exact_peak > 0 ? peak[k] / exact_peak : 0.0});
    return out;
  }
  std::vector<double> err2, peak;
  double exact2 = 0, exact_peak = 0;
};

}  // namespace

double disc_solid_angle(double half_angle) {
  return 2.0 * kPi * (1.0 - std::cos(half_angle));
}

double disc_normal_irradiance(double half_angle, double radiance) {
  const double s = std::sin(half_angle);
  return radiance * kPi * s * s;
}

std::vector<double> disc_zonal_coefficients(int order, double half_angle, double radiance) {
  std::vector<double> p(std::size_t(order) + 1, 0.0), h(std::size_t(order), 0.0);
  const double c = std::cos(half_angle);
  legendre(order + 1, c, p.data());
  for (int l = 0; l < order; ++l) {
    const double integral =
        l == 0 ? 1.0 - c : (p[std::size_t(l) - 1] - p[std::size_t(l) + 1]) / (2.0 * l + 1.0);
    h[std::size_t(l)] = 2.0 * kPi * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * radiance * integral;
  }
  return h;
}

Rgb sun_exit_radiance(const brdf::Brdf& brdf, const Vec3& wo, const Vec3& sun, double half_angle,
                      double radiance, int rings, int sectors) {
  const Vec3 s = normalized(sun);
  const Vec3 helper = std::fabs(s.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
  const Vec3 e1 = normalized(cross3(helper, s)), e2 = cross3(s, e1);
  std::vector<double> u, wu;
  numerics::append_gauss_legendre(rings, std::cos(half_angle), 1.0, &u, &wu);
  double sum[3] = {0, 0, 0};
  for (std::size_t i = 0; i < u.size(); ++i) {
    const double r = std::sqrt(std::max(0.0, 1.0 - u[i] * u[i]));
    for (int k = 0; k < sectors; ++k) {
      const double phi = 2.0 * kPi * (k + 0.5) / sectors;
      const double a = r * std::cos(phi), b = r * std::sin(phi);
      const Vec3 wi{u[i] * s.x + a * e1.x + b * e2.x, u[i] * s.y + a * e1.y + b * e2.y,
                    u[i] * s.z + a * e1.z + b * e2.z};
      if (wi.z <= 0.0) continue;
      const Rgb f = brdf.eval(wi, wo);
      const double weight = wu[i] * (2.0 * kPi / sectors) * wi.z * radiance;
      for (int c = 0; c < 3; ++c) sum[c] += weight * channel(f, c);
    }
  }
  return Rgb{sum[0], sum[1], sum[2]};
}

std::vector<SunStudyMaterial> sun_study_materials(const std::vector<double>& ggx_alphas) {
  std::vector<SunStudyMaterial> out;
  brdf::Material lambert;
  lambert.diffuse = brdf::grey(0.8);
  out.push_back({"lambert", lambert});
  for (double alpha : ggx_alphas) {
    brdf::Material m;
    m.model = brdf::MaterialModel::kMicrofacet;
    m.distribution = brdf::NormalDistribution::kGgx;
    m.fresnel = brdf::FresnelMode::kSchlick;
    m.specular = brdf::grey(0.95);
    m.diffuse = brdf::grey(0.0);
    m.alpha_x = m.alpha_y = alpha;
    char name[48];
    std::snprintf(name, sizeof name, "ggx_a%g", alpha);
    out.push_back({name, m});
  }
  const scene::Scene glossy = scene::make_glossy_scene();
  for (const char* wanted : {"glossy_red", "brushed_steel", "rough_gold"})
    for (const scene::ScenePrimitive& p : glossy.primitives)
      if (p.material == wanted && p.brdf) {
        out.push_back({wanted, *p.brdf});
        break;
      }
  return out;
}

SunSphereSetup default_sun_setup(double sky_fraction, int sun_count) {
  SunSphereSetup s;
  s.half_angle = 0.5 * kSunAngularDiameterDegrees * kPi / 180.0;
  s.sun_radiance = 1.0 / disc_normal_irradiance(s.half_angle, 1.0);  // E = 1 facing the sun
  s.sky = sky_fraction / kPi;
  for (int theta : {0, 30, 60, 80})
    for (int phi : {0, 90}) {
      if (theta == 0 && phi > 0) continue;
      const double t = theta * kPi / 180.0, p = phi * kPi / 180.0;
      s.views.push_back({std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)});
      s.view_names.push_back("theta_o_" + std::to_string(theta) + "_phi_o_" + std::to_string(phi));
    }
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < sun_count; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / sun_count, r = std::sqrt(1.0 - z * z);
    s.suns.push_back({r * std::cos(golden * k), r * std::sin(golden * k), z});
  }
  return s;
}

BrdfProjectionOptions sun_study_projection_options() {
  BrdfProjectionOptions o;
  o.table_size = 19;
  o.table_nodes = 32;
  return o;
}

std::vector<OrderError> sphere_errors(const brdf::Material& material, const SunSphereSetup& setup,
                                      int max_order, const BrdfProjectionOptions& options,
                                      std::vector<std::vector<OrderError>>* per_view) {
  Result<BrdfProjection> projection = BrdfProjection::create(material, max_order, options);
  if (!projection) throw std::runtime_error("sun study: " + projection.status().message());
  Result<std::shared_ptr<const brdf::Brdf>> made = brdf::make_brdf(material);
  if (!made) throw std::runtime_error("sun study: " + made.status().message());
  const brdf::Brdf& f = **made;
  const std::size_t n2 = std::size_t(max_order) * std::size_t(max_order);
  const std::vector<double> sun_zonal =
      disc_zonal_coefficients(max_order, setup.half_angle, setup.sun_radiance);
  const double sky_sh0 = setup.sky * std::sqrt(4.0 * kPi);
  std::vector<std::vector<double>> b(setup.views.size(), std::vector<double>(3 * n2));
  for (std::size_t k = 0; k < setup.views.size(); ++k)
    projection->evaluate(setup.views[k], b[k].data());
  std::vector<double> sun_sh(n2);
  ErrorSums sums(max_order);
  std::vector<ErrorSums> view_sums(setup.views.size(), ErrorSums(max_order));
  for (const Vec3& sun : setup.suns) {
    sh::rotate_zonal(max_order, sun_zonal.data(), sun.x, sun.y, sun.z, sun_sh.data());
    sun_sh[0] += sky_sh0;
    for (std::size_t k = 0; k < setup.views.size(); ++k) {
      const Rgb sun_exact =
          sun_exit_radiance(f, setup.views[k], sun, setup.half_angle, setup.sun_radiance);
      for (int c = 0; c < 3; ++c) {
        const double* bc = b[k].data() + std::size_t(c) * n2;
        // The sky's share, the same on both sides: b_0 · its only coefficient.
        const double exact = channel(sun_exact, c) + bc[0] * sky_sh0;
        double approx = 0.0;
        sums.add_exact(exact, 1.0);
        view_sums[k].add_exact(exact, 1.0);
        for (int l = 0; l < max_order; ++l) {
          for (int i = l * l; i < (l + 1) * (l + 1); ++i) approx += bc[i] * sun_sh[std::size_t(i)];
          sums.add(l, approx - exact, 1.0);
          view_sums[k].add(l, approx - exact, 1.0);
        }
      }
    }
  }
  if (per_view) {
    per_view->clear();
    for (const ErrorSums& v : view_sums) per_view->push_back(v.result());
  }
  return sums.result();
}

std::vector<OrderError> normal_incidence_errors(const brdf::Brdf& brdf, double half_angle,
                                                int max_order) {
  const double uniform = std::min(0.01, 4.0 / max_order);
  std::vector<double> x, w;
  graded_polar_rule(uniform, &x, &w);
  std::vector<double> p(static_cast<std::size_t>(max_order));
  // b_l0 per channel: 2π √((2l+1)/4π) ∫ f(θ) cos θ P_l(cos θ) sin θ dθ.
  std::vector<double> b(std::size_t(3 * max_order), 0.0);
  const Vec3 wo{0, 0, 1};
  for (std::size_t k = 0; k < x.size(); ++k) {
    const Vec3 wi{std::sin(x[k]), 0.0, std::cos(x[k])};
    const Rgb f = brdf.eval(wi, wo);
    legendre(max_order, wi.z, p.data());
    for (int c = 0; c < 3; ++c) {
      const double s = 2.0 * kPi * w[k] * channel(f, c) * wi.z * wi.x;
      for (int l = 0; l < max_order; ++l)
        b[std::size_t(c * max_order + l)] += s * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi)) * p[l];
    }
  }
  const double radiance = 1.0 / disc_normal_irradiance(half_angle, 1.0);
  const std::vector<double> h = disc_zonal_coefficients(max_order, half_angle, radiance);
  ErrorSums sums(max_order);
  for (std::size_t k = 0; k < x.size(); ++k) {
    const double weight = w[k] * std::sin(x[k]);
    const Vec3 sun{std::sin(x[k]), 0.0, std::cos(x[k])};
    const Rgb exact = sun_exit_radiance(brdf, wo, sun, half_angle, radiance);
    legendre(max_order, sun.z, p.data());
    for (int c = 0; c < 3; ++c) {
      sums.add_exact(channel(exact, c), weight);
      double approx = 0.0;
      for (int l = 0; l < max_order; ++l) {
        approx += b[std::size_t(c * max_order + l)] * h[std::size_t(l)] * p[std::size_t(l)];
        sums.add(l, approx - channel(exact, c), weight);
      }
    }
  }
  return sums.result();
}

int direct_needed_order(const std::vector<OrderError>& errors, double target) {
  int needed = 0;
  for (auto it = errors.rbegin(); it != errors.rend(); ++it) {
    if (!(it->rms <= target)) break;
    needed = it->order;
  }
  return needed;
}

double DecayFit::error_at(int order) const {
  const double x = exponential ? double(order) : std::log(double(order));
  return std::exp(a + b * x);
}

int DecayFit::order_for(double target) const {
  if (!(b < 0.0) || !(target > 0.0)) return 0;
  const double x = (std::log(target) - a) / b;
  const double n = exponential ? x : std::exp(x);
  if (!(n < 1e7)) return 0;
  return std::max(1, int(std::ceil(n - 1e-9)));
}

DecayFit fit_decay(const std::vector<OrderError>& errors) {
  const int last = errors.empty() ? 0 : errors.back().order;
  DecayFit best;
  best.residual = std::numeric_limits<double>::infinity();
  for (bool exponential : {true, false}) {
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    int count = 0, first = 0;
    for (const OrderError& e : errors) {
      if (2 * e.order < last || !(e.rms > 0.0)) continue;
      const double x = exponential ? double(e.order) : std::log(double(e.order));
      const double y = std::log(e.rms);
      sx += x, sy += y, sxx += x * x, sxy += x * y, ++count;
      if (first == 0) first = e.order;
    }
    if (count < 2) continue;
    DecayFit fit;
    fit.exponential = exponential;
    fit.b = (count * sxy - sx * sy) / (count * sxx - sx * sx);
    fit.a = (sy - fit.b * sx) / count;
    fit.first_order = first;
    fit.last_order = last;
    double r = 0;
    for (const OrderError& e : errors) {
      if (2 * e.order < last || !(e.rms > 0.0)) continue;
      const double d = std::log(fit.error_at(e.order)) - std::log(e.rms);
      r += d * d;
    }
    fit.residual = std::sqrt(r / count);
    if (fit.residual < best.residual) best = fit;
  }
  return best;
}

double transfer_matrix_bytes(int order, int bytes_per_value) {
  const double n2 = double(order) * order;
  return n2 * n2 * bytes_per_value;
}

int largest_fitting_order(double vertices, int bytes_per_value, double budget_bytes) {
  int n = 0;
  while (n < 100000 && vertices * transfer_matrix_bytes(n + 1, bytes_per_value) <= budget_bytes)
    ++n;
  return n;
}

}  // namespace prt::report
