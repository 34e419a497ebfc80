// glossy_transfer_file.cpp — glossy transfer file encoding, decoding and validation.
// See prt/formats/glossy_transfer_file.h and docs/FORMAT.md ("Glossy transfer files").
#include "prt/formats/glossy_transfer_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <new>
#include <sstream>

#include "formats/binary_layout.h"
#include "formats/glossy_file_plan.h"
#include "prt/core/atomic_file.h"
#include "prt/core/half.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/geometry_check.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "prt glossy transfer files are little-endian; this reader copies arrays directly"
#endif

namespace prt {
namespace {

using detail::align_up;
using detail::fail;
using detail::file_checksum;
using detail::kAnySize;
using detail::load_u32;
using detail::load_u64;
using detail::store_u32;
using detail::store_u64;

constexpr std::size_t kGHeaderSize = 208;
constexpr std::size_t kPrimitiveRecord = detail::kPrimitiveRecordSize;
constexpr std::size_t kMaterialRecord = 128;
// Header field offsets.
constexpr std::size_t kOffMagic = 0, kOffVersion = 4, kOffHeaderSize = 8, kOffOrder = 12,
                      kOffChannels = 16, kOffStorage = 20, kOffFlags = 24, kOffReserved = 28,
                      kOffVertexCount = 32, kOffPrimitiveCount = 40, kOffMaterialCount = 48,
                      kOffFingerprint = 56, kOffFileSize = 64, kOffChecksum = 72,
                      kOffReserved2 = 76, kOffSections = 80;
constexpr uint32_t kFlagInterreflected = 1u;
}  // namespace
// (Named apart from detail::kOffChecksum, the coefficient files' field.)
constexpr std::size_t kOffGlossyChecksum = 72;
static_assert(kOffGlossyChecksum == kOffChecksum);
namespace {

enum GSection : int {
  kPrims = 0,
  kPos,
  kNrm,
  kTan,
  kMats,
  kMatOfVertex,
  kMatrices,
  kMeta,
  kGSectionCount
};
const char* const kSectionNames[kGSectionCount] = {
    "primitive table", "positions",          "normals",  "tangents",
    "materials",       "material of vertex", "matrices", "metadata"};

double load_f64(const unsigned char* p) {
  double d;
  std::memcpy(&d, p, 8);
  return d;
}
void store_f64(unsigned char* p, double d) {
  std::memcpy(p, &d, 8);
}

// --- materials ---

bool finite_rgb(const brdf::Rgb& c) {
  return std::isfinite(c.r) && std::isfinite(c.g) && std::isfinite(c.b);
}

Status check_material(const brdf::Material& m, std::size_t index, const std::string& name) {
  const auto bad = [&](const std::string& what) {
    return fail(name, "material " + std::to_string(index) + ": " + what);
  };
  if (static_cast<unsigned>(m.model) > static_cast<unsigned>(brdf::MaterialModel::kGltf)) {
    return bad("unknown model " + std::to_string(static_cast<unsigned>(m.model)));
  }
  if (static_cast<unsigned>(m.ward_form) > static_cast<unsigned>(brdf::WardForm::kNormalized)) {
    return bad("unknown Ward form");
  }
  if (static_cast<unsigned>(m.distribution) >
      static_cast<unsigned>(brdf::NormalDistribution::kBeckmann)) {
    return bad("unknown normal distribution");
  }
  if (static_cast<unsigned>(m.fresnel) > static_cast<unsigned>(brdf::FresnelMode::kDielectric)) {
    return bad("unknown Fresnel mode");
  }
  if (!finite_rgb(m.diffuse) || !finite_rgb(m.specular) || !std::isfinite(m.exponent) ||
      !std::isfinite(m.alpha_x) || !std::isfinite(m.alpha_y) || !std::isfinite(m.eta) ||
      !std::isfinite(m.metallic)) {
    return bad("a parameter is not finite");
  }
  if (m.model != brdf::MaterialModel::kGltf && m.metallic != 0.0) {
    return bad("metallic is set for a model other than glTF");
  }
  if (m.model == brdf::MaterialModel::kMerl && m.merl_path.empty()) {
    return bad("a MERL material without a path");
  }
  return Status::Ok();
}

void store_material(unsigned char* r, const brdf::Material& m, uint64_t path_offset) {
  store_u32(r, static_cast<uint32_t>(m.model));
  store_u32(r + 4, static_cast<uint32_t>(m.ward_form));
  store_u32(r + 8, static_cast<uint32_t>(m.distribution));
  store_u32(r + 12, static_cast<uint32_t>(m.fresnel));
  const double values[10] = {m.diffuse.r,  m.diffuse.g, m.diffuse.b, m.specular.r, m.specular.g,
                             m.specular.b, m.exponent,  m.alpha_x,   m.alpha_y,    m.eta};
  for (int i = 0; i < 10; ++i) store_f64(r + 16 + 8 * i, values[i]);
  store_u64(r + 96, path_offset);
  store_u64(r + 104, m.merl_path.size());
  store_f64(r + 112, m.metallic);
}

// One record (enumerators range-checked by check_material afterwards).
Status load_material(const unsigned char* section, uint64_t section_size, uint64_t table_size,
                     std::size_t index, const std::string& name, brdf::Material* m) {
  const unsigned char* r = section + index * kMaterialRecord;
  m->model = static_cast<brdf::MaterialModel>(std::min<uint32_t>(load_u32(r), 255));
  m->ward_form = static_cast<brdf::WardForm>(std::min<uint32_t>(load_u32(r + 4), 255));
  m->distribution = static_cast<brdf::NormalDistribution>(std::min<uint32_t>(load_u32(r + 8), 255));
  m->fresnel = static_cast<brdf::FresnelMode>(std::min<uint32_t>(load_u32(r + 12), 255));
  double v[10];
  for (int i = 0; i < 10; ++i) v[i] = load_f64(r + 16 + 8 * i);
  m->diffuse = {v[0], v[1], v[2]};
  m->specular = {v[3], v[4], v[5]};
  m->exponent = v[6];
  m->alpha_x = v[7];
  m->alpha_y = v[8];
  m->eta = v[9];
  const uint64_t at = load_u64(r + 96), size = load_u64(r + 104);
  m->metallic = load_f64(r + 112);
  if (load_u64(r + 120) != 0) {
    return fail(name, "material " + std::to_string(index) + ": reserved fields are not zero");
  }
  if (at < table_size || at > section_size || size > section_size - at) {
    return fail(name, "path of material " + std::to_string(index) + " lies outside the table");
  }
  m->merl_path.assign(reinterpret_cast<const char*>(section + at), static_cast<std::size_t>(size));
  return check_material(*m, index, name);
}

// --- validation of the in-memory data ---

Status check_sizes(const GlossyTransferData& d, const std::string& name, bool with_matrices) {
  const uint64_t v = d.vertex_count;
  const auto size_error = [&](const char* what, std::size_t have, uint64_t want) {
    std::ostringstream os;
    os << what << " holds " << have << " values, expected " << want << " for " << v << " vertices";
    return fail(name, os.str());
  };
  if (d.positions.size() != 3 * v) return size_error("positions", d.positions.size(), 3 * v);
  if (d.normals.size() != 3 * v) return size_error("normals", d.normals.size(), 3 * v);
  if (d.tangents.size() != 4 * v) return size_error("tangents", d.tangents.size(), 4 * v);
  if (d.material_of_vertex.size() != v) {
    return size_error("material_of_vertex", d.material_of_vertex.size(), v);
  }
  const uint64_t want = v * d.channels * d.matrix_floats();
  if (with_matrices && d.matrices.size() != want)
    return size_error("matrices", d.matrices.size(), want);
  for (std::size_t i = 0; i < d.primitives.size(); ++i) {
    const PrimitiveRange& p = d.primitives[i];
    if (p.first_vertex > v || p.vertex_count > v - p.first_vertex) {
      return fail(name, "primitive " + std::to_string(i) + " (\"" + p.name +
                            "\") covers vertices beyond the " + std::to_string(v) + " vertices");
    }
  }
  return Status::Ok();
}

Status check_finite(const std::string& name, const char* what, const float* x, std::size_t n,
                    std::size_t per_vertex) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(x[i])) {
      std::ostringstream os;
      os << what << " of vertex " << i / per_vertex << " is not finite (" << x[i] << ")";
      return fail(name, os.str());
    }
  }
  return Status::Ok();
}

// Unit normals, unit tangents ⊥ normals with w = ±1 (tolerance 1e-3: float frames).
Status check_frames(const GlossyTransferData& d, const std::string& name) {
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    const float* n = &d.normals[3 * v];
    const float* t = &d.tangents[4 * v];
    const double nn = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    const double tt = std::sqrt(double(t[0]) * t[0] + double(t[1]) * t[1] + double(t[2]) * t[2]);
    const double nt = double(n[0]) * t[0] + double(n[1]) * t[1] + double(n[2]) * t[2];
    if (std::fabs(nn - 1) > 1e-3 || std::fabs(tt - 1) > 1e-3 || std::fabs(nt) > 1e-3 ||
        std::fabs(t[3]) != 1.0f) {
      return fail(name, "the frame of vertex " + std::to_string(v) +
                            " is not orthonormal (unit normal, unit tangent ⊥ normal, w = ±1)");
    }
  }
  return Status::Ok();
}

Status check_materials(const GlossyTransferData& d, const std::string& name) {
  if (d.materials.size() > kMaxGlossyMaterials) return fail(name, "too many materials");
  if (d.vertex_count > 0 && d.materials.empty()) return fail(name, "no materials");
  for (std::size_t i = 0; i < d.materials.size(); ++i) {
    if (Status s = check_material(d.materials[i], i, name); !s.ok()) return s;
  }
  for (std::size_t v = 0; v < d.material_of_vertex.size(); ++v) {
    if (d.material_of_vertex[v] >= d.materials.size()) {
      return fail(name, "vertex " + std::to_string(v) + " has material " +
                            std::to_string(d.material_of_vertex[v]) + " of " +
                            std::to_string(d.materials.size()));
    }
  }
  return Status::Ok();
}

// Every entry of `count` floats of matrices that start at vertex `first_vertex` finite (and, for
// F16 storage, within binary16); the error names the vertex, channel, row and column.
Status check_matrix_entries(const float* m, std::size_t count, uint64_t first_vertex,
                            std::size_t channels, std::size_t k, Precision storage,
                            const std::string& name) {
  const std::size_t per_vertex = channels * k * k;
  for (std::size_t at = 0; at < count; ++at) {
    const float x = m[at];
    const bool bad = !std::isfinite(x) || (storage == Precision::F16 && would_overflow_half(x));
    if (!bad) continue;
    const uint64_t v = first_vertex + at / per_vertex;
    const std::size_t rest = at % per_vertex;
    std::ostringstream os;
    os << "matrix entry (vertex " << v << ", channel " << rest / (k * k) << ", row "
       << rest % (k * k) / k << ", column " << rest % k << ") = " << x
       << (std::isfinite(x) ? " does not fit in float16" : " is not finite");
    return fail(name, os.str());
  }
  return Status::Ok();
}

Status check_matrices(const GlossyTransferData& d, const std::string& name) {
  return check_matrix_entries(d.matrices.data(), d.matrices.size(), 0, d.channels, d.coefficients(),
                              d.storage, name);
}

// Everything but the matrices' finiteness (the reader checks those in the stored precision);
// with_matrices false: not their count either (a streamed file's data holds none).
Status validate_except_matrices(const GlossyTransferData& d, const std::string& name,
                                bool with_matrices = true) {
  if (d.order < 1 || d.order > kMaxGlossyOrder) {
    return fail(name, "SH order " + std::to_string(d.order) + " is outside [1, " +
                          std::to_string(kMaxGlossyOrder) + "]");
  }
  if (d.channels != 1 && d.channels != 3) {
    return fail(name, "channel count " + std::to_string(d.channels) + " is not 1 or 3");
  }
  if (d.storage != Precision::F32 && d.storage != Precision::F16) {
    return fail(name, "unknown storage precision");
  }
  if (d.vertex_count > 0xffffffffull) return fail(name, "more than 2^32 - 1 vertices");
  if (Status s = check_sizes(d, name, with_matrices); !s.ok()) return s;
  if (Status s = check_finite(name, "position", d.positions.data(), d.positions.size(), 3); !s)
    return s;
  if (Status s = check_finite(name, "normal", d.normals.data(), d.normals.size(), 3); !s) return s;
  if (Status s = check_finite(name, "tangent", d.tangents.data(), d.tangents.size(), 4); !s)
    return s;
  if (Status s = check_frames(d, name); !s.ok()) return s;
  return check_materials(d, name);
}

// --- the header and sections of a file ---

struct Layout {
  std::array<uint64_t, kGSectionCount> offsets{}, sizes{};
  uint64_t file_size = 0;
};

uint64_t material_table_size(const GlossyTransferData& d) {
  uint64_t size = d.materials.size() * kMaterialRecord;
  for (const brdf::Material& m : d.materials) size += m.merl_path.size();
  return size;
}

Layout plan_layout(const GlossyTransferData& d) {
  Layout l;
  const uint64_t v = d.vertex_count;
  l.sizes = {detail::primitive_table_bytes(d.primitives),
             12 * v,
             12 * v,
             16 * v,
             material_table_size(d),
             4 * v,
             v * d.channels * d.matrix_floats() * (d.storage == Precision::F16 ? 2 : 4),
             d.metadata_json.size()};
  uint64_t end = kGHeaderSize;
  for (int s = 0; s < kGSectionCount; ++s) {
    if (l.sizes[s] == 0) continue;
    l.offsets[s] = end;
    end = align_up(end + l.sizes[s]);
  }
  l.file_size = end;
  return l;
}

void write_header(unsigned char* h, const GlossyTransferData& d, const Layout& l) {
  std::memcpy(h + kOffMagic, "PRTG", 4);
  store_u32(h + kOffVersion, kGlossyFileVersion);
  store_u32(h + kOffHeaderSize, kGHeaderSize);
  store_u32(h + kOffOrder, d.order);
  store_u32(h + kOffChannels, d.channels);
  store_u32(h + kOffStorage, static_cast<uint32_t>(d.storage));
  store_u32(h + kOffFlags, d.interreflected ? kFlagInterreflected : 0u);
  store_u64(h + kOffVertexCount, d.vertex_count);
  store_u64(h + kOffPrimitiveCount, d.primitives.size());
  store_u64(h + kOffMaterialCount, d.materials.size());
  store_u64(h + kOffFingerprint,
            geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(d.vertex_count)));
  store_u64(h + kOffFileSize, l.file_size);
  for (int s = 0; s < kGSectionCount; ++s) {
    store_u64(h + kOffSections + 16 * s, l.offsets[s]);
    store_u64(h + kOffSections + 16 * s + 8, l.sizes[s]);
  }
}

void write_tables(unsigned char* h, const GlossyTransferData& d, const Layout& l) {
  detail::write_primitive_table(h + l.offsets[kPrims], d.primitives);
  unsigned char* mats = h + l.offsets[kMats];
  uint64_t at = d.materials.size() * kMaterialRecord;
  for (std::size_t i = 0; i < d.materials.size(); ++i) {
    const brdf::Material& m = d.materials[i];
    store_material(mats + i * kMaterialRecord, m, at);
    if (!m.merl_path.empty()) std::memcpy(mats + at, m.merl_path.data(), m.merl_path.size());
    at += m.merl_path.size();
  }
}

void write_arrays(unsigned char* h, const GlossyTransferData& d, const Layout& l) {
  const auto copy = [&](int s, const void* src, std::size_t bytes) {
    if (bytes != 0) std::memcpy(h + l.offsets[s], src, bytes);
  };
  copy(kPos, d.positions.data(), 4 * d.positions.size());
  copy(kNrm, d.normals.data(), 4 * d.normals.size());
  copy(kTan, d.tangents.data(), 4 * d.tangents.size());
  copy(kMatOfVertex, d.material_of_vertex.data(), 4 * d.material_of_vertex.size());
  copy(kMeta, d.metadata_json.data(), d.metadata_json.size());
  if (d.storage == Precision::F16) {
    std::vector<uint16_t> halves(d.matrices.size());
    convert_floats_to_halves(d.matrices.data(), d.matrices.size(), halves.data());
    copy(kMatrices, halves.data(), 2 * halves.size());
  } else {
    copy(kMatrices, d.matrices.data(), 4 * d.matrices.size());
  }
}

// --- reading ---

struct Header {
  uint32_t order = 0, channels = 0, storage = 0, flags = 0;
  uint64_t v = 0, primitive_count = 0, material_count = 0, fingerprint = 0;
  Layout layout;
};

Status check_container(const unsigned char* b, std::size_t size, const std::string& name) {
  if (b == nullptr && size != 0) return fail(name, "null buffer");
  if (size >= 4 && std::memcmp(b, "PRTC", 4) == 0) {
    return fail(name, "is a diffuse coefficient file (PRTC), not a glossy transfer file");
  }
  if (size < kGHeaderSize) {
    return fail(name, "truncated: " + std::to_string(size) + " bytes, less than the " +
                          std::to_string(kGHeaderSize) + "-byte header");
  }
  if (std::memcmp(b, "PRTG", 4) != 0) return fail(name, "not a glossy transfer file (bad magic)");
  if (load_u32(b + kOffVersion) != kGlossyFileVersion) {
    return fail(name,
                "unsupported glossy format version " + std::to_string(load_u32(b + kOffVersion)));
  }
  if (load_u32(b + kOffHeaderSize) != kGHeaderSize) return fail(name, "bad header size");
  if (Status s = detail::check_recorded_size(name, load_u64(b + kOffFileSize), size); !s.ok())
    return s;
  return detail::check_checksum(name, b, size, kOffChecksum);
}

Status read_header(const unsigned char* b, std::size_t size, const std::string& name, Header* h) {
  h->order = load_u32(b + kOffOrder);
  h->channels = load_u32(b + kOffChannels);
  h->storage = load_u32(b + kOffStorage);
  h->flags = load_u32(b + kOffFlags);
  h->v = load_u64(b + kOffVertexCount);
  h->primitive_count = load_u64(b + kOffPrimitiveCount);
  h->material_count = load_u64(b + kOffMaterialCount);
  h->fingerprint = load_u64(b + kOffFingerprint);
  h->layout.file_size = size;
  if (h->order < 1 || h->order > kMaxGlossyOrder) {
    return fail(name, "SH order " + std::to_string(h->order) + " is outside [1, " +
                          std::to_string(kMaxGlossyOrder) + "]");
  }
  if (h->channels != 1 && h->channels != 3) {
    return fail(name, "channel count " + std::to_string(h->channels) + " is not 1 or 3");
  }
  if (h->storage > 1) return fail(name, "unknown storage precision " + std::to_string(h->storage));
  if (h->flags & ~kFlagInterreflected) return fail(name, "unknown flags");
  if (load_u32(b + kOffReserved) != 0 || load_u32(b + kOffReserved2) != 0) {
    return fail(name, "reserved header fields are not zero");
  }
  if (h->v > 0xffffffffull) return fail(name, "vertex count exceeds 2^32 - 1");
  if (h->material_count > kMaxGlossyMaterials) return fail(name, "too many materials");
  for (int s = 0; s < kGSectionCount; ++s) {
    h->layout.offsets[s] = load_u64(b + kOffSections + 16 * s);
    h->layout.sizes[s] = load_u64(b + kOffSections + 16 * s + 8);
  }
  return Status::Ok();
}

Status check_sections(const std::string& name, const Header& h) {
  const uint64_t v = h.v, k2 = uint64_t{h.order} * h.order * h.order * h.order;
  const auto& off = h.layout.offsets;
  const auto& size = h.layout.sizes;
  // Bounded products: v < 2^32, channels · k2 · 4 < 2^17.
  const std::array<uint64_t, kGSectionCount> expected = {
      kAnySize,
      12 * v,
      12 * v,
      16 * v,
      kAnySize,
      4 * v,
      v * h.channels * k2 * (h.storage == 1 ? 2 : 4),
      kAnySize};
  if (Status s =
          detail::check_section_table(name, kGSectionCount, off.data(), size.data(), kSectionNames,
                                      expected.data(), kGHeaderSize, h.layout.file_size, v);
      !s.ok())
    return s;
  if (h.primitive_count > size[kPrims] / kPrimitiveRecord) {
    return fail(name, "the primitive count does not fit the primitive table");
  }
  if (h.material_count > size[kMats] / kMaterialRecord) {
    return fail(name, "the material count does not fit the material table");
  }
  return Status::Ok();
}

Status read_matrices(const unsigned char* b, const std::string& name, const Header& h,
                     GlossyTransferData& d) {
  const unsigned char* src = b + h.layout.offsets[kMatrices];
  const std::size_t n = static_cast<std::size_t>(h.v * h.channels * d.matrix_floats());
  d.matrices.resize(n);
  if (h.storage == 1) {
    for (std::size_t i = 0; i < n; ++i) {
      if ((src[2 * i + 1] & 0x7cu) == 0x7cu) {
        return fail(name, "a float16 matrix entry is Inf or NaN");
      }
    }
    std::vector<uint16_t> halves(n);
    if (n != 0) std::memcpy(halves.data(), src, 2 * n);
    convert_halves_to_floats(halves.data(), n, d.matrices.data());
    return Status::Ok();
  }
  if (n != 0) std::memcpy(d.matrices.data(), src, 4 * n);
  return check_matrices(d, name);
}

Status read_contents(const unsigned char* b, const std::string& name, const Header& h,
                     GlossyTransferData& d, bool with_matrices = true) {
  d.order = h.order;
  d.channels = h.channels;
  d.storage = static_cast<Precision>(h.storage);
  d.interreflected = (h.flags & kFlagInterreflected) != 0;
  d.vertex_count = h.v;
  d.fingerprint = h.fingerprint;
  if (Status s = detail::read_primitive_table(b + h.layout.offsets[kPrims], h.layout.sizes[kPrims],
                                              h.primitive_count, h.v, false, name, &d.primitives);
      !s.ok())
    return s;
  const auto floats = [&](int s, std::vector<float>& dst) {
    dst.resize(static_cast<std::size_t>(h.layout.sizes[s] / 4));
    if (!dst.empty()) std::memcpy(dst.data(), b + h.layout.offsets[s], 4 * dst.size());
  };
  floats(kPos, d.positions);
  floats(kNrm, d.normals);
  floats(kTan, d.tangents);
  d.material_of_vertex.resize(static_cast<std::size_t>(h.v));
  if (h.v != 0)
    std::memcpy(d.material_of_vertex.data(), b + h.layout.offsets[kMatOfVertex], 4 * h.v);
  d.materials.resize(static_cast<std::size_t>(h.material_count));
  for (std::size_t i = 0; i < d.materials.size(); ++i) {
    Status s = load_material(b + h.layout.offsets[kMats], h.layout.sizes[kMats],
                             h.material_count * kMaterialRecord, i, name, &d.materials[i]);
    if (!s.ok()) return s;
  }
  d.metadata_json.assign(reinterpret_cast<const char*>(b + h.layout.offsets[kMeta]),
                         static_cast<std::size_t>(h.layout.sizes[kMeta]));
  if (with_matrices) {
    if (Status s = read_matrices(b, name, h, d); !s.ok()) return s;
  }
  if (Status s = validate_except_matrices(d, name, with_matrices); !s.ok()) return s;
  if (d.fingerprint != geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(h.v))) {
    return fail(name, "stored fingerprint does not match the stored positions");
  }
  return Status::Ok();
}

// Streams the matrix section of an open file: checksum and finiteness, a few MiB at a time.
Status scan_matrices(std::FILE* f, const std::string& name, const Header& h, uint32_t* crc) {
  const uint64_t bytes = h.layout.sizes[kMatrices], per = h.storage == 1 ? 2 : 4;
  const uint64_t per_vertex = uint64_t{h.channels} * h.order * h.order * h.order * h.order;
  const uint64_t chunk_vertices = std::max<uint64_t>(1, (4u << 20) / (per_vertex * per));
  std::vector<unsigned char> chunk(static_cast<std::size_t>(chunk_vertices * per_vertex * per));
  std::vector<float> floats(h.storage == 1 ? 0
                                           : static_cast<std::size_t>(chunk_vertices * per_vertex));
  for (uint64_t v = 0; v < h.v; v += chunk_vertices) {
    const uint64_t n = std::min(chunk_vertices, h.v - v), size = n * per_vertex * per;
    if (std::fread(chunk.data(), 1, static_cast<std::size_t>(size), f) != size)
      return fail(name, "cannot read the matrices");
    *crc = crc32c(chunk.data(), static_cast<std::size_t>(size), *crc);
    if (h.storage == 1) {
      for (uint64_t i = 0; i < size; i += 2)
        if ((chunk[i + 1] & 0x7cu) == 0x7cu)
          return fail(name, "a float16 matrix entry is Inf or NaN");
      continue;
    }
    std::memcpy(floats.data(), chunk.data(), static_cast<std::size_t>(size));
    if (Status s =
            check_matrix_entries(floats.data(), static_cast<std::size_t>(n * per_vertex), v,
                                 h.channels, std::size_t{h.order} * h.order, Precision::F32, name);
        !s.ok())
      return s;
  }
  (void)bytes;
  return Status::Ok();
}

// Reads `size` bytes at `offset` of an open file.
Status read_at(std::FILE* f, uint64_t offset, unsigned char* out, uint64_t size,
               const std::string& name) {
  if (size == 0) return Status::Ok();
  if (std::fseek(f, static_cast<long>(offset), SEEK_SET) != 0 ||
      std::fread(out, 1, static_cast<std::size_t>(size), f) != size)
    return fail(
        name, "cannot read " + std::to_string(size) + " bytes at offset " + std::to_string(offset));
  return Status::Ok();
}

struct FileCloser {
  void operator()(std::FILE* f) const {
    if (f != nullptr) std::fclose(f);
  }
};

// read_glossy_transfer_layout's body: the file `f` of `size` bytes.
Status read_layout(std::FILE* f, uint64_t size, const std::string& name, GlossyFileLayout* out) {
  unsigned char head[kGHeaderSize] = {};
  const std::size_t got = std::fread(head, 1, kGHeaderSize, f);
  if (got >= 4 && std::memcmp(head, "PRTC", 4) == 0)
    return fail(name, "is a diffuse coefficient file (PRTC), not a glossy transfer file");
  if (got < kGHeaderSize) return check_container(head, got, name);
  if (std::memcmp(head, "PRTG", 4) != 0)
    return fail(name, "not a glossy transfer file (bad magic)");
  if (load_u32(head + kOffVersion) != kGlossyFileVersion)
    return fail(
        name, "unsupported glossy format version " + std::to_string(load_u32(head + kOffVersion)));
  if (load_u32(head + kOffHeaderSize) != kGHeaderSize) return fail(name, "bad header size");
  if (Status s = detail::check_recorded_size(name, load_u64(head + kOffFileSize),
                                             static_cast<std::size_t>(size));
      !s.ok())
    return s;
  Header h;
  if (Status s = read_header(head, static_cast<std::size_t>(size), name, &h); !s.ok()) return s;
  if (Status s = check_sections(name, h); !s.ok()) return s;
  // The file without its matrices: [0, m) ++ [m + bytes, size); later sections shift down.
  const uint64_t m = h.layout.sizes[kMatrices] ? h.layout.offsets[kMatrices] : size;
  const uint64_t m_bytes = h.layout.sizes[kMatrices], m_end = std::min(size, m + m_bytes);
  std::vector<unsigned char> image(static_cast<std::size_t>(m + (size - m_end)));
  if (Status s = read_at(f, 0, image.data(), m, name); !s.ok()) return s;
  uint32_t crc = detail::file_checksum(image.data(), static_cast<std::size_t>(m), kOffChecksum);
  if (m_bytes != 0) {
    if (std::fseek(f, static_cast<long>(m), SEEK_SET) != 0) return fail(name, "cannot seek");
    if (Status s = scan_matrices(f, name, h, &crc); !s.ok()) return s;
  }
  if (Status s = read_at(f, m_end, image.data() + m, size - m_end, name); !s.ok()) return s;
  crc = crc32c(image.data() + m, static_cast<std::size_t>(size - m_end), crc);
  const uint32_t stored = load_u32(image.data() + kOffChecksum);
  if (stored != crc) {
    char text[96];
    std::snprintf(text, sizeof text, "checksum mismatch (stored 0x%08x, computed 0x%08x)", stored,
                  crc);
    return fail(name, text);
  }
  Header shifted = h;
  for (int s = 0; s < kGSectionCount; ++s)
    if (s != kMatrices && shifted.layout.offsets[s] > m) shifted.layout.offsets[s] -= m_bytes;
  out->data = GlossyTransferData{};
  if (Status s = read_contents(image.data(), name, shifted, out->data, false); !s.ok()) return s;
  out->matrix_offset = m;
  out->matrix_bytes = m_bytes;
  return Status::Ok();
}

}  // namespace

bool is_glossy_transfer_file(const void* bytes, std::size_t size) {
  return bytes != nullptr && size >= 4 && std::memcmp(bytes, "PRTG", 4) == 0;
}

Status validate_glossy_transfer_data(const GlossyTransferData& d, const std::string& name) {
  if (Status s = validate_except_matrices(d, name); !s.ok()) return s;
  if (Status s = check_matrices(d, name); !s.ok()) return s;
  if (d.fingerprint != 0 &&
      d.fingerprint !=
          geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(d.vertex_count))) {
    return fail(name, "fingerprint does not match the positions (leave it 0 to have it computed)");
  }
  return Status::Ok();
}

Result<std::vector<unsigned char>> encode_glossy_transfer_file(const GlossyTransferData& d,
                                                               const std::string& name) {
  if (Status s = validate_glossy_transfer_data(d, name); !s.ok()) return s;
  try {
    const Layout l = plan_layout(d);
    if (l.file_size > std::numeric_limits<std::size_t>::max()) return fail(name, "file too large");
    std::vector<unsigned char> out(static_cast<std::size_t>(l.file_size), 0);
    write_header(out.data(), d, l);
    write_tables(out.data(), d, l);
    write_arrays(out.data(), d, l);
    store_u32(out.data() + kOffChecksum, file_checksum(out.data(), out.size(), kOffChecksum));
    return out;
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while encoding");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while encoding");
  }
}

Status write_glossy_transfer_file(const std::string& path, const GlossyTransferData& d) {
  Result<std::vector<unsigned char>> bytes = encode_glossy_transfer_file(d, path);
  if (!bytes.ok()) return bytes.status();
  return write_file_atomically(path, bytes.value().data(), bytes.value().size());
}

Result<GlossyTransferData> read_glossy_transfer_data(const void* bytes, std::size_t size,
                                                     const std::string& name) {
  const auto* b = static_cast<const unsigned char*>(bytes);
  if (Status s = check_container(b, size, name); !s.ok()) return s;
  Header h;
  if (Status s = read_header(b, size, name, &h); !s.ok()) return s;
  if (Status s = check_sections(name, h); !s.ok()) return s;
  try {
    GlossyTransferData d;
    if (Status s = read_contents(b, name, h, d); !s.ok()) return s;
    return d;
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while reading");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while reading");
  }
}

Result<GlossyTransferData> read_glossy_transfer_file(const std::string& path) {
  std::vector<unsigned char> bytes;
  if (Status s = detail::read_file_bytes(path, &bytes); !s.ok()) return s;
  return read_glossy_transfer_data(bytes.data(), bytes.size(), path);
}

}  // namespace prt

namespace prt {

Result<GlossyFileLayout> read_glossy_transfer_layout(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) return fail(path, std::string("cannot open: ") + std::strerror(errno));
  if (std::fseek(f.get(), 0, SEEK_END) != 0) return fail(path, "cannot seek");
  const long end = std::ftell(f.get());
  if (end < 0 || std::fseek(f.get(), 0, SEEK_SET) != 0) return fail(path, "cannot seek");
  try {
    GlossyFileLayout layout;
    if (Status s = read_layout(f.get(), static_cast<uint64_t>(end), path, &layout); !s.ok())
      return s;
    return layout;
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory while reading");
  } catch (const std::length_error&) {
    return fail(path, "out of memory while reading");
  }
}

Status read_glossy_matrices(const std::string& path, const GlossyFileLayout& layout,
                            uint64_t first_vertex, uint64_t count, float* out) {
  const GlossyTransferData& d = layout.data;
  if (first_vertex > d.vertex_count || count > d.vertex_count - first_vertex)
    return fail(path, "vertices " + std::to_string(first_vertex) + " + " + std::to_string(count) +
                          " lie beyond the " + std::to_string(d.vertex_count) + " vertices");
  std::unique_ptr<std::FILE, FileCloser> f(std::fopen(path.c_str(), "rb"));
  if (!f) return fail(path, std::string("cannot open: ") + std::strerror(errno));
  const uint64_t floats = count * d.channels * d.matrix_floats();
  const uint64_t per = d.storage == Precision::F16 ? 2 : 4;
  const uint64_t at = layout.matrix_offset + first_vertex * d.channels * d.matrix_floats() * per;
  if (d.storage == Precision::F32)
    return read_at(f.get(), at, reinterpret_cast<unsigned char*>(out), 4 * floats, path);
  try {
    std::vector<uint16_t> halves(static_cast<std::size_t>(floats));
    if (Status s =
            read_at(f.get(), at, reinterpret_cast<unsigned char*>(halves.data()), 2 * floats, path);
        !s.ok())
      return s;
    convert_halves_to_floats(halves.data(), halves.size(), out);
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory while reading");
  }
}

namespace detail {

uint64_t glossy_checksum_offset() {
  return prt::kOffGlossyChecksum;
}

Status check_glossy_matrix_entries(const float* m, std::size_t count, uint64_t first_vertex,
                                   uint32_t channels, uint32_t order, Precision storage,
                                   const std::string& name) {
  return check_matrix_entries(m, count, first_vertex, channels, std::size_t{order} * order, storage,
                              name);
}

Result<GlossyFilePlan> plan_glossy_file(const GlossyTransferData& d, const std::string& name) {
  if (Status s = validate_except_matrices(d, name, false); !s.ok()) return s;
  if (d.fingerprint != 0 &&
      d.fingerprint !=
          geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(d.vertex_count)))
    return fail(name, "fingerprint does not match the positions (leave it 0 to have it computed)");
  try {
    const Layout l = plan_layout(d);
    // Where the matrices start: their offset, or (none) where they would.
    uint64_t m = kGHeaderSize;
    for (int s = 0; s < kMatrices; ++s)
      if (l.sizes[s] != 0) m = align_up(l.offsets[s] + l.sizes[s]);
    GlossyFilePlan plan;
    plan.matrix_offset = m;
    plan.matrix_bytes = l.sizes[kMatrices];
    std::vector<unsigned char> head(static_cast<std::size_t>(m), 0);
    write_header(head.data(), d, l);
    write_tables(head.data(), d, l);
    const auto copy = [&](int s, const void* src, std::size_t bytes) {
      if (bytes != 0) std::memcpy(head.data() + l.offsets[s], src, bytes);
    };
    copy(kPos, d.positions.data(), 4 * d.positions.size());
    copy(kNrm, d.normals.data(), 4 * d.normals.size());
    copy(kTan, d.tangents.data(), 4 * d.tangents.size());
    copy(kMatOfVertex, d.material_of_vertex.data(), 4 * d.material_of_vertex.size());
    plan.prefix = std::move(head);
    const uint64_t m_end = m + plan.matrix_bytes;
    plan.tail.assign(static_cast<std::size_t>(l.file_size - m_end), 0);
    if (!d.metadata_json.empty())
      std::memcpy(plan.tail.data() + (l.offsets[kMeta] - m_end), d.metadata_json.data(),
                  d.metadata_json.size());
    return plan;
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while encoding");
  }
}

}  // namespace detail
}  // namespace prt
