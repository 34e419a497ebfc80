// haar_transfer_file.cpp — the Haar kind of the coefficient-file container (see
// prt/formats/haar_transfer_file.h and docs/FORMAT.md, "Haar-wavelet transfer").
#include "prt/formats/haar_transfer_file.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <new>
#include <stdexcept>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"

namespace prt {
namespace {

using detail::align_up;

constexpr uint64_t kPayloadHeaderBytes = 16;  // u64 entry count, u64 reserved

uint64_t bytes_per_value(HaarQuantization q) {
  return q == HaarQuantization::Float32 ? 4 : q == HaarQuantization::Bits16 ? 2 : 1;
}

// Byte offsets of the payload's arrays inside the coefficient section.
struct PayloadLayout {
  uint64_t offsets_at = kPayloadHeaderBytes, vertices_at = 0, steps_at = 0, values_at = 0;
  uint64_t total = 0;
};

// All operands are bounded by the caller (N ≤ 128, V < 2³², entries·channels checked against
// the bytes present), so the arithmetic cannot overflow 64 bits.
PayloadLayout layout_payload(uint64_t size, uint64_t vertices, uint64_t entries, uint64_t channels,
                             uint64_t value_bytes) {
  PayloadLayout l;
  const uint64_t wavelets = 6 * size * size;
  l.vertices_at = align_up(l.offsets_at + 8 * (wavelets + 1));
  l.steps_at = align_up(l.vertices_at + 4 * entries);
  l.values_at = align_up(l.steps_at + 4 * vertices);
  l.total = l.values_at + entries * channels * value_bytes;
  return l;
}

using detail::fail;
using detail::load_u64;

HaarQuantization quantization_from_code(uint32_t code) {
  return code == detail::kHaarStorageI8    ? HaarQuantization::Bits8
         : code == detail::kHaarStorageI16 ? HaarQuantization::Bits16
                                           : HaarQuantization::Float32;
}

const void* values_of(const HaarTransfer& t) {
  switch (t.quantization) {
    case HaarQuantization::Float32:
      return t.values_f32.data();
    case HaarQuantization::Bits16:
      return t.values_i16.data();
    case HaarQuantization::Bits8:
      return t.values_i8.data();
  }
  return nullptr;
}

uint64_t value_count_of(const HaarTransfer& t) {
  switch (t.quantization) {
    case HaarQuantization::Float32:
      return t.values_f32.size();
    case HaarQuantization::Bits16:
      return t.values_i16.size();
    case HaarQuantization::Bits8:
      return t.values_i8.size();
  }
  return 0;
}

// The payload checks shared by the writer and the reader: the arrays of `t` are sized
// consistently (the caller has checked t.size, t.channels and t.vertex_count).
Status check_haar_arrays(const HaarTransfer& t, const std::string& name) {
  const uint64_t wavelets = 6 * uint64_t(t.size) * uint64_t(t.size);
  if (t.offsets.size() != wavelets + 1) return fail(name, "Haar offsets table has the wrong size");
  if (t.offsets[0] != 0 || t.offsets[wavelets] != t.vertices.size()) {
    return fail(name, "Haar offsets do not start at 0 and end at the entry count");
  }
  const uint64_t levels = static_cast<uint64_t>(haar_quantization_levels(t.quantization));
  if (value_count_of(t) != t.vertices.size() * uint64_t(t.channels)) {
    return fail(name, "Haar value array does not hold channels values per entry");
  }
  if (t.vertex_step.size() != static_cast<uint64_t>(t.vertex_count)) {
    return fail(name, "Haar step array does not hold one step per vertex");
  }
  for (uint64_t i = 0; i < wavelets; ++i) {
    const uint64_t begin = t.offsets[i], end = t.offsets[i + 1];
    if (end < begin || end > t.vertices.size()) {
      return fail(name, "Haar offsets decrease or overrun at wavelet index " + std::to_string(i));
    }
    for (uint64_t e = begin; e < end; ++e) {
      if (t.vertices[e] >= t.vertex_count || (e > begin && t.vertices[e] <= t.vertices[e - 1])) {
        return fail(name, "the vertex list of wavelet index " + std::to_string(i) +
                              " is out of range or not ascending");
      }
    }
  }
  for (uint64_t v = 0; v < t.vertex_step.size(); ++v) {
    if (!std::isfinite(t.vertex_step[v]) || t.vertex_step[v] < 0.0f) {
      return fail(name, "dequantisation step of vertex " + std::to_string(v) +
                            " is negative or not finite");
    }
  }
  for (float x : t.values_f32) {
    if (!std::isfinite(x)) return fail(name, "a Haar coefficient is Inf or NaN");
  }
  const long q = static_cast<long>(levels);
  for (int16_t x : t.values_i16) {
    if (x < -q || x > q) return fail(name, "a 16-bit Haar coefficient lies outside ±32767");
  }
  for (int8_t x : t.values_i8) {
    if (x < -q || x > q) return fail(name, "an 8-bit Haar coefficient lies outside ±127");
  }
  return Status::Ok();
}

}  // namespace

Status validate_haar_transfer_file(const HaarTransferFile& file, const std::string& name) {
  const TransferData& d = file.info;
  const HaarTransfer& t = file.transfer;
  if (d.kind != TransferKind::Haar) return fail(name, "info.kind is not TransferKind::Haar");
  if (!is_valid_cube_size(t.size)) {
    return fail(name,
                "Haar cube size " + std::to_string(t.size) + " is not a power of two in [8, 128]");
  }
  if (d.order != static_cast<uint32_t>(t.size) || d.channels != static_cast<uint32_t>(t.channels) ||
      d.vertex_count != static_cast<uint64_t>(t.vertex_count)) {
    return fail(name, "info (order/cube size, channels, vertex count) disagrees with the transfer");
  }
  if (!d.coefficients.empty()) return fail(name, "info.coefficients must be empty for Haar");
  Status s = detail::validate_common_transfer_fields(d, name);
  if (!s.ok()) return s;
  return check_haar_arrays(t, name);
}

Result<std::vector<unsigned char>> encode_haar_transfer_file(const HaarTransferFile& file,
                                                             const std::string& name) {
  Status valid = validate_haar_transfer_file(file, name);
  if (!valid.ok()) return valid;
  const HaarTransfer& t = file.transfer;
  const uint64_t value_bytes = bytes_per_value(t.quantization);
  const PayloadLayout l = layout_payload(uint64_t(t.size), uint64_t(t.vertex_count),
                                         t.vertices.size(), uint64_t(t.channels), value_bytes);
  auto write_payload = [&](unsigned char* p) {
    const uint64_t entries = t.vertices.size();
    std::memcpy(p, &entries, 8);
    std::memcpy(p + l.offsets_at, t.offsets.data(), 8 * t.offsets.size());
    if (entries) std::memcpy(p + l.vertices_at, t.vertices.data(), 4 * entries);
    if (!t.vertex_step.empty()) {
      std::memcpy(p + l.steps_at, t.vertex_step.data(), 4 * t.vertex_step.size());
    }
    if (entries) std::memcpy(p + l.values_at, values_of(t), value_count_of(t) * value_bytes);
  };
  return detail::encode_transfer_container(file.info, static_cast<uint32_t>(t.size),
                                           static_cast<uint32_t>(t.quantization), l.total,
                                           write_payload, name);
}

Status write_haar_transfer_file(const std::string& path, const HaarTransferFile& file) {
  Result<std::vector<unsigned char>> bytes = encode_haar_transfer_file(file, path);
  if (!bytes.ok()) return bytes.status();
  return write_file_atomically(path, bytes.value().data(), bytes.value().size());
}

Result<HaarTransferFile> read_haar_transfer_data(const void* bytes, std::size_t size,
                                                 const std::string& name) {
  try {
    detail::ParsedTransferFile parsed;
    Status s = detail::parse_transfer_file(bytes, size, name, &parsed, /*allow_haar=*/true);
    if (!s.ok()) return s;
    if (parsed.data.kind != TransferKind::Haar) {
      return fail(name, "holds SH transfer, not Haar: read it with prt::read_transfer_file");
    }
    HaarTransferFile out;
    out.info = std::move(parsed.data);
    HaarTransfer& t = out.transfer;
    t.size = static_cast<int>(out.info.order);
    t.channels = static_cast<int>(out.info.channels);
    t.vertex_count = static_cast<int64_t>(out.info.vertex_count);
    t.quantization = quantization_from_code(parsed.storage_code);
    const unsigned char* p = parsed.coefficients;
    const uint64_t section = parsed.coefficient_bytes;
    if (section < kPayloadHeaderBytes) return fail(name, "Haar payload is truncated");
    const uint64_t entries = load_u64(p);
    if (load_u64(p + 8) != 0) return fail(name, "Haar payload reserved field is not zero");
    // Bound the entry count by the bytes present before any arithmetic or allocation.
    if (entries > section / 4) {
      return fail(name, "Haar entry count " + std::to_string(entries) +
                            " does not fit in the coefficient section");
    }
    const uint64_t value_bytes = bytes_per_value(t.quantization);
    const PayloadLayout l = layout_payload(uint64_t(t.size), uint64_t(t.vertex_count), entries,
                                           uint64_t(t.channels), value_bytes);
    if (l.total != section) {
      return fail(name, "Haar coefficient section holds " + std::to_string(section) +
                            " bytes, expected " + std::to_string(l.total) + " for " +
                            std::to_string(entries) + " entries");
    }
    const uint64_t wavelets = 6 * uint64_t(t.size) * uint64_t(t.size);
    t.offsets.resize(wavelets + 1);
    std::memcpy(t.offsets.data(), p + l.offsets_at, 8 * t.offsets.size());
    t.vertices.resize(entries);
    if (entries) std::memcpy(t.vertices.data(), p + l.vertices_at, 4 * entries);
    t.vertex_step.resize(static_cast<std::size_t>(t.vertex_count));
    if (!t.vertex_step.empty()) {
      std::memcpy(t.vertex_step.data(), p + l.steps_at, 4 * t.vertex_step.size());
    }
    const std::size_t values = static_cast<std::size_t>(entries * t.channels);
    const unsigned char* src = p + l.values_at;
    switch (t.quantization) {
      case HaarQuantization::Float32:
        t.values_f32.resize(values);
        if (values) std::memcpy(t.values_f32.data(), src, 4 * values);
        break;
      case HaarQuantization::Bits16:
        t.values_i16.resize(values);
        if (values) std::memcpy(t.values_i16.data(), src, 2 * values);
        break;
      case HaarQuantization::Bits8:
        t.values_i8.resize(values);
        if (values) std::memcpy(t.values_i8.data(), src, values);
        break;
    }
    s = check_haar_arrays(t, name);
    if (!s.ok()) return s;
    return out;
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory while reading");
  } catch (const std::length_error&) {
    return fail(name, "out of memory while reading");
  }
}

Result<HaarTransferFile> read_haar_transfer_file(const std::string& path) {
  std::vector<unsigned char> bytes;
  Status s = detail::read_file_bytes(path, &bytes);
  if (!s.ok()) return s;
  return read_haar_transfer_data(bytes.data(), bytes.size(), path);
}

bool is_haar_transfer_file(const std::string& path) noexcept {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  unsigned char header[16] = {};
  const bool read = std::fread(header, 1, sizeof header, f) == sizeof header;
  std::fclose(f);
  uint32_t kind = 0;
  std::memcpy(&kind, header + detail::kOffKind, 4);
  return read && std::memcmp(header, "PRTC", 4) == 0 &&
         kind == static_cast<uint32_t>(TransferKind::Haar);
}

}  // namespace prt
