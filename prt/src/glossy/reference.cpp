// reference.cpp — the slow double-precision references of prt/glossy/reference.h.
#include <algorithm>
#include <vector>

#include "prt/glossy/reference.h"

namespace prt {
namespace {

// out[c·n² + i] = Σ_{j < used²} m_c[i·n² + j] · L_c,j in double; m_c = m + c'·n⁴.
template <class T>
void apply(const T* m, uint32_t channels, uint32_t order, const ShLighting& light, double* out) {
  const std::size_t n2 = std::size_t(order) * order;
  const std::size_t used =
      static_cast<std::size_t>(std::min<int>(static_cast<int>(order), light.order()));
  for (std::size_t c = 0; c < 3; ++c) {
    const T* mc = m + (channels == 1 ? 0 : c) * n2 * n2;
    const double* l = light.coefficients_double(static_cast<int>(c));
    for (std::size_t i = 0; i < n2; ++i) {
      double sum = 0.0;
      for (std::size_t j = 0; j < used * used; ++j)
        sum += static_cast<double>(mc[i * n2 + j]) * l[j];
      out[c * n2 + i] = sum;
    }
  }
}

Status dot_b(const double* lp, std::size_t n2, const float* b, int b_channels, double out[3]) {
  if (b_channels != 1 && b_channels != 3) return Status::Error("reference: b_channels not 1 or 3");
  if (b == nullptr) return Status::Error("reference: null b");
  for (std::size_t c = 0; c < 3; ++c) {
    const float* bc = b + (b_channels == 1 ? 0 : c) * n2;
    double sum = 0.0;
    for (std::size_t i = 0; i < n2; ++i) sum += static_cast<double>(bc[i]) * lp[c * n2 + i];
    out[c] = sum;
  }
  return Status::Ok();
}

Status check(const GlossyTransferData& d, std::size_t v) {
  if (d.order < 1 || (d.channels != 1 && d.channels != 3)) {
    return Status::Error("reference: bad order or channels");
  }
  if (d.matrices.size() != d.vertex_count * d.channels * d.matrix_floats()) {
    return Status::Error("reference: the matrix array has the wrong size");
  }
  if (v >= d.vertex_count) return Status::Error("reference: vertex out of range");
  return Status::Ok();
}

}  // namespace

Status glossy_transfer_reference(const GlossyTransferData& d, const ShLighting& light,
                                 std::size_t v, double* out) {
  Status s = check(d, v);
  if (!s.ok()) return s;
  apply(d.matrices.data() + v * d.channels * d.matrix_floats(), d.channels, d.order, light, out);
  return Status::Ok();
}

Status glossy_shade_reference(const GlossyTransferData& d, const ShLighting& light, const float* b,
                              int b_channels, std::size_t v, double out_rgb[3]) {
  Status s = check(d, v);
  if (!s.ok()) return s;
  std::vector<double> lp(3 * d.coefficients());
  apply(d.matrices.data() + v * d.channels * d.matrix_floats(), d.channels, d.order, light,
        lp.data());
  return dot_b(lp.data(), d.coefficients(), b, b_channels, out_rgb);
}

Status cpca_transfer_reference(const CpcaTransfer& t, const ShLighting& light, std::size_t v,
                               double* out) {
  Status s = cpca_validate(t);
  if (!s.ok()) return s;
  if (v >= t.vertex_count) return Status::Error("reference: vertex out of range");
  std::vector<double> m(t.dimension());
  cpca_reconstruct(t, v, m.data());
  apply(m.data(), t.channels, t.order, light, out);
  return Status::Ok();
}

Status cpca_shade_reference(const CpcaTransfer& t, const ShLighting& light, const float* b,
                            int b_channels, std::size_t v, double out_rgb[3]) {
  std::vector<double> lp(3 * std::size_t(t.order) * t.order);
  Status s = cpca_transfer_reference(t, light, v, lp.data());
  if (!s.ok()) return s;
  return dot_b(lp.data(), std::size_t(t.order) * t.order, b, b_channels, out_rgb);
}

}  // namespace prt
