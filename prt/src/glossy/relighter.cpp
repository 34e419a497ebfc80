// prt/src/glossy/relighter.cpp — exit radiance of glossy transfer toward an eye point
// (prt/glossy/relighter.h).
#include "prt/glossy/relighter.h"
#include "prt/glossy/reference.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

namespace prt {
namespace {

using brdf::Vec3;

std::string vertex_text(std::size_t v) {
  return "vertex " + std::to_string(v);
}

Status check_data(const GlossyTransferData& d, bool with_matrices = true) {
  const std::size_t v = d.vertex_count;
  if (d.order < 1 || d.order > uint32_t(kMaxBrdfProjectionOrder))
    return Status::Error("glossy transfer: order " + std::to_string(d.order) + " is outside [1, " +
                         std::to_string(kMaxBrdfProjectionOrder) + "]");
  if (d.channels != 1 && d.channels != 3)
    return Status::Error("glossy transfer: channels must be 1 or 3, not " +
                         std::to_string(d.channels));
  if (d.positions.size() != 3 * v || d.normals.size() != 3 * v || d.tangents.size() != 4 * v ||
      d.material_of_vertex.size() != v ||
      (with_matrices && d.matrices.size() != v * d.channels * d.matrix_floats()))
    return Status::Error("glossy transfer: array sizes do not match " + std::to_string(v) +
                         " vertices of order " + std::to_string(d.order));
  for (std::size_t k = 0; k < v; ++k)
    if (d.material_of_vertex[k] >= d.materials.size())
      return Status::Error("glossy transfer: " + vertex_text(k) + " has material " +
                           std::to_string(d.material_of_vertex[k]) + " of " +
                           std::to_string(d.materials.size()));
  return Status::Ok();
}

// Orthonormal (t, b, n) of vertex k (Gram–Schmidt of the tangent against the normal), row-major
// into frame[9]: rows t, b, n, so frame·d gives d in the local frame.
Status vertex_frame(const GlossyTransferData& d, std::size_t k, double frame[9]) {
  Vec3 n{d.normals[3 * k], d.normals[3 * k + 1], d.normals[3 * k + 2]};
  Vec3 t{d.tangents[4 * k], d.tangents[4 * k + 1], d.tangents[4 * k + 2]};
  const double w = d.tangents[4 * k + 3] < 0.f ? -1.0 : 1.0;
  n = normalize(n);
  t = t - dot(t, n) * n;  // a tangent within ~0.06° of the normal is refused, not guessed at
  const bool degenerate = !(length(n) > 0.5) || !(length(t) > 1e-3);
  t = normalize(t);
  if (degenerate)
    return Status::Error("glossy transfer: " + vertex_text(k) +
                         " has a degenerate or non-finite normal/tangent frame");
  const Vec3 b = w * Vec3{n.y * t.z - n.z * t.y, n.z * t.x - n.x * t.z, n.x * t.y - n.y * t.x};
  const double rows[9] = {t.x, t.y, t.z, b.x, b.y, b.z, n.x, n.y, n.z};
  std::copy(rows, rows + 9, frame);
  return Status::Ok();
}

}  // namespace

struct GlossyRelighter::Impl {
  int order = 1, channels = 1;
  std::size_t vertex_count = 0;
  std::vector<float> positions, frames;  // 3 and 9 floats per vertex
  std::vector<uint32_t> material_of_vertex;
  GlossyShadingPath path = GlossyShadingPath::kKernel;
  bool compressed = false;
  std::vector<float> matrices;  // kPortable
  GlossyKernel kernel;          // kKernel
  CpcaKernel cpca;              // compressed
  std::vector<BrdfProjection> projections;
  bool grey_b = false;  // every projection is grey: the kernels take b of channel 0 only

  Status shade_portable(const ShLighting& light, const float eye[3], std::size_t first,
                        std::size_t count, float* out_rgb) const;
  void view_vectors(const float eye[3], std::size_t first, std::size_t count, float* b,
                    float* scratch, float* local, int b_channels) const;
};

GlossyRelighter::GlossyRelighter() : impl_(std::make_unique<Impl>()) {}
GlossyRelighter::GlossyRelighter(GlossyRelighter&&) noexcept = default;
GlossyRelighter& GlossyRelighter::operator=(GlossyRelighter&&) noexcept = default;
GlossyRelighter::~GlossyRelighter() = default;

std::size_t GlossyRelighter::vertex_count() const {
  return impl_->vertex_count;
}
int GlossyRelighter::order() const {
  return impl_->order;
}
int GlossyRelighter::channels() const {
  return impl_->channels;
}
const std::vector<BrdfProjection>& GlossyRelighter::projections() const {
  return impl_->projections;
}

Result<GlossyRelighter> GlossyRelighter::create(const GlossyTransferData& data,
                                                const BrdfProjectionOptions& options) {
  return create(GlossyTransferData(data), options);
}

namespace {

// Frames, positions, materials and projections of `data` into p (the matrices are left alone).
Status set_geometry(const GlossyTransferData& data, const BrdfProjectionOptions& options,
                    GlossyRelighter::Impl& p) {
  p.order = int(data.order);
  p.channels = int(data.channels);
  p.vertex_count = data.vertex_count;
  p.positions = data.positions;
  p.material_of_vertex = data.material_of_vertex;
  p.frames.resize(9 * p.vertex_count);
  for (std::size_t k = 0; k < p.vertex_count; ++k) {
    double frame[9];
    if (Status s = vertex_frame(data, k, frame); !s) return s;
    for (int e = 0; e < 9; ++e) p.frames[9 * k + e] = float(frame[e]);
  }
  for (const brdf::Material& material : data.materials) {
    Result<BrdfProjection> projection = BrdfProjection::create(material, p.order, options);
    if (!projection) return projection.status();
    p.projections.push_back(std::move(projection).value());
  }
  p.grey_b = std::all_of(p.projections.begin(), p.projections.end(),
                         [](const BrdfProjection& b) { return b.grey(); });
  return Status::Ok();
}

}  // namespace

Result<GlossyRelighter> GlossyRelighter::create(GlossyTransferData&& data,
                                                const BrdfProjectionOptions& options) {
  return create(std::move(data), options, GlossyShadingPath::kKernel);
}

Result<GlossyRelighter> GlossyRelighter::create(GlossyTransferData&& data,
                                                const BrdfProjectionOptions& options,
                                                GlossyShadingPath path) {
  if (Status s = check_data(data); !s) return s;
  GlossyRelighter out;
  Impl& p = *out.impl_;
  if (Status s = set_geometry(data, options, p); !s) return s;
  p.path = path;
  if (path == GlossyShadingPath::kKernel) {
    Result<GlossyKernel> kernel = GlossyKernel::create(data);
    if (!kernel) return kernel.status();
    p.kernel = std::move(kernel).value();
  } else {
    p.matrices = std::move(data.matrices);
  }
  return out;
}

Result<GlossyRelighter> GlossyRelighter::create_cpca(GlossyTransferData&& geometry,
                                                     const CpcaTransfer& cpca,
                                                     const BrdfProjectionOptions& options) {
  if (Status s = check_data(geometry, false); !s) return s;
  if (Status s = cpca_validate(cpca); !s) return s;
  if (cpca.vertex_count != geometry.vertex_count || cpca.order != geometry.order ||
      cpca.channels != geometry.channels)
    return Status::Error("glossy transfer: the CPCA has " + std::to_string(cpca.vertex_count) +
                         " vertices of order " + std::to_string(cpca.order) + " and " +
                         std::to_string(cpca.channels) + " channel(s), the geometry " +
                         std::to_string(geometry.vertex_count) + ", " +
                         std::to_string(geometry.order) + ", " + std::to_string(geometry.channels));
  GlossyRelighter out;
  Impl& p = *out.impl_;
  if (Status s = set_geometry(geometry, options, p); !s) return s;
  Result<CpcaKernel> kernel = CpcaKernel::create(cpca);
  if (!kernel) return kernel.status();
  p.cpca = std::move(kernel).value();
  p.compressed = true;
  return out;
}

bool GlossyRelighter::compressed() const {
  return impl_->compressed;
}
GlossyShadingPath GlossyRelighter::path() const {
  return impl_->path;
}

Status GlossyRelighter::prepare(const ShLighting& light, GlossyFrame* frame) const {
  if (frame == nullptr) return Status::Error("glossy shading: null frame");
  frame->light = light;
  frame->owner = impl_.get();
  if (impl_->compressed) return impl_->cpca.prepare(light, &frame->cpca);
  return Status::Ok();
}

// b of vertices [first, first + count) toward `eye`: b_channels·n² floats per vertex (1: channel
// 0 only, for grey projections), zero where the eye is below the tangent plane (or at the vertex,
// or not finite). `local` holds 3·count floats (the views in the tangent frames); b is computed
// for each run of vertices of one material at once (BrdfProjection::evaluate_many()).
void GlossyRelighter::Impl::view_vectors(const float eye[3], std::size_t first, std::size_t count,
                                         float* b, float* scratch, float* local,
                                         int b_channels) const {
  const std::size_t n2 = std::size_t(order) * order, per_vertex = std::size_t(b_channels) * n2;
  for (std::size_t k = first; k < first + count; ++k) {
    const float* f = &frames[9 * k];
    const float d[3] = {eye[0] - positions[3 * k], eye[1] - positions[3 * k + 1],
                        eye[2] - positions[3 * k + 2]};
    float* l = local + 3 * (k - first);
    l[0] = f[0] * d[0] + f[1] * d[1] + f[2] * d[2];
    l[1] = f[3] * d[0] + f[4] * d[1] + f[5] * d[2];
    l[2] = f[6] * d[0] + f[7] * d[1] + f[8] * d[2];
  }
  for (std::size_t k = first; k < first + count;) {
    const uint32_t material = material_of_vertex[k];
    std::size_t end = k + 1;
    while (end < first + count && material_of_vertex[end] == material) ++end;
    projections[material].evaluate_many(local + 3 * (k - first), end - k,
                                        b + (k - first) * per_vertex, scratch, b_channels);
    k = end;
  }
}

Status GlossyRelighter::shade(const ShLighting& light, const float eye[3], std::size_t first,
                              std::size_t count, float* out_rgb) const {
  if (!impl_->compressed && impl_->path == GlossyShadingPath::kPortable)
    return impl_->shade_portable(light, eye, first, count, out_rgb);
  GlossyFrame frame;
  if (Status s = prepare(light, &frame); !s) return s;
  return shade(frame, eye, first, count, out_rgb);
}

Status GlossyRelighter::shade(const GlossyFrame& frame, const float eye[3], std::size_t first,
                              std::size_t count, float* out_rgb) const {
  const Impl& p = *impl_;
  if (frame.owner != impl_.get())
    return Status::Error("glossy shading: the frame was prepared by another relighter");
  if (!p.compressed && p.path == GlossyShadingPath::kPortable)
    return p.shade_portable(frame.light, eye, first, count, out_rgb);
  if (first > p.vertex_count || count > p.vertex_count - first)
    return Status::Error("glossy shading: vertices [" + std::to_string(first) + ", " +
                         std::to_string(first + count) + ") beyond " +
                         std::to_string(p.vertex_count));
  if (count == 0) return Status::Ok();
  if (eye == nullptr || out_rgb == nullptr) return Status::Error("glossy shading: null pointer");
  // Blocks: b of a block stays in cache between the two steps, and a CPCA block is long enough
  // for the kernel to shade many vertices of each cluster in a row.
  constexpr std::size_t kBlock = 1024;
  const std::size_t n2 = std::size_t(p.order) * p.order;
  // Grey b: channel 0 alone for the uncompressed kernel (it transposes b into lanes per block,
  // a third of the work); CpcaKernel reads b in place, so three channels suit it best.
  const int bc = p.grey_b && !p.compressed ? 1 : 3;
  std::size_t scratch_size = 0;
  for (const BrdfProjection& b : p.projections)
    scratch_size = std::max(scratch_size, b.scratch_floats());
  std::vector<float> scratch(scratch_size), b(kBlock * std::size_t(bc) * n2), local(3 * kBlock);
  for (std::size_t at = first; at < first + count; at += kBlock) {
    const std::size_t n = std::min(kBlock, first + count - at);
    p.view_vectors(eye, at, n, b.data(), scratch.data(), local.data(), bc);
    float* out = out_rgb + 3 * (at - first);
    const Status s = p.compressed ? p.cpca.shade(frame.cpca, b.data(), bc, at, n, out)
                                  : p.kernel.shade(frame.light, b.data(), bc, at, n, out);
    if (!s) return s;
  }
  return Status::Ok();
}

Status GlossyRelighter::Impl::shade_portable(const ShLighting& light, const float eye[3],
                                             std::size_t first, std::size_t count,
                                             float* out_rgb) const {
  const Impl& p = *this;
  if (first > p.vertex_count || count > p.vertex_count - first)
    return Status::Error("glossy shading: vertices [" + std::to_string(first) + ", " +
                         std::to_string(first + count) + ") beyond " +
                         std::to_string(p.vertex_count));
  if (count == 0) return Status::Ok();
  if (eye == nullptr || out_rgb == nullptr) return Status::Error("glossy shading: null pointer");
  const int n2 = p.order * p.order;
  const int k_used = std::min(p.order, light.order()) * std::min(p.order, light.order());
  std::size_t scratch_size = 0;
  for (const BrdfProjection& b : p.projections)
    scratch_size = std::max(scratch_size, b.scratch_floats());
  std::vector<float> scratch(scratch_size), b(3 * std::size_t(n2));
  const float* lc[3] = {light.coefficients(0), light.coefficients(1), light.coefficients(2)};
  for (std::size_t k = first; k < first + count; ++k) {
    const float* f = &p.frames[9 * k];
    const float d[3] = {eye[0] - p.positions[3 * k], eye[1] - p.positions[3 * k + 1],
                        eye[2] - p.positions[3 * k + 2]};
    const float local[3] = {f[0] * d[0] + f[1] * d[1] + f[2] * d[2],
                            f[3] * d[0] + f[4] * d[1] + f[5] * d[2],
                            f[6] * d[0] + f[7] * d[1] + f[8] * d[2]};
    float* out = out_rgb + 3 * (k - first);
    out[0] = out[1] = out[2] = 0.f;
    if (!(local[2] > 0.f)) continue;  // below the tangent plane, at the eye, or not finite
    p.projections[p.material_of_vertex[k]].evaluate(local, b.data(), scratch.data());
    for (int c = 0; c < 3; ++c) {
      const int cm = p.channels == 3 ? c : 0;
      const float* m = &p.matrices[(k * std::size_t(p.channels) + cm) * n2 * n2];
      const float* bc = &b[std::size_t(c) * n2];
      float sum = 0.f;
      for (int i = 0; i < n2; ++i) {
        if (bc[i] == 0.f) continue;
        const float* row = m + std::size_t(i) * n2;
        float transferred = 0.f;
        for (int j = 0; j < k_used; ++j) transferred += row[j] * lc[c][j];
        sum += bc[i] * transferred;
      }
      out[c] = sum;
    }
  }
  return Status::Ok();
}

Status shade_glossy_reference(const GlossyTransferData& data, const ShLighting& light,
                              const double eye[3], std::size_t v, const SliceQuadrature& quadrature,
                              double out_rgb[3]) {
  if (Status s = check_data(data); !s) return s;
  if (v >= data.vertex_count)
    return Status::Error("glossy reference: " + vertex_text(v) + " out of range");
  double frame[9];
  if (Status s = vertex_frame(data, v, frame); !s) return s;
  Result<std::shared_ptr<const brdf::Brdf>> f =
      brdf::make_brdf(data.materials[data.material_of_vertex[v]]);
  if (!f) return f.status();
  const int order = int(data.order), n2 = order * order;
  const double d[3] = {eye[0] - data.positions[3 * v], eye[1] - data.positions[3 * v + 1],
                       eye[2] - data.positions[3 * v + 2]};
  const Vec3 local{frame[0] * d[0] + frame[1] * d[1] + frame[2] * d[2],
                   frame[3] * d[0] + frame[4] * d[1] + frame[5] * d[2],
                   frame[6] * d[0] + frame[7] * d[1] + frame[8] * d[2]};
  std::vector<double> b(3 * std::size_t(n2));
  if (Status s = project_brdf_slice(**f, order, local, quadrature, b.data()); !s) return s;
  const int k_used = std::min(order, light.order()) * std::min(order, light.order());
  for (int c = 0; c < 3; ++c) {
    const int cm = data.channels == 3 ? c : 0;
    const float* m = &data.matrices[(v * data.channels + cm) * std::size_t(n2) * n2];
    const double* l = light.coefficients_double(c);
    double sum = 0.0;
    for (int i = 0; i < n2; ++i) {
      double transferred = 0.0;
      for (int j = 0; j < k_used; ++j) transferred += double(m[std::size_t(i) * n2 + j]) * l[j];
      sum += b[std::size_t(c) * n2 + i] * transferred;
    }
    out_rgb[c] = sum;
  }
  return Status::Ok();
}

}  // namespace prt
