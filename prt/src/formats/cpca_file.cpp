// cpca_file.cpp — the `.prtq` file; see prt/formats/cpca_file.h and docs/GLOSSY_CPCA.md.
#include "prt/formats/cpca_file.h"

#include <cmath>
#include <cstring>
#include <new>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/glossy_transfer_file.h"

namespace prt {
namespace {

constexpr unsigned char kMagic[4] = {'P', 'R', 'C', 'P'};
constexpr uint32_t kVersion = kCpcaFileVersion;
constexpr uint64_t kMaxRecordBytes = uint64_t(1) << 20;
constexpr std::size_t kHeaderSize = 64;
constexpr std::size_t kChecksumOffset = 56;

using detail::load_u32;
using detail::load_u64;
using detail::store_u32;
using detail::store_u64;
void put_floats(unsigned char* p, const std::vector<float>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    uint32_t bits;
    std::memcpy(&bits, &v[i], 4);
    store_u32(p + 4 * i, bits);
  }
}
void get_floats(const unsigned char* p, std::size_t n, std::vector<float>* v) {
  v->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t bits = load_u32(p + 4 * i);
    std::memcpy(&(*v)[i], &bits, 4);
  }
}

// Crc of the whole file with the checksum field taken as zero.
uint32_t file_checksum(const unsigned char* bytes, std::size_t size) {
  return detail::file_checksum(bytes, size, kChecksumOffset);
}

}  // namespace

namespace {

// The source section: `source` without its matrices, as a glossy transfer file of order 1
// with zero binary16 matrices (so every other field is stored and checked by that format).
Result<std::vector<unsigned char>> encode_source(const CpcaTransfer& t,
                                                 const GlossyTransferData& source) {
  if (source.vertex_count != t.vertex_count || source.order != t.order ||
      source.channels != t.channels)
    return Status::Error("cpca file: the source has " + std::to_string(source.vertex_count) +
                         " vertices, order " + std::to_string(source.order) + ", " +
                         std::to_string(source.channels) + " channel(s); the CPCA " +
                         std::to_string(t.vertex_count) + ", " + std::to_string(t.order) + ", " +
                         std::to_string(t.channels));
  const uint64_t fingerprint =
      geometry_fingerprint(source.positions.data(), source.positions.size() / 3);
  if (t.fingerprint != 0 && t.fingerprint != fingerprint)
    return Status::Error("cpca file: the source's geometry fingerprint differs from the CPCA's");
  GlossyTransferData shell;
  shell.order = 1;
  shell.channels = 1;
  shell.storage = Precision::F16;
  shell.interreflected = source.interreflected;
  shell.vertex_count = source.vertex_count;
  shell.primitives = source.primitives;
  shell.positions = source.positions;
  shell.normals = source.normals;
  shell.tangents = source.tangents;
  shell.materials = source.materials;
  shell.material_of_vertex = source.material_of_vertex;
  shell.metadata_json = source.metadata_json;
  shell.matrices.assign(static_cast<std::size_t>(source.vertex_count), 0.f);
  Result<std::vector<unsigned char>> bytes = encode_glossy_transfer_file(shell, "cpca source");
  if (!bytes.ok()) return bytes.status();
  return bytes;
}

Result<std::vector<unsigned char>> encode_impl(const CpcaTransfer& t,
                                               const GlossyTransferData* source,
                                               const std::string& record) {
  Status s = cpca_validate(t);
  if (!s.ok()) return s;
  if (record.size() > kMaxRecordBytes)
    return Status::Error("cpca file: the compression record exceeds 1 MiB");
  try {
    std::vector<unsigned char> section;
    if (source != nullptr) {
      Result<std::vector<unsigned char>> bytes = encode_source(t, *source);
      if (!bytes.ok()) return bytes.status();
      section = std::move(bytes).value();
    }
    const std::size_t payload = static_cast<std::size_t>(t.payload_bytes());
    const std::size_t sourced = source ? 8 + section.size() : 0;
    const std::size_t recorded = record.empty() ? 0 : 8 + record.size();
    std::vector<unsigned char> out(payload + sourced + recorded, 0);
    unsigned char* p = out.data();
    std::memcpy(p, kMagic, 4);
    store_u32(p + 4, kVersion);
    store_u32(p + 8, kHeaderSize);
    store_u32(p + 12, t.order);
    store_u32(p + 16, t.channels);
    store_u32(p + 20, t.cluster_count);
    store_u32(p + 24, t.vector_count);
    store_u32(p + 28, (source ? kCpcaFlagSource : 0) | (record.empty() ? 0 : kCpcaFlagRecord));
    store_u64(p + 32, t.vertex_count);
    store_u64(p + 40, t.fingerprint);
    store_u64(p + 48, out.size());
    std::size_t at = kHeaderSize;
    put_floats(p + at, t.means);
    at += 4 * t.means.size();
    put_floats(p + at, t.basis);
    at += 4 * t.basis.size();
    for (uint32_t id : t.cluster_of_vertex) {
      p[at] = static_cast<unsigned char>(id);
      p[at + 1] = static_cast<unsigned char>(id >> 8);
      at += 2;
    }
    at = (at + 3) / 4 * 4;
    put_floats(p + at, t.weights);
    if (source) {
      store_u64(p + payload, section.size());
      std::memcpy(p + payload + 8, section.data(), section.size());
    }
    if (!record.empty()) {
      store_u64(p + payload + sourced, record.size());
      std::memcpy(p + payload + sourced + 8, record.data(), record.size());
    }
    store_u32(p + kChecksumOffset, file_checksum(p, out.size()));
    return out;
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca file: out of memory");
  }
}

}  // namespace

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t) {
  return encode_impl(t, nullptr, {});
}

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t,
                                                    const GlossyTransferData& source) {
  return encode_impl(t, &source, {});
}

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t,
                                                    const GlossyTransferData& source,
                                                    const std::string& record_json) {
  return encode_impl(t, &source, record_json);
}

namespace {

// The source section at `p` (size bytes) of a CPCA whose header is `t`.
Status decode_source(const unsigned char* p, std::size_t size, const CpcaTransfer& t,
                     const std::string& name, GlossyTransferData* out) {
  Result<GlossyTransferData> shell = read_glossy_transfer_data(p, size, name + " (source section)");
  if (!shell.ok()) return shell.status();
  GlossyTransferData d = std::move(shell).value();
  if (d.order != 1 || d.channels != 1 || d.vertex_count != t.vertex_count)
    return Status::Error(name + ": the source section does not describe the CPCA's " +
                         std::to_string(t.vertex_count) + " vertices");
  if (t.fingerprint != 0 && d.fingerprint != t.fingerprint)
    return Status::Error(name +
                         ": the source section's geometry fingerprint differs from the "
                         "header's");
  d.order = t.order;
  d.channels = t.channels;
  d.storage = Precision::F32;
  d.matrices.clear();
  d.matrices.shrink_to_fit();
  *out = std::move(d);
  return Status::Ok();
}

Result<CpcaFile> decode_impl(const void* data, std::size_t size, const std::string& name,
                             bool want_source) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (size < kHeaderSize || std::memcmp(p, kMagic, 4) != 0) {
    return Status::Error(name + ": not a CPCA transfer file (no PRCP header)");
  }
  const uint32_t version = load_u32(p + 4);
  if (version < 1 || version > kVersion || load_u32(p + 8) != kHeaderSize) {
    return Status::Error(name + ": unsupported CPCA file version " +
                         std::to_string(load_u32(p + 4)));
  }
  if (load_u64(p + 48) != size) {
    return Status::Error(name + ": file size " + std::to_string(size) + " differs from the " +
                         std::to_string(load_u64(p + 48)) +
                         " bytes the header records (truncated?)");
  }
  if (load_u32(p + kChecksumOffset) != file_checksum(p, size)) {
    return Status::Error(name + ": checksum mismatch (the file is corrupt)");
  }
  try {
    CpcaFile file;
    CpcaTransfer& t = file.cpca;
    t.order = load_u32(p + 12);
    t.channels = load_u32(p + 16);
    t.cluster_count = load_u32(p + 20);
    t.vector_count = load_u32(p + 24);
    t.vertex_count = load_u64(p + 32);
    t.fingerprint = load_u64(p + 40);
    const uint32_t flags = load_u32(p + 28);
    const bool sourced = (flags & kCpcaFlagSource) != 0;
    const bool recorded = (flags & kCpcaFlagRecord) != 0;
    const uint32_t known_flags = version >= 2 ? kCpcaFlagSource | kCpcaFlagRecord : kCpcaFlagSource;
    const bool counts_ok = t.order >= 1 && t.order <= 16 && (t.channels == 1 || t.channels == 3) &&
                           t.cluster_count >= 1 && t.cluster_count <= 65535 &&
                           t.vector_count <= 4096 && t.vertex_count <= (uint64_t(1) << 32);
    const uint64_t payload = counts_ok ? t.payload_bytes() : 0;
    // The sections after the payload: [u64 size, source section], then [u64 size, record].
    uint64_t at_section = payload, source_size = 0, record_size = 0;
    bool sizes_agree = counts_ok && payload <= size;
    if (sizes_agree && sourced) {
      sizes_agree = size - at_section >= 8 && load_u64(p + at_section) <= size - at_section - 8;
      if (sizes_agree) source_size = load_u64(p + at_section);
      at_section += 8 + source_size;
    }
    if (sizes_agree && recorded) {
      sizes_agree = size - at_section >= 8 && load_u64(p + at_section) <= kMaxRecordBytes &&
                    load_u64(p + at_section) <= size - at_section - 8;
      if (sizes_agree) record_size = load_u64(p + at_section);
      at_section += 8 + record_size;
    }
    sizes_agree = sizes_agree && at_section == size;
    if (!counts_ok || (flags & ~known_flags) != 0 || !sizes_agree) {
      return Status::Error(name + ": inconsistent CPCA header");
    }
    const std::size_t d = t.dimension(), q = t.cluster_count, k = t.vector_count;
    const std::size_t n = static_cast<std::size_t>(t.vertex_count);
    std::size_t at = kHeaderSize;
    get_floats(p + at, q * d, &t.means);
    at += 4 * q * d;
    get_floats(p + at, q * k * d, &t.basis);
    at += 4 * q * k * d;
    t.cluster_of_vertex.resize(n);
    for (std::size_t v = 0; v < n; ++v, at += 2) t.cluster_of_vertex[v] = p[at] | (p[at + 1] << 8);
    at = (at + 3) / 4 * 4;
    get_floats(p + at, n * k, &t.weights);
    Status s = cpca_validate(t);
    if (!s.ok()) return Status::Error(name + ": " + s.message());
    if (sourced && want_source) {
      s = decode_source(p + payload + 8, static_cast<std::size_t>(source_size), t, name,
                        &file.source);
      if (!s.ok()) return s;
      file.has_source = true;
    }
    if (recorded) {
      const unsigned char* r = p + (size - record_size);
      file.record_json.assign(reinterpret_cast<const char*>(r),
                              static_cast<std::size_t>(record_size));
    }
    return file;
  } catch (const std::bad_alloc&) {
    return Status::Error(name + ": out of memory");
  }
}

}  // namespace

bool is_cpca_transfer_file(const void* bytes, std::size_t size) {
  return bytes != nullptr && size >= 4 && std::memcmp(bytes, kMagic, 4) == 0;
}

Result<CpcaTransfer> decode_cpca_file(const void* data, std::size_t size, const std::string& name) {
  Result<CpcaFile> file = decode_impl(data, size, name, false);
  if (!file.ok()) return file.status();
  return std::move(file->cpca);
}

Result<CpcaFile> decode_cpca_file_with_source(const void* data, std::size_t size,
                                              const std::string& name) {
  return decode_impl(data, size, name, true);
}

Status write_cpca_file(const std::string& path, const CpcaTransfer& t,
                       const GlossyTransferData& source) {
  auto bytes = encode_cpca_file(t, source);
  if (!bytes.ok()) return Status::Error(path + ": " + bytes.status().message());
  return write_file_atomically(path, bytes->data(), bytes->size());
}

Status write_cpca_file(const std::string& path, const CpcaTransfer& t,
                       const GlossyTransferData& source, const std::string& record_json) {
  auto bytes = encode_cpca_file(t, source, record_json);
  if (!bytes.ok()) return Status::Error(path + ": " + bytes.status().message());
  return write_file_atomically(path, bytes->data(), bytes->size());
}

Result<CpcaFile> read_cpca_file_with_source(const std::string& path) {
  std::vector<unsigned char> bytes;
  Status s = detail::read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  return decode_cpca_file_with_source(bytes.data(), bytes.size(), path);
}

Status write_cpca_file(const std::string& path, const CpcaTransfer& t) {
  auto bytes = encode_cpca_file(t);
  if (!bytes.ok()) return Status::Error(path + ": " + bytes.status().message());
  return write_file_atomically(path, bytes->data(), bytes->size());
}

Result<CpcaTransfer> read_cpca_file(const std::string& path) {
  std::vector<unsigned char> bytes;
  Status s = detail::read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  return decode_cpca_file(bytes.data(), bytes.size(), path);
}

}  // namespace prt
