// cpca_file.cpp — the `.prtq` file; see prt/cpca_file.h and docs/GLOSSY_CPCA.md.
#include "prt/cpca_file.h"

#include <cmath>
#include <cstring>
#include <new>

#include "prt/atomic_file.h"
#include "prt/crc32c.h"
#include "prt/geometry_check.h"
#include "prt/glossy_transfer_file.h"
#include "transfer_format.h"

namespace prt {
namespace {

constexpr unsigned char kMagic[4] = {'P', 'R', 'C', 'P'};
constexpr uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 64;
constexpr std::size_t kChecksumOffset = 56;

void put32(unsigned char* p, uint32_t v) {
  for (int i = 0; i < 4; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
void put64(unsigned char* p, uint64_t v) {
  for (int i = 0; i < 8; ++i) p[i] = static_cast<unsigned char>(v >> (8 * i));
}
uint32_t get32(const unsigned char* p) {
  uint32_t v = 0;
  for (int i = 0; i < 4; ++i) v |= uint32_t(p[i]) << (8 * i);
  return v;
}
uint64_t get64(const unsigned char* p) {
  uint64_t v = 0;
  for (int i = 0; i < 8; ++i) v |= uint64_t(p[i]) << (8 * i);
  return v;
}
void put_floats(unsigned char* p, const std::vector<float>& v) {
  for (std::size_t i = 0; i < v.size(); ++i) {
    uint32_t bits;
    std::memcpy(&bits, &v[i], 4);
    put32(p + 4 * i, bits);
  }
}
void get_floats(const unsigned char* p, std::size_t n, std::vector<float>* v) {
  v->resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const uint32_t bits = get32(p + 4 * i);
    std::memcpy(&(*v)[i], &bits, 4);
  }
}

// Crc of the whole file with the checksum field taken as zero.
uint32_t file_checksum(const unsigned char* bytes, std::size_t size) {
  const unsigned char zero[4] = {0, 0, 0, 0};
  uint32_t crc = crc32c(bytes, kChecksumOffset);
  crc = crc32c(zero, 4, crc);
  return crc32c(bytes + kChecksumOffset + 4, size - kChecksumOffset - 4, crc);
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
                                               const GlossyTransferData* source) {
  Status s = cpca_validate(t);
  if (!s.ok()) return s;
  try {
    std::vector<unsigned char> section;
    if (source != nullptr) {
      Result<std::vector<unsigned char>> bytes = encode_source(t, *source);
      if (!bytes.ok()) return bytes.status();
      section = std::move(bytes).value();
    }
    const std::size_t payload = static_cast<std::size_t>(t.payload_bytes());
    std::vector<unsigned char> out(payload + (source ? 8 + section.size() : 0), 0);
    unsigned char* p = out.data();
    std::memcpy(p, kMagic, 4);
    put32(p + 4, kVersion);
    put32(p + 8, kHeaderSize);
    put32(p + 12, t.order);
    put32(p + 16, t.channels);
    put32(p + 20, t.cluster_count);
    put32(p + 24, t.vector_count);
    put32(p + 28, source ? kCpcaFlagSource : 0);
    put64(p + 32, t.vertex_count);
    put64(p + 40, t.fingerprint);
    put64(p + 48, out.size());
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
      put64(p + payload, section.size());
      std::memcpy(p + payload + 8, section.data(), section.size());
    }
    put32(p + kChecksumOffset, file_checksum(p, out.size()));
    return out;
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca file: out of memory");
  }
}

}  // namespace

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t) {
  return encode_impl(t, nullptr);
}

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t,
                                                    const GlossyTransferData& source) {
  return encode_impl(t, &source);
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
  if (get32(p + 4) != kVersion || get32(p + 8) != kHeaderSize) {
    return Status::Error(name + ": unsupported CPCA file version " + std::to_string(get32(p + 4)));
  }
  if (get64(p + 48) != size) {
    return Status::Error(name + ": file size " + std::to_string(size) + " differs from the " +
                         std::to_string(get64(p + 48)) + " bytes the header records (truncated?)");
  }
  if (get32(p + kChecksumOffset) != file_checksum(p, size)) {
    return Status::Error(name + ": checksum mismatch (the file is corrupt)");
  }
  try {
    CpcaFile file;
    CpcaTransfer& t = file.cpca;
    t.order = get32(p + 12);
    t.channels = get32(p + 16);
    t.cluster_count = get32(p + 20);
    t.vector_count = get32(p + 24);
    t.vertex_count = get64(p + 32);
    t.fingerprint = get64(p + 40);
    const uint32_t flags = get32(p + 28);
    const bool sourced = (flags & kCpcaFlagSource) != 0;
    const uint64_t payload = t.order >= 1 && t.order <= 16 ? t.payload_bytes() : 0;
    const bool sizes_agree =
        sourced ? payload <= size && size - payload >= 8 && get64(p + payload) == size - payload - 8
                : payload == size;
    if (t.order < 1 || t.order > 16 || (t.channels != 1 && t.channels != 3) ||
        t.cluster_count < 1 || t.cluster_count > 65535 || t.vector_count > 4096 ||
        t.vertex_count > (uint64_t(1) << 32) || (flags & ~kCpcaFlagSource) != 0 || !sizes_agree) {
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
      s = decode_source(p + payload + 8, size - payload - 8, t, name, &file.source);
      if (!s.ok()) return s;
      file.has_source = true;
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
