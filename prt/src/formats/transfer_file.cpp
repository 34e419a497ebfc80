// transfer_file.cpp — coefficient file encoding, decoding and validation.
// See prt/formats/transfer_file.h and docs/FORMAT.md.
#include "prt/formats/transfer_file.h"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <new>
#include <sstream>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"
#include "prt/core/half.h"
#include "prt/formats/geometry_check.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "prt coefficient files are little-endian; this reader copies arrays directly"
#endif

namespace prt {
namespace detail {

bool blocked_coefficient_bytes(uint64_t vertex_count, uint64_t channels, uint64_t k_count,
                               uint64_t bytes_per_value, uint64_t* out) {
  const uint64_t blocks = vertex_count / kVertexBlock + (vertex_count % kVertexBlock ? 1 : 0);
  uint64_t n = blocks;
  return !__builtin_mul_overflow(n, channels, &n) && !__builtin_mul_overflow(n, k_count, &n) &&
         !__builtin_mul_overflow(n, uint64_t{kVertexBlock}, &n) &&
         !__builtin_mul_overflow(n, bytes_per_value, &n) && (*out = n, true);
}

}  // namespace detail

namespace {

using namespace detail;

const char* const kSectionNames[kSectionCount] = {
    "primitive table", "positions", "normals", "coefficients", "ao", "bent normals", "metadata"};

// Index of the first non-finite value, or n.
std::size_t find_non_finite(const float* v, std::size_t n) {
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(v[i])) return i;
  }
  return n;
}

Status check_finite_array(const std::string& name, const char* what, const float* v, std::size_t n,
                          std::size_t per_vertex) {
  const std::size_t bad = find_non_finite(v, n);
  if (bad == n) return Status::Ok();
  std::ostringstream os;
  os << what << " of vertex " << bad / per_vertex << " is not finite (" << v[bad] << ")";
  return fail(name, os.str());
}

// Positions, normals, AO and bent normals must all be finite (the first bad value is named).
Status check_finite_vertex_arrays(const std::string& name, const TransferData& d) {
  Status s = check_finite_array(name, "position", d.positions.data(), d.positions.size(), 3);
  if (s.ok()) s = check_finite_array(name, "normal", d.normals.data(), d.normals.size(), 3);
  if (s.ok()) s = check_finite_array(name, "ao", d.ao.data(), d.ao.size(), 1);
  if (s.ok()) {
    s = check_finite_array(name, "bent normal", d.bent_normals.data(), d.bent_normals.size(), 3);
  }
  return s;
}

}  // namespace

namespace detail {

Status validate_common_transfer_fields(const TransferData& d, const std::string& name) {
  if (d.channels != 1 && d.channels != 3) {
    return fail(name, "channel count " + std::to_string(d.channels) + " is not 1 or 3");
  }
  if (d.vertex_count > kMaxTransferVertices) {
    return fail(name, "vertex count " + std::to_string(d.vertex_count) + " exceeds " +
                          std::to_string(kMaxTransferVertices));
  }
  const uint64_t v = d.vertex_count;
  auto size_error = [&](const char* what, std::size_t have, uint64_t want) {
    std::ostringstream os;
    os << what << " holds " << have << " floats, expected " << want << " for " << v << " vertices";
    return fail(name, os.str());
  };
  if (d.positions.size() != 3 * v) return size_error("positions", d.positions.size(), 3 * v);
  if (d.normals.size() != 3 * v) return size_error("normals", d.normals.size(), 3 * v);
  if (!d.ao.empty() && d.ao.size() != v) return size_error("ao", d.ao.size(), v);
  if (!d.bent_normals.empty() && d.bent_normals.size() != 3 * v) {
    return size_error("bent normals", d.bent_normals.size(), 3 * v);
  }
  for (std::size_t i = 0; i < d.primitives.size(); ++i) {
    const PrimitiveRange& p = d.primitives[i];
    if (p.first_vertex > v || p.vertex_count > v - p.first_vertex) {
      std::ostringstream os;
      os << "primitive " << i << " (\"" << p.name << "\") covers vertices [" << p.first_vertex
         << ", +" << p.vertex_count << ") beyond the " << v << " vertices";
      return fail(name, os.str());
    }
  }
  if (Status s = check_finite_vertex_arrays(name, d); !s.ok()) return s;
  if (d.fingerprint != 0 &&
      d.fingerprint != geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(v))) {
    return fail(name, "fingerprint does not match the positions (leave it 0 to have it computed)");
  }
  return Status::Ok();
}

}  // namespace detail

Status validate_transfer_data(const TransferData& d, const std::string& name) {
  if (static_cast<uint32_t>(d.kind) > static_cast<uint32_t>(TransferKind::Haar)) {
    return fail(name, "unknown transfer kind " + std::to_string(static_cast<uint32_t>(d.kind)));
  }
  if (d.kind == TransferKind::Haar) {
    return fail(name,
                "Haar-wavelet transfer is stored with prt::write_haar_transfer_file "
                "(prt/formats/haar_transfer_file.h), not as SH coefficients");
  }
  if (d.storage != Precision::F32 && d.storage != Precision::F16) {
    return fail(name,
                "unknown storage precision " + std::to_string(static_cast<uint32_t>(d.storage)));
  }
  if (d.order < 1 || d.order > kMaxTransferOrder) {
    return fail(name, "SH order " + std::to_string(d.order) + " is outside [1, " +
                          std::to_string(kMaxTransferOrder) + "]");
  }
  Status s = validate_common_transfer_fields(d, name);
  if (!s.ok()) return s;
  const uint64_t v = d.vertex_count;
  const uint64_t k = uint64_t{d.order} * d.order;
  if (d.coefficients.size() != v * d.channels * k) {
    std::ostringstream os;
    os << "coefficients holds " << d.coefficients.size() << " floats, expected "
       << v * d.channels * k << " for " << v << " vertices";
    return fail(name, os.str());
  }
  s = check_finite_array(name, "a coefficient", d.coefficients.data(), d.coefficients.size(),
                         d.channels * k);
  if (!s.ok()) return s;
  if (d.storage == Precision::F16) {
    const std::size_t n = d.coefficients.size();
    const std::size_t bad = find_half_overflow(d.coefficients.data(), n);
    if (bad != n) {
      std::ostringstream os;
      os.precision(9);
      os << "coefficient " << d.coefficients[bad] << " of vertex " << bad / (d.channels * k)
         << " (channel " << (bad / k) % d.channels << ", index " << bad % k
         << ") overflows float16 (largest 65504); store it as F32";
      return fail(name, os.str());
    }
  }
  return Status::Ok();
}

namespace detail {

Result<std::vector<unsigned char>> encode_transfer_container(
    const TransferData& d, uint32_t order_field, uint32_t storage_field, uint64_t coefficient_bytes,
    const std::function<void(unsigned char*)>& write_coefficients, const std::string& name) {
  try {
    const uint64_t v = d.vertex_count;
    std::array<uint64_t, kSectionCount> sizes{};
    sizes[kPrimitives] = primitive_table_bytes(d.primitives);
    sizes[kPositions] = 12 * v;
    sizes[kNormals] = 12 * v;
    sizes[kCoefficients] = coefficient_bytes;
    sizes[kAo] = 4 * uint64_t{d.ao.size()};
    sizes[kBentNormals] = 4 * uint64_t{d.bent_normals.size()};
    sizes[kMetadata] = d.metadata_json.size();
    std::array<uint64_t, kSectionCount> offsets{};
    uint64_t end = kHeaderSize;
    for (int s = 0; s < kSectionCount; ++s) {
      if (sizes[s] == 0) continue;
      offsets[s] = end;
      end = align_up(end + sizes[s]);
    }
    if (end > std::numeric_limits<std::size_t>::max()) return fail(name, "file too large");
    std::vector<unsigned char> out(static_cast<std::size_t>(end), 0);
    unsigned char* h = out.data();
    std::memcpy(h + kOffMagic, "PRTC", 4);
    store_u32(h + kOffVersion, kTransferFileVersion);
    store_u32(h + kOffHeaderSize, kHeaderSize);
    store_u32(h + kOffKind, static_cast<uint32_t>(d.kind));
    store_u32(h + kOffOrder, order_field);
    store_u32(h + kOffChannels, d.channels);
    store_u32(h + kOffStorage, storage_field);
    const uint32_t flags = (d.albedo_folded ? kFlagAlbedoFolded : 0u) |
                           (d.ao.empty() ? 0u : kFlagHasAo) |
                           (d.bent_normals.empty() ? 0u : kFlagHasBentNormals);
    store_u32(h + kOffFlags, flags);
    store_u64(h + kOffVertexCount, v);
    store_u64(h + kOffPrimitiveCount, d.primitives.size());
    store_u64(h + kOffFingerprint,
              geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(v)));
    store_u64(h + kOffFileSize, end);
    for (int s = 0; s < kSectionCount; ++s) {
      store_u64(h + kOffSections + 16 * s, offsets[s]);
      store_u64(h + kOffSections + 16 * s + 8, sizes[s]);
    }
    write_primitive_table(h + offsets[kPrimitives], d.primitives);
    auto copy_floats = [&](int s, const std::vector<float>& src) {
      if (!src.empty()) std::memcpy(h + offsets[s], src.data(), src.size() * sizeof(float));
    };
    copy_floats(kPositions, d.positions);
    copy_floats(kNormals, d.normals);
    copy_floats(kAo, d.ao);
    copy_floats(kBentNormals, d.bent_normals);
    if (!d.metadata_json.empty()) {
      std::memcpy(h + offsets[kMetadata], d.metadata_json.data(), d.metadata_json.size());
    }
    if (coefficient_bytes != 0) write_coefficients(h + offsets[kCoefficients]);
    store_u32(h + kOffChecksum, file_checksum(h, out.size(), kOffChecksum));
    return out;
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while encoding");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while encoding");
  }
}

}  // namespace detail

Result<std::vector<unsigned char>> encode_transfer_file(const TransferData& d,
                                                        const std::string& name) {
  Status valid = validate_transfer_data(d, name);
  if (!valid.ok()) return valid;
  const uint64_t v = d.vertex_count;
  const uint64_t k = uint64_t{d.order} * d.order;
  const uint64_t bytes_per_value = d.storage == Precision::F16 ? 2 : 4;
  uint64_t coefficient_bytes = 0;
  if (!blocked_coefficient_bytes(v, d.channels, k, bytes_per_value, &coefficient_bytes)) {
    return fail(name, "coefficient section size overflows");
  }
  // Coefficients: vertex-major floats -> blocked layout (padding stays zero).
  auto write_blocked = [&](unsigned char* coeffs) {
    const std::size_t vk = d.channels * static_cast<std::size_t>(k);
    for (std::size_t vi = 0; vi < v; ++vi) {
      for (std::size_t c = 0; c < d.channels; ++c) {
        const float* src = d.coefficients.data() + vi * vk + c * k;
        for (std::size_t ki = 0; ki < k; ++ki) {
          const std::size_t at = blocked_coefficient_index(vi, c, ki, d.channels, k);
          if (d.storage == Precision::F16) {
            const uint16_t half = float_to_half(src[ki]);
            std::memcpy(coeffs + 2 * at, &half, 2);
          } else {
            std::memcpy(coeffs + 4 * at, src + ki, 4);
          }
        }
      }
    }
  };
  return encode_transfer_container(d, d.order, static_cast<uint32_t>(d.storage), coefficient_bytes,
                                   write_blocked, name);
}

Status write_transfer_file(const std::string& path, const TransferData& data) {
  Result<std::vector<unsigned char>> bytes = encode_transfer_file(data, path);
  if (!bytes.ok()) return bytes.status();
  return write_file_atomically(path, bytes.value().data(), bytes.value().size());
}

namespace detail {
namespace {

// The header fields parse_transfer_file checks and reads from.
struct HeaderFields {
  uint64_t file_size = 0;
  uint32_t kind = 0, order = 0, channels = 0, storage = 0, flags = 0;
  uint64_t v = 0;  // vertex count
  uint64_t primitive_count = 0;
  bool haar = false;
  std::array<uint64_t, kSectionCount> offsets{}, sizes{};
};

// The container: header size, magic, version, file size against the buffer, checksum.
Status check_container(const unsigned char* b, std::size_t size, const std::string& name,
                       HeaderFields* h) {
  if (b == nullptr && size != 0) return fail(name, "null buffer");
  if (size < kHeaderSize) {
    return fail(name, "truncated: " + std::to_string(size) + " bytes, less than the " +
                          std::to_string(kHeaderSize) + "-byte header");
  }
  if (std::memcmp(b, "PRTC", 4) != 0) return fail(name, "not a prt coefficient file (bad magic)");
  const uint32_t version = load_u32(b + kOffVersion);
  if (version != kTransferFileVersion) {
    return fail(name, "unsupported format version " + std::to_string(version) +
                          " (this library reads version " + std::to_string(kTransferFileVersion) +
                          ")");
  }
  if (load_u32(b + kOffHeaderSize) != kHeaderSize) {
    return fail(name, "header size " + std::to_string(load_u32(b + kOffHeaderSize)) + " is not " +
                          std::to_string(kHeaderSize));
  }
  const uint64_t file_size = load_u64(b + kOffFileSize);
  if (Status s = check_recorded_size(name, file_size, size); !s.ok()) return s;
  if (Status s = check_checksum(name, b, size, kOffChecksum); !s.ok()) return s;
  h->file_size = file_size;
  return Status::Ok();
}

// The fields of a checksummed header: kind (Haar only when allowed), order or cube size,
// channels, storage, flags, reserved fields, vertex count; then the section table.
Status read_header_fields(const unsigned char* b, const std::string& name, bool allow_haar,
                          HeaderFields* h) {
  // The bytes are what the writer wrote; now check that the writer was consistent.
  const uint32_t kind = h->kind = load_u32(b + kOffKind);
  const uint32_t order = h->order = load_u32(b + kOffOrder);
  const uint32_t channels = h->channels = load_u32(b + kOffChannels);
  const uint32_t storage = h->storage = load_u32(b + kOffStorage);
  const uint32_t flags = h->flags = load_u32(b + kOffFlags);
  const uint64_t v = h->v = load_u64(b + kOffVertexCount);
  h->primitive_count = load_u64(b + kOffPrimitiveCount);
  if (kind > static_cast<uint32_t>(TransferKind::Haar)) {
    return fail(name, "unknown transfer kind " + std::to_string(kind));
  }
  const bool haar = h->haar = kind == static_cast<uint32_t>(TransferKind::Haar);
  if (haar && !allow_haar) {
    return fail(
        name,
        "holds Haar-wavelet transfer (kind 3, cube size " + std::to_string(order) +
            "): read it with prt::read_haar_transfer_file (prt/formats/haar_transfer_file.h)");
  }
  if (haar) {
    if (order < 8 || order > 128 || (order & (order - 1)) != 0) {
      return fail(name,
                  "Haar cube size " + std::to_string(order) + " is not a power of two in [8, 128]");
    }
  } else if (order < 1 || order > kMaxTransferOrder) {
    return fail(name, "SH order " + std::to_string(order) + " is outside [1, " +
                          std::to_string(kMaxTransferOrder) + "]");
  }
  if (channels != 1 && channels != 3) {
    return fail(name, "channel count " + std::to_string(channels) + " is not 1 or 3");
  }
  if (haar ? (storage != kHaarStorageF32 && storage != kHaarStorageI16 && storage != kHaarStorageI8)
           : storage > 1) {
    return fail(name, "unknown storage precision " + std::to_string(storage));
  }
  if (flags & ~kKnownFlags) return fail(name, "unknown flags " + std::to_string(flags));
  if (load_u32(b + kOffReserved0) != 0 || load_u64(b + kOffReserved1) != 0) {
    return fail(name, "reserved header fields are not zero");
  }
  if (v > kMaxTransferVertices) {
    return fail(name, "vertex count " + std::to_string(v) + " exceeds " +
                          std::to_string(kMaxTransferVertices));
  }
  for (int s = 0; s < kSectionCount; ++s) {
    h->offsets[s] = load_u64(b + kOffSections + 16 * s);
    h->sizes[s] = load_u64(b + kOffSections + 16 * s + 8);
  }
  return Status::Ok();
}

// Sections: sizes as the header implies, inside the file and aligned, not overlapping; the
// primitive count fits the primitive table.
Status check_sections(const std::string& name, const HeaderFields& h) {
  const uint64_t v = h.v, file_size = h.file_size;
  const auto& offsets = h.offsets;
  const auto& sizes = h.sizes;
  const uint64_t k = uint64_t{h.order} * h.order;
  // Expected section sizes (all products bounded: v < 2^32, k <= 4096).
  uint64_t coefficient_bytes = 0;
  if (!h.haar) {
    blocked_coefficient_bytes(v, h.channels, k, h.storage == 1 ? 2 : 4, &coefficient_bytes);
  }
  const bool has_ao = h.flags & kFlagHasAo, has_bent = h.flags & kFlagHasBentNormals;
  const std::array<uint64_t, kSectionCount> expected = {kAnySize,
                                                        12 * v,
                                                        12 * v,
                                                        h.haar ? kAnySize : coefficient_bytes,
                                                        has_ao ? 4 * v : 0,
                                                        has_bent ? 12 * v : 0,
                                                        kAnySize};
  if (Status s = check_section_table(name, kSectionCount, offsets.data(), sizes.data(),
                                     kSectionNames, expected.data(), kHeaderSize, file_size, v);
      !s.ok())
    return s;
  if (h.primitive_count > sizes[kPrimitives] / kPrimitiveRecordSize) {
    return fail(name, "primitive count " + std::to_string(h.primitive_count) +
                          " does not fit in the " + std::to_string(sizes[kPrimitives]) +
                          "-byte primitive table");
  }
  return Status::Ok();
}

// Finite coefficients (padding included: it must be zero, which is finite). The Haar payload is
// checked by its decoder (prt/formats/haar_transfer_file.h).
Status check_finite_coefficients(const std::string& name, const HeaderFields& h,
                                 const ParsedTransferFile& out) {
  if (h.haar) {
  } else if (h.storage == 1) {
    for (std::size_t i = 0; i < out.coefficient_bytes; i += 2) {
      const unsigned exponent = out.coefficients[i + 1] & 0x7cu;  // high byte: s eeeee mm
      if (exponent == 0x7cu) {
        return fail(name, "a float16 coefficient is Inf or NaN");
      }
    }
  } else {
    for (std::size_t i = 0; i < out.coefficient_bytes; i += 4) {
      float f;
      std::memcpy(&f, out.coefficients + i, 4);
      if (!std::isfinite(f)) return fail(name, "a coefficient is Inf or NaN");
    }
  }
  return Status::Ok();
}

// The file's contents once its header and sections have been checked. May throw
// std::bad_alloc or std::length_error.
Status read_contents(const unsigned char* b, const std::string& name, const HeaderFields& h,
                     ParsedTransferFile* out) {
  TransferData& d = out->data;
  d = TransferData{};
  d.kind = static_cast<TransferKind>(h.kind);
  d.order = h.order;
  d.channels = h.channels;
  d.storage = h.haar ? Precision::F32 : static_cast<Precision>(h.storage);
  out->storage_code = h.storage;
  d.albedo_folded = h.flags & kFlagAlbedoFolded;
  d.vertex_count = h.v;
  d.fingerprint = load_u64(b + kOffFingerprint);
  // The primitive table: ranges within the vertices, names within the table.
  if (Status s = read_primitive_table(b + h.offsets[kPrimitives], h.sizes[kPrimitives],
                                      h.primitive_count, h.v, true, name, &d.primitives);
      !s.ok())
    return s;
  auto read_floats = [&](int s, std::vector<float>& dst) {
    dst.resize(static_cast<std::size_t>(h.sizes[s] / 4));
    if (!dst.empty()) std::memcpy(dst.data(), b + h.offsets[s], dst.size() * sizeof(float));
  };
  read_floats(kPositions, d.positions);
  read_floats(kNormals, d.normals);
  read_floats(kAo, d.ao);
  read_floats(kBentNormals, d.bent_normals);
  d.metadata_json.assign(reinterpret_cast<const char*>(b + h.offsets[kMetadata]),
                         static_cast<std::size_t>(h.sizes[kMetadata]));
  if (Status s = check_finite_vertex_arrays(name, d); !s.ok()) return s;
  out->coefficients = b + h.offsets[kCoefficients];
  out->coefficient_bytes = static_cast<std::size_t>(h.sizes[kCoefficients]);
  if (Status s = check_finite_coefficients(name, h, *out); !s.ok()) return s;
  if (d.fingerprint != geometry_fingerprint(d.positions.data(), static_cast<std::size_t>(h.v))) {
    return fail(name, "stored fingerprint does not match the stored positions");
  }
  return Status::Ok();
}

}  // namespace

Status parse_transfer_file(const void* bytes_in, std::size_t size, const std::string& name,
                           ParsedTransferFile* out, bool allow_haar) {
  const auto* b = static_cast<const unsigned char*>(bytes_in);
  HeaderFields h;
  if (Status s = check_container(b, size, name, &h); !s.ok()) return s;
  if (Status s = read_header_fields(b, name, allow_haar, &h); !s.ok()) return s;
  if (Status s = check_sections(name, h); !s.ok()) return s;
  try {
    return read_contents(b, name, h, out);
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while reading");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while reading");
  }
}

}  // namespace detail

Result<TransferData> read_transfer_data(const void* bytes, std::size_t size,
                                        const std::string& name) {
  try {
    ParsedTransferFile parsed;
    Status s = parse_transfer_file(bytes, size, name, &parsed);
    if (!s.ok()) return s;
    TransferData& d = parsed.data;
    const std::size_t v = static_cast<std::size_t>(d.vertex_count);
    const std::size_t k = d.coefficients_per_channel();
    const std::size_t c_count = d.channels;
    d.coefficients.resize(v * c_count * k);
    const unsigned char* src = parsed.coefficients;
    for (std::size_t vi = 0; vi < v; ++vi) {
      for (std::size_t c = 0; c < c_count; ++c) {
        float* dst = d.coefficients.data() + (vi * c_count + c) * k;
        for (std::size_t ki = 0; ki < k; ++ki) {
          const std::size_t at = blocked_coefficient_index(vi, c, ki, c_count, k);
          if (d.storage == Precision::F16) {
            uint16_t h;
            std::memcpy(&h, src + 2 * at, 2);
            dst[ki] = half_to_float(h);
          } else {
            std::memcpy(dst + ki, src + 4 * at, 4);
          }
        }
      }
    }
    return std::move(parsed.data);
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while reading");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while reading");
  }
}

Result<TransferData> read_transfer_file(const std::string& path) {
  std::vector<unsigned char> bytes;
  Status s = read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  return read_transfer_data(bytes.data(), bytes.size(), path);
}

Status detail::read_file_bytes(const std::string& path, std::vector<unsigned char>* out) {
  std::vector<unsigned char>& bytes = *out;
  std::error_code ec;  // a folder opens on some systems and reports a huge length
  if (std::filesystem::is_directory(path, ec)) return fail(path, "is a directory, not a file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return fail(path, std::string("cannot open: ") + std::strerror(errno));
  bool read_error = std::fseek(f, 0, SEEK_END) != 0;
  const long length = read_error ? -1 : std::ftell(f);
  read_error = read_error || length < 0 || std::fseek(f, 0, SEEK_SET) != 0;
  if (!read_error) {
    try {
      bytes.resize(static_cast<std::size_t>(length));
    } catch (const std::exception&) {
      std::fclose(f);
      return fail(path, "out of memory while reading " + std::to_string(length) + " bytes");
    }
    read_error = std::fread(bytes.data(), 1, bytes.size(), f) != bytes.size();
  }
  std::fclose(f);
  if (read_error) return fail(path, "read error");
  return Status::Ok();
}

}  // namespace prt
