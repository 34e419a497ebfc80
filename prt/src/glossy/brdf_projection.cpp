// prt/src/glossy/brdf_projection.cpp — b(ωo) by direct quadrature, by zonal lobes about the mirror
// direction, and by the view-side SH matrix (prt/glossy/brdf_projection.h).
#include "prt/glossy/brdf_projection.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>

#include "glossy/hemisphere_rules.h"
#include "numerics/constants.h"
#include "sh/basis.h"
#include "sh/zonal.h"

namespace prt {
namespace {
using numerics::kPi;

using brdf::Rgb;
using brdf::Vec3;

double channel(const Rgb& c, int k) {
  return k == 0 ? c.r : (k == 1 ? c.g : c.b);
}

// The BRDF without an additive Lambert term: f − ρ/π (where f itself is non-zero).
class WithoutLambert final : public brdf::Brdf {
 public:
  WithoutLambert(std::shared_ptr<const brdf::Brdf> f, const Rgb& rho) : f_(std::move(f)) {
    rho_over_pi_ = (1.0 / kPi) * rho;
  }
  Rgb eval(const Vec3& wi, const Vec3& wo) const override {
    if (wi.z <= 0.0 || wo.z <= 0.0) return {};
    const Rgb v = f_->eval(wi, wo);
    return {v.r - rho_over_pi_.r, v.g - rho_over_pi_.g, v.b - rho_over_pi_.b};
  }
  brdf::BrdfSample sample(const Vec3& wo, double u1, double u2) const override {
    return f_->sample(wo, u1, u2);
  }
  double pdf(const Vec3& wo, const Vec3& wi) const override { return f_->pdf(wo, wi); }
  bool reciprocal() const override { return f_->reciprocal(); }

 private:
  std::shared_ptr<const brdf::Brdf> f_;
  Rgb rho_over_pi_;
};

// Unit ωo from any vector; false (b = 0) when it is below the horizon, zero or not finite.
bool usable_view(const Vec3& wo, Vec3* unit) {
  const double len = length(wo);
  if (!(len > 0.0) || !std::isfinite(len)) return false;
  *unit = (1.0 / len) * wo;
  return unit->z > 0.0;
}

// Float copy for the kernel; magnitudes below 1e-30 become 0, so no subnormal float (slow on
// x86) reaches the shading loops.
std::vector<float> to_float(const std::vector<double>& v) {
  std::vector<float> out(v.size());
  for (std::size_t k = 0; k < v.size(); ++k) out[k] = std::fabs(v[k]) < 1e-30 ? 0.f : float(v[k]);
  return out;
}

// Legendre P_0..P_{n−1}(t) · √((2l+1)/4π): the zonal basis function Y_l0 about an axis at
// angle arccos t.
void zonal_basis(int n, double t, double* out) {
  double p0 = 1.0, p1 = t;
  for (int l = 0; l < n; ++l) {
    double p = l == 0 ? 1.0 : (l == 1 ? t : 0.0);
    if (l >= 2) {
      p = ((2.0 * l - 1.0) * t * p1 - (l - 1.0) * p0) / l;
      p0 = p1;
      p1 = p;
    }
    out[l] = p * std::sqrt((2.0 * l + 1.0) / (4.0 * kPi));
  }
}

}  // namespace

Status project_brdf_slice(const brdf::Brdf& f, int order, const Vec3& wo,
                          const SliceQuadrature& quadrature, double* out) {
  if (order < 1 || order > kMaxBrdfProjectionOrder)
    return Status::Error("BRDF projection: order " + std::to_string(order) + " is outside [1, " +
                         std::to_string(kMaxBrdfProjectionOrder) + "]");
  if (out == nullptr) return Status::Error("BRDF projection: null output");
  if (quadrature.nodes_per_panel < 2 || quadrature.nodes_per_panel > 64)
    return Status::Error("BRDF projection: nodes per panel outside [2, 64]");
  const int n2 = order * order;
  std::fill(out, out + 3 * n2, 0.0);
  Vec3 v;
  if (!usable_view(wo, &v)) return Status::Ok();
  const Vec3 mirror{-v.x, -v.y, v.z};
  std::vector<double> y(std::size_t(n2), 0.0);
  for (const glossy::HemisphereNode& node :
       glossy::graded_hemisphere_rule(mirror, quadrature.nodes_per_panel)) {
    const Rgb value = f.eval(node.w, v);
    const double w = node.weight * node.w.z;
    if (w == 0.0 || (value.r == 0.0 && value.g == 0.0 && value.b == 0.0)) continue;
    sh::evaluate(order, node.w.x, node.w.y, node.w.z, y.data());
    for (int c = 0; c < 3; ++c) {
      const double s = w * channel(value, c);
      double* row = out + c * n2;
      for (int i = 0; i < n2; ++i) row[i] += s * y[std::size_t(i)];
    }
  }
  return Status::Ok();
}

struct BrdfProjection::Impl {
  BrdfProjectionMethod method = BrdfProjectionMethod::kZonal;
  int order = 1;
  int view_order = 0;
  // kZonal: ρ_d/π · z_l (diffuse, per channel) and the table of glossy zonal coefficients,
  // pre-multiplied by √(4π/(2l+1)): table[(t · 3 + c) · order + l] at cos θo = t / (T − 1).
  double diffuse[3][kMaxBrdfProjectionOrder] = {};
  int table_size = 0;
  std::vector<double> table;
  std::vector<float> table_f;
  float diffuse_f[3][kMaxBrdfProjectionOrder] = {};
  // kIsotropicTable: b(θo, 0) at θo = t/(T − 1)·π/2: iso[t · 3n² + c·n² + i].
  int iso_size = 0;
  std::vector<double> iso;
  std::vector<float> iso_f;
  // kMatrix: B_c,ij over the even j only: matrix[(c · n² + i) · E + e], e indexing even_j.
  std::vector<int> even_j;
  std::vector<double> matrix;
  std::vector<float> matrix_f;
  // The float tables hold the same values in the three channels (a grey material): the float
  // evaluate() computes channel 0 and copies it.
  bool grey_f = false;
};

namespace {

// The table node at the horizon (cos θo = 0) is the limit of b as the view approaches the
// horizon, not b at the horizon (zero: the BRDFs are one-sided). b has a finite, nonzero limit
// for a Lambert layer and for microfacet lobes with Smith masking, so a zero node would pull
// every view within one table step of the horizon towards 0 (measured: 60% low 0.4° above it).
// The limit is extrapolated linearly from the two nearest nodes rather than evaluated near
// cos θo = 0, where the original Ward form diverges as 1/√cos θo. `table` holds `size` nodes of
// `stride` values; the horizon node is the first (`horizon_first`) or the last.
void extrapolate_horizon_node(std::vector<double>* table, std::size_t stride, int size,
                              bool horizon_first) {
  if (size < 3) return;
  const std::size_t h = horizon_first ? 0 : std::size_t(size - 1);
  const std::size_t a = horizon_first ? 1 : std::size_t(size - 2);
  const std::size_t b = horizon_first ? 2 : std::size_t(size - 3);
  for (std::size_t k = 0; k < stride; ++k)
    (*table)[h * stride + k] = 2.0 * (*table)[a * stride + k] - (*table)[b * stride + k];
}

// g_c,l(cos θo) of the glossy part, by the graded rule about the mirror direction.
void fill_zonal_table(const brdf::Brdf& glossy, BrdfProjection::Impl* p, int table_size) {
  const int n = p->order;
  p->table_size = table_size;
  p->table.assign(std::size_t(table_size) * 3 * n, 0.0);
  std::vector<double> zb(std::size_t(n), 0.0);
  for (int t = 1; t < table_size; ++t) {
    const double c = double(t) / (table_size - 1), s = std::sqrt(std::max(0.0, 1.0 - c * c));
    const Vec3 wo{s, 0.0, c}, mirror{-s, 0.0, c};
    double* g = &p->table[std::size_t(t) * 3 * n];
    for (const glossy::HemisphereNode& node : glossy::graded_hemisphere_rule(mirror, 10)) {
      const Rgb value = glossy.eval(node.w, wo);
      const double w = node.weight * node.w.z;
      zonal_basis(n, dot(node.w, mirror), zb.data());
      for (int k = 0; k < 3; ++k)
        for (int l = 0; l < n; ++l) g[k * n + l] += w * channel(value, k) * zb[std::size_t(l)];
    }
    for (int k = 0; k < 3; ++k)
      for (int l = 0; l < n; ++l) g[k * n + l] *= std::sqrt(4.0 * kPi / (2.0 * l + 1.0));
  }
  extrapolate_horizon_node(&p->table, 3 * std::size_t(n), table_size, /*horizon_first=*/true);
}

// b(θo, 0) by the reference quadrature at each tabulated elevation.
Status fill_isotropic_table(const brdf::Brdf& f, const BrdfProjectionOptions& o,
                            BrdfProjection::Impl* p) {
  const std::size_t n2 = std::size_t(p->order) * p->order;
  p->iso_size = o.table_size;
  p->iso.assign(std::size_t(o.table_size) * 3 * n2, 0.0);
  for (int t = 0; t < o.table_size; ++t) {
    const double theta = 0.5 * kPi * t / (o.table_size - 1);
    const Vec3 wo{std::sin(theta), 0.0, std::cos(theta)};
    if (!(wo.z > 1e-12)) continue;  // the horizon node: extrapolated below
    if (Status s = project_brdf_slice(f, p->order, wo, {o.table_nodes}, &p->iso[t * 3 * n2]); !s)
      return s;
  }
  extrapolate_horizon_node(&p->iso, 3 * n2, o.table_size, /*horizon_first=*/false);
  p->iso_f = to_float(p->iso);
  return Status::Ok();
}

// The symmetry class of y_k under the reflections y → −y and x → −x of the local frame:
// bit 0 set when y_k changes sign under y → −y (m < 0), bit 1 when it does under x → −x
// ((−1)^m for m ≥ 0, −(−1)^|m| for m < 0; basis of sh/basis.h, no Condon–Shortley phase).
int reflection_class(int k) {
  int l = 0;
  while ((l + 1) * (l + 1) <= k) ++l;
  const int m = k - l * (l + 1), am = m < 0 ? -m : m;
  const bool odd_y = m < 0;
  const bool odd_x = m < 0 ? am % 2 == 0 : am % 2 == 1;
  return (odd_y ? 1 : 0) | (odd_x ? 2 : 0);
}

// B_c,ij = 2 ∫_{H+} b_c,i(ωo) y_j(ωo) dωo for even j (the even extension across the horizon).
// `orthotropic`: f is unchanged when ωi and ωo are both reflected by y → −y or by x → −x (every
// analytic model of prt/brdf: α_x, α_y enter through h_x², h_y²). With both φ rules symmetric
// under those reflections (node counts multiples of 4, offset by half a step), b at a reflected
// view is b with the signs of its classes, so each view of the first φ quadrant stands for its
// four images: the images' terms sum to 4× when y_i and y_j share a class and cancel otherwise
// (the characters of the group {1, Y, X, XY}). Same sums, a quarter of the BRDF evaluations.
void fill_matrix(const brdf::Brdf& f, const BrdfProjectionOptions& o, bool orthotropic,
                 BrdfProjection::Impl* p) {
  const int n2 = p->order * p->order, m = p->view_order;
  for (int l = 0; l < m; ++l)
    for (int mm = -l; mm <= l; ++mm)
      if ((l + mm) % 2 == 0) p->even_j.push_back(sh::index(l, mm));
  const std::size_t e_count = p->even_j.size();
  const std::vector<glossy::HemisphereNode> inner =
      glossy::product_hemisphere_rule(o.inner_theta, o.inner_phi);
  const int outer_theta = o.outer_theta > 0 ? o.outer_theta : 2 * m + 8;
  const int outer_phi = o.outer_phi > 0 ? o.outer_phi : 4 * m + 8;
  const std::vector<glossy::HemisphereNode> outer =
      glossy::product_hemisphere_rule(outer_theta, outer_phi);
  const bool mirror = orthotropic && outer_phi % 4 == 0 && o.inner_phi % 4 == 0;
  std::vector<int> class_i(static_cast<std::size_t>(n2)), class_e(e_count);
  for (int i = 0; i < n2; ++i) class_i[std::size_t(i)] = reflection_class(i);
  for (std::size_t e = 0; e < e_count; ++e) class_e[e] = reflection_class(p->even_j[e]);
  std::vector<double> y_in(inner.size() * std::size_t(n2));
  for (std::size_t k = 0; k < inner.size(); ++k)
    sh::evaluate(p->order, inner[k].w.x, inner[k].w.y, inner[k].w.z, &y_in[k * n2]);
  std::vector<double> y_out(std::size_t(m) * m), b(3 * std::size_t(n2));
  p->matrix.assign(3 * std::size_t(n2) * e_count, 0.0);
  for (std::size_t v = 0; v < outer.size(); ++v) {
    if (mirror && int(v % std::size_t(outer_phi)) >= outer_phi / 4) continue;
    const glossy::HemisphereNode& view = outer[v];
    std::fill(b.begin(), b.end(), 0.0);
    for (std::size_t k = 0; k < inner.size(); ++k) {
      const Rgb value = f.eval(inner[k].w, view.w);
      if (value.r == 0.0 && value.g == 0.0 && value.b == 0.0) continue;
      const double w = inner[k].weight * inner[k].w.z;
      const double* y = &y_in[k * n2];
      for (int c = 0; c < 3; ++c) {
        const double s = w * channel(value, c);
        for (int i = 0; i < n2; ++i) b[std::size_t(c * n2 + i)] += s * y[i];
      }
    }
    sh::evaluate(m, view.w.x, view.w.y, view.w.z, y_out.data());
    for (std::size_t r = 0; r < b.size(); ++r) {
      double* row = &p->matrix[r * e_count];
      if (!mirror) {
        const double s = 2.0 * view.weight * b[r];
        for (std::size_t e = 0; e < e_count; ++e) row[e] += s * y_out[std::size_t(p->even_j[e])];
        continue;
      }
      const double s = 8.0 * view.weight * b[r];  // 2 × the four images
      const int ci = class_i[r % std::size_t(n2)];
      for (std::size_t e = 0; e < e_count; ++e)
        if (class_e[e] == ci) row[e] += s * y_out[std::size_t(p->even_j[e])];
    }
  }
}

// b_c,l0 = ρ_c/π · z_l of the clamped cosine about the normal (exact).
void set_diffuse(const Rgb& rho, BrdfProjection::Impl* p) {
  for (int c = 0; c < 3; ++c)
    for (int l = 0; l < p->order; ++l) {
      p->diffuse[c][l] = channel(rho, c) / kPi * sh::clamped_cosine_zonal_coefficient(l);
      p->diffuse_f[c][l] = float(p->diffuse[c][l]);
    }
}

// True when the float tables give the same b in the three channels (bitwise), so the float
// evaluate() may compute one channel and copy it. Layouts as in Impl: [outer][c][inner].
bool same_channels(const std::vector<float>& v, std::size_t inner) {
  for (std::size_t o = 0; o + 3 * inner <= v.size(); o += 3 * inner)
    if (std::memcmp(&v[o], &v[o + inner], inner * sizeof(float)) != 0 ||
        std::memcmp(&v[o], &v[o + 2 * inner], inner * sizeof(float)) != 0)
      return false;
  return true;
}

bool grey_tables(const BrdfProjection::Impl& p) {
  const std::size_t n = std::size_t(p.order), n2 = n * n;
  switch (p.method) {
    case BrdfProjectionMethod::kIsotropicTable:
      return same_channels(p.iso_f, n2);
    case BrdfProjectionMethod::kMatrix:
      return same_channels(p.matrix_f, n2 * p.even_j.size());
    default:
      return same_channels(p.table_f, n) &&
             std::memcmp(p.diffuse_f[0], p.diffuse_f[1], sizeof p.diffuse_f[0]) == 0 &&
             std::memcmp(p.diffuse_f[0], p.diffuse_f[2], sizeof p.diffuse_f[0]) == 0;
  }
}

Status check_options(int order, const BrdfProjectionOptions& o) {
  const auto out_of = [](int v, int lo, int hi) { return v < lo || v > hi; };
  if (out_of(order, 1, kMaxBrdfProjectionOrder))
    return Status::Error("BRDF projection: order " + std::to_string(order) + " is outside [1, " +
                         std::to_string(kMaxBrdfProjectionOrder) + "]");
  if (o.view_order != 0 && out_of(o.view_order, 1, kMaxBrdfProjectionOrder))
    return Status::Error("BRDF projection: view order " + std::to_string(o.view_order) +
                         " is outside [1, " + std::to_string(kMaxBrdfProjectionOrder) + "]");
  if (out_of(o.zonal_table, 2, 65536) || out_of(o.table_size, 2, 65536) ||
      out_of(o.table_nodes, 2, 64))
    return Status::Error("BRDF projection: table size or table nodes out of range");
  if (out_of(o.inner_theta, 8, 4096) || out_of(o.inner_phi, 8, 4096))
    return Status::Error("BRDF projection: inner quadrature size outside [8, 4096]");
  if ((o.outer_theta != 0 && out_of(o.outer_theta, 4, 4096)) ||
      (o.outer_phi != 0 && out_of(o.outer_phi, 4, 4096)))
    return Status::Error("BRDF projection: outer quadrature size outside [4, 4096]");
  return Status::Ok();
}

}  // namespace

BrdfProjection::BrdfProjection() : impl_(std::make_unique<Impl>()) {}
BrdfProjection::BrdfProjection(BrdfProjection&&) noexcept = default;
BrdfProjection& BrdfProjection::operator=(BrdfProjection&&) noexcept = default;
BrdfProjection::BrdfProjection(const BrdfProjection& other)
    : impl_(std::make_unique<Impl>(*other.impl_)) {}
BrdfProjection& BrdfProjection::operator=(const BrdfProjection& other) {
  if (this != &other) impl_ = std::make_unique<Impl>(*other.impl_);
  return *this;
}
BrdfProjection::~BrdfProjection() = default;

int BrdfProjection::order() const {
  return impl_->order;
}
int BrdfProjection::view_order() const {
  return impl_->view_order;
}
BrdfProjectionMethod BrdfProjection::method() const {
  return impl_->method;
}

Result<BrdfProjection> BrdfProjection::create(std::shared_ptr<const brdf::Brdf> f, int order,
                                              const Rgb& lambert_part,
                                              const BrdfProjectionOptions& options) {
  return create_impl(std::move(f), order, lambert_part, options, /*orthotropic=*/false);
}

Result<BrdfProjection> BrdfProjection::create_impl(std::shared_ptr<const brdf::Brdf> f, int order,
                                                   const Rgb& lambert_part,
                                                   const BrdfProjectionOptions& options,
                                                   bool orthotropic) {
  if (Status s = check_options(order, options); !s) return s;
  if (!f) return Status::Error("BRDF projection: null BRDF");
  BrdfProjection out;
  Impl* p = out.impl_.get();
  p->order = order;
  p->method = options.method == BrdfProjectionMethod::kAuto ? BrdfProjectionMethod::kMatrix
                                                            : options.method;
  if (p->method == BrdfProjectionMethod::kIsotropicTable) {
    if (Status s = fill_isotropic_table(*f, options, p); !s) return s;
  } else if (p->method == BrdfProjectionMethod::kMatrix) {
    p->view_order = options.view_order > 0 ? options.view_order : std::min(order + 6, 32);
    fill_matrix(*f, options, orthotropic, p);
    p->matrix_f = to_float(p->matrix);
  } else {
    set_diffuse(lambert_part, p);
    const WithoutLambert glossy(std::move(f), lambert_part);
    fill_zonal_table(glossy, p, options.zonal_table);
    p->table_f = to_float(p->table);
  }
  p->grey_f = grey_tables(*p);
  return out;
}

Result<BrdfProjection> BrdfProjection::create(const brdf::Material& material, int order,
                                              const BrdfProjectionOptions& options) {
  if (Status s = check_options(order, options); !s) return s;
  const bool zonal_ok = material.isotropic() && material.model != brdf::MaterialModel::kMerl;
  BrdfProjectionOptions o = options;
  if (o.method == BrdfProjectionMethod::kAuto)
    o.method = material.lambertian()  ? BrdfProjectionMethod::kZonal
               : material.isotropic() ? BrdfProjectionMethod::kIsotropicTable
                                      : BrdfProjectionMethod::kMatrix;
  if (o.method == BrdfProjectionMethod::kZonal && !zonal_ok)
    return Status::Error(
        "BRDF projection: the zonal approximation needs an isotropic analytic "
        "material, not " +
        brdf::describe(material));
  if (o.method == BrdfProjectionMethod::kIsotropicTable && !material.isotropic())
    return Status::Error("BRDF projection: the isotropic table needs an isotropic material, not " +
                         brdf::describe(material));
  Result<std::shared_ptr<const brdf::Brdf>> f = brdf::make_brdf(material);
  if (!f) return f.status();
  // Every analytic model is orthotropic in the local frame (fill_matrix); MERL is isotropic
  // but not trusted to be tabulated symmetrically.
  if (o.method != BrdfProjectionMethod::kZonal)
    return create_impl(std::move(f).value(), order, brdf::grey(0.0), o,
                       material.model != brdf::MaterialModel::kMerl);
  if (material.lambertian()) {  // no glossy part: no table, b is the exact diffuse part
    BrdfProjection out;
    out.impl_->order = order;
    set_diffuse(material.diffuse, out.impl_.get());
    out.impl_->grey_f = grey_tables(*out.impl_);
    return out;
  }
  // glTF's diffuse layer is weighted by 1 − F(ωo·h): its Lambert part is taken at F = F0.
  const brdf::Rgb lambert_part =
      material.model == brdf::MaterialModel::kGltf
          ? brdf::Rgb{(1.0 - material.metallic) * (1.0 - material.specular.r) * material.diffuse.r,
                      (1.0 - material.metallic) * (1.0 - material.specular.g) * material.diffuse.g,
                      (1.0 - material.metallic) * (1.0 - material.specular.b) * material.diffuse.b}
          : material.diffuse;
  return create(std::move(f).value(), order, lambert_part, o);
}

}  // namespace prt

namespace prt {
namespace {

// Zonal path: b_c,lm = g_c,l(cos θo) · Y_lm(R) + δ_m0 · diffuse_c,l. `y` holds order² values.
template <class T>
void evaluate_zonal(const BrdfProjection::Impl& p, const T* table,
                    const T (*diffuse)[kMaxBrdfProjectionOrder], T x, T y_, T z, T* y, T* out,
                    int channels = 3) {
  const int n = p.order, n2 = n * n;
  std::fill(out, out + channels * n2, T(0));
  if (p.table_size >= 2) {
    sh::evaluate(n, -x, -y_, z, y);
    const T position = z * T(p.table_size - 1);
    const int t0 = std::min(int(position), p.table_size - 2);
    const T a = position - T(t0);
    const T* g0 = table + std::size_t(t0) * 3 * n;
    const T* g1 = g0 + 3 * n;
    for (int c = 0; c < channels; ++c)
      for (int l = 0; l < n; ++l) {
        const T g = g0[c * n + l] + a * (g1[c * n + l] - g0[c * n + l]);
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) out[c * n2 + k] = g * y[k];
      }
  }
  for (int c = 0; c < channels; ++c)
    for (int l = 0; l < n; ++l) out[c * n2 + l * (l + 1)] += diffuse[c][l];
}

// Matrix path: b_c,i = Σ_e B_c,i,e · y_{j_e}(ωo). `y` holds view_order² + E values.
template <class T>
void evaluate_matrix(const BrdfProjection::Impl& p, const T* matrix, T x, T y_, T z, T* y, T* out,
                     int channels = 3) {
  const int n2 = p.order * p.order, m2 = p.view_order * p.view_order;
  const std::size_t e_count = p.even_j.size();
  sh::evaluate(p.view_order, x, y_, z, y);
  T* even = y + m2;
  for (std::size_t e = 0; e < e_count; ++e) even[e] = y[p.even_j[e]];
  for (int r = 0; r < channels * n2; ++r) {
    const T* row = matrix + std::size_t(r) * e_count;
    T sum = 0;
    for (std::size_t e = 0; e < e_count; ++e) sum += row[e] * even[e];
    out[r] = sum;
  }
}

// Rotates order-n coefficients (3 channels) about +z by the azimuth of (x, y) in place: for m > 0
// (c, s) = (coefficient of Y_l,m, of Y_l,−m) → (c cos mα − s sin mα, c sin mα + s cos mα).
template <class T>
void rotate_about_z(int n, T x, T y, T* out, int channels = 3) {
  const T r = std::sqrt(x * x + y * y);
  if (!(r > T(0))) return;
  const T c1 = x / r, s1 = y / r;
  const int n2 = n * n;
  T cm = 1, sm = 0;
  for (int m = 1; m < n; ++m) {
    const T next_c = cm * c1 - sm * s1, next_s = sm * c1 + cm * s1;
    cm = next_c;
    sm = next_s;
    for (int l = m; l < n; ++l)
      for (int ch = 0; ch < channels; ++ch) {
        T* b = out + ch * n2;
        const T a = b[sh::index(l, m)], s = b[sh::index(l, -m)];
        b[sh::index(l, m)] = a * cm - s * sm;
        b[sh::index(l, -m)] = a * sm + s * cm;
      }
  }
}

// Table path: b(θo, 0) interpolated in θo, then rotated about +z by φo.
template <class T>
void evaluate_table(const BrdfProjection::Impl& p, const T* table, T x, T y, T z, T* out,
                    int channels = 3) {
  const int n2 = p.order * p.order;
  const T theta = std::acos(std::min(z, T(1)));
  const T position = theta / T(0.5 * kPi) * T(p.iso_size - 1);
  const int t0 = std::min(int(position), p.iso_size - 2);
  const T a = position - T(t0);
  const T* b0 = table + std::size_t(t0) * 3 * n2;
  const T* b1 = b0 + 3 * n2;
  for (int k = 0; k < channels * n2; ++k) out[k] = b0[k] + a * (b1[k] - b0[k]);
  rotate_about_z(p.order, x, y, out, channels);
}

}  // namespace

std::size_t BrdfProjection::scratch_floats() const {
  return std::size_t(impl_->order) * impl_->order +
         std::size_t(impl_->view_order) * impl_->view_order + impl_->even_j.size();
}

void BrdfProjection::evaluate(const Vec3& wo, double* out) const {
  const Impl& p = *impl_;
  Vec3 v;
  if (!usable_view(wo, &v)) {
    std::fill(out, out + 3 * p.order * p.order, 0.0);
    return;
  }
  std::vector<double> y(scratch_floats());
  if (p.method == BrdfProjectionMethod::kIsotropicTable)
    evaluate_table(p, p.iso.data(), v.x, v.y, v.z, out);
  else if (p.method == BrdfProjectionMethod::kMatrix)
    evaluate_matrix(p, p.matrix.data(), v.x, v.y, v.z, y.data(), out);
  else
    evaluate_zonal(p, p.table.data(), p.diffuse, v.x, v.y, v.z, y.data(), out);
}

namespace {

// The float b of `channels` (1: channel 0 only; 3: all, the grey shortcut included).
void evaluate_float(const BrdfProjection::Impl& p, const float wo[3], float* out, float* scratch,
                    int channels) {
  const float len2 = wo[0] * wo[0] + wo[1] * wo[1] + wo[2] * wo[2];
  if (!(len2 > 0.f) || !std::isfinite(len2) || !(wo[2] > 0.f)) {
    std::fill(out, out + channels * p.order * p.order, 0.f);
    return;
  }
  const float s = 1.f / std::sqrt(len2);
  const float x = wo[0] * s, y = wo[1] * s, z = std::min(wo[2] * s, 1.f);
  const int computed = p.grey_f ? 1 : channels;
  if (p.method == BrdfProjectionMethod::kIsotropicTable)
    evaluate_table(p, p.iso_f.data(), x, y, z, out, computed);
  else if (p.method == BrdfProjectionMethod::kMatrix)
    evaluate_matrix(p, p.matrix_f.data(), x, y, z, scratch, out, computed);
  else
    evaluate_zonal(p, p.table_f.data(), p.diffuse_f, x, y, z, scratch, out, computed);
  if (computed < channels) {
    const std::size_t n2 = std::size_t(p.order) * p.order;
    std::copy(out, out + n2, out + n2);
    std::copy(out, out + n2, out + 2 * n2);
  }
}

// θo ∈ [0, π/2] of cos θo = z ∈ [0, 1] without a libm call: Abramowitz & Stegun 4.4.46 ([116] of
// docs/REFERENCES.md), acos z = √(1 − z) · (a0 + a1 z + … + a7 z⁷) with |error| ≤ 2·10⁻⁸ in exact
// arithmetic; in float a few ulp of θo (measured against acosf in the tests: < 5·10⁻⁷ rad).
inline float acos_unit(float z) {
  float q = -0.0012624911f;
  q = q * z + 0.0066700901f;
  q = q * z - 0.0170881256f;
  q = q * z + 0.0308918810f;
  q = q * z - 0.0501743046f;
  q = q * z + 0.0889789874f;
  q = q * z - 0.2145988016f;
  q = q * z + 1.5707963050f;
  return std::sqrt(1.f - z) * q;
}

// Per view of a chunk: whether b ≠ 0, the table position in θo, and cos φo, sin φo.
struct ViewChunk {
  static constexpr std::size_t kSize = 64;
  bool ok[kSize];
  float position[kSize], c1[kSize], s1[kSize];
};

// The first pass of evaluate_table_many() over views [0, count ≤ kSize): the arithmetic of
// evaluate_float() and rotate_about_z() except acosf (acos_unit() instead); no branches on data
// but the validity select, so the loop may be vectorised.
void prepare_views(const BrdfProjection::Impl& p, const float* wo, std::size_t count,
                   ViewChunk* v) {
  const float scale = float(p.iso_size - 1);
  for (std::size_t i = 0; i < count; ++i) {
    const float wx = wo[3 * i], wy = wo[3 * i + 1], wz = wo[3 * i + 2];
    const float len2 = wx * wx + wy * wy + wz * wz;
    const bool ok = len2 > 0.f && len2 <= std::numeric_limits<float>::max() && wz > 0.f;
    const float s = 1.f / std::sqrt(ok ? len2 : 1.f);
    const float x = wx * s, y = wy * s, z = std::min(ok ? wz * s : 1.f, 1.f);
    v->ok[i] = ok;
    v->position[i] = acos_unit(z) / float(0.5 * kPi) * scale;
    const float r = std::sqrt(x * x + y * y);
    const bool turn = ok && r > 0.f;
    v->c1[i] = turn ? x / r : 1.f;
    v->s1[i] = turn ? y / r : 0.f;
  }
}

// One view of the table path: the lerp in θo and the rotation by φo fused, per band l the zonal
// entry and the pairs (m, −m); the same operations per value as evaluate_table(). N > 0 is the
// order known at compile time (the loops unrolled), N = 0 p.order.
template <int N>
void table_view(const BrdfProjection::Impl& p, const float* table, float position, float c1,
                float s1, float* out, int channels) {
  const int n = N > 0 ? N : p.order, n2 = n * n;
  const int t0 = std::min(int(position), p.iso_size - 2);
  const float a = position - float(t0);
  const float* b0 = table + std::size_t(t0) * 3 * n2;
  const float* b1 = b0 + 3 * n2;
  for (int ch = 0; ch < channels; ++ch) {
    const float* u = b0 + ch * n2;
    const float* w = b1 + ch * n2;
    float* o = out + ch * n2;
    for (int l = 0; l < n; ++l) {
      const int c = l * l + l;
      o[c] = u[c] + a * (w[c] - u[c]);
    }
    // cos mφ, sin mφ by the recurrence of rotate_about_z(), in scalars (an array written
    // element-wise and read back as a vector would stall store forwarding).
    float cm = 1.f, sm = 0.f;
    for (int m = 1; m < n; ++m) {
      const float next_c = cm * c1 - sm * s1, next_s = sm * c1 + cm * s1;
      cm = next_c;
      sm = next_s;
      for (int l = m; l < n; ++l) {
        const int c = l * l + l;
        const float pos = u[c + m] + a * (w[c + m] - u[c + m]);
        const float neg = u[c - m] + a * (w[c - m] - u[c - m]);
        o[c + m] = pos * cm - neg * sm;
        o[c - m] = pos * sm + neg * cm;
      }
    }
  }
}

template <int N>
void evaluate_table_many(const BrdfProjection::Impl& p, const float* wo, std::size_t count,
                         float* out, int channels) {
  const std::size_t n2 = std::size_t(p.order) * p.order, per_view = channels * n2;
  const int computed = p.grey_f ? 1 : channels;
  ViewChunk v;
  for (std::size_t at = 0; at < count; at += ViewChunk::kSize) {
    const std::size_t m = std::min(ViewChunk::kSize, count - at);
    prepare_views(p, wo + 3 * at, m, &v);
    for (std::size_t i = 0; i < m; ++i) {
      float* o = out + (at + i) * per_view;
      if (!v.ok[i]) {
        std::fill(o, o + per_view, 0.f);
        continue;
      }
      table_view<N>(p, p.iso_f.data(), v.position[i], v.c1[i], v.s1[i], o, computed);
      if (computed < channels) {
        std::copy(o, o + n2, o + n2);
        std::copy(o, o + n2, o + 2 * n2);
      }
    }
  }
}

}  // namespace

void BrdfProjection::evaluate_many(const float* wo, std::size_t count, float* out, float* scratch,
                                   int channels) const {
  const Impl& p = *impl_;
  channels = channels == 1 ? 1 : 3;
  if (p.method == BrdfProjectionMethod::kIsotropicTable && p.iso_size >= 2) {
    switch (p.order) {  // the orders of interactive glossy PRT unrolled, the rest generic
      case 3:
        return evaluate_table_many<3>(p, wo, count, out, channels);
      case 4:
        return evaluate_table_many<4>(p, wo, count, out, channels);
      case 5:
        return evaluate_table_many<5>(p, wo, count, out, channels);
      case 6:
        return evaluate_table_many<6>(p, wo, count, out, channels);
      default:
        return evaluate_table_many<0>(p, wo, count, out, channels);
    }
  }
  const std::size_t per_view = std::size_t(channels) * p.order * p.order;
  for (std::size_t k = 0; k < count; ++k)
    evaluate_float(p, wo + 3 * k, out + k * per_view, scratch, channels);
}

void BrdfProjection::evaluate(const float wo[3], float* out, float* scratch) const {
  evaluate_float(*impl_, wo, out, scratch, 3);
}

void BrdfProjection::evaluate_channel0(const float wo[3], float* out, float* scratch) const {
  evaluate_float(*impl_, wo, out, scratch, 1);
}

bool BrdfProjection::grey() const {
  return impl_->grey_f;
}

}  // namespace prt
