// cpca_file.cpp — the `.prtq` file; see prt/cpca_file.h and docs/GLOSSY_CPCA.md.
#include "prt/cpca_file.h"

#include <cmath>
#include <cstring>
#include <new>

#include "prt/atomic_file.h"
#include "transfer_format.h"

namespace prt {
namespace {

constexpr unsigned char kMagic[4] = {'P', 'R', 'C', 'P'};
constexpr uint32_t kVersion = 1;
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

Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& t) {
  Status s = cpca_validate(t);
  if (!s.ok()) return s;
  try {
    std::vector<unsigned char> out(static_cast<std::size_t>(t.payload_bytes()), 0);
    unsigned char* p = out.data();
    std::memcpy(p, kMagic, 4);
    store_u32(p + 4, kVersion);
    store_u32(p + 8, kHeaderSize);
    store_u32(p + 12, t.order);
    store_u32(p + 16, t.channels);
    store_u32(p + 20, t.cluster_count);
    store_u32(p + 24, t.vector_count);
    store_u32(p + 28, 0);
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
    store_u32(p + kChecksumOffset, file_checksum(p, out.size()));
    return out;
  } catch (const std::bad_alloc&) {
    return Status::Error("cpca file: out of memory");
  }
}

Result<CpcaTransfer> decode_cpca_file(const void* data, std::size_t size, const std::string& name) {
  const auto* p = static_cast<const unsigned char*>(data);
  if (size < kHeaderSize || std::memcmp(p, kMagic, 4) != 0) {
    return Status::Error(name + ": not a CPCA transfer file (no PRCP header)");
  }
  if (load_u32(p + 4) != kVersion || load_u32(p + 8) != kHeaderSize) {
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
    CpcaTransfer t;
    t.order = load_u32(p + 12);
    t.channels = load_u32(p + 16);
    t.cluster_count = load_u32(p + 20);
    t.vector_count = load_u32(p + 24);
    t.vertex_count = load_u64(p + 32);
    t.fingerprint = load_u64(p + 40);
    if (t.order < 1 || t.order > 16 || (t.channels != 1 && t.channels != 3) ||
        t.cluster_count < 1 || t.cluster_count > 65535 || t.vector_count > 4096 ||
        t.vertex_count > (uint64_t(1) << 32) || load_u32(p + 28) != 0 ||
        t.payload_bytes() != size) {
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
    return t;
  } catch (const std::bad_alloc&) {
    return Status::Error(name + ": out of memory");
  }
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
