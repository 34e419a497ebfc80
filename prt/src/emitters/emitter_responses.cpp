// emitter_responses.cpp — see prt/emitters/emitter_responses.h; byte layout in docs/FORMAT.md.
#include "prt/emitters/emitter_responses.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <new>
#include <set>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"
#include "prt/formats/geometry_check.h"

#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "prt emitter-response files are little-endian; this reader copies arrays directly"
#endif

namespace prt {
namespace {

constexpr uint64_t kHeaderSize = 64;
constexpr uint64_t kRecordSize = 16;  // u32 name_size, f32 r, g, b
// Header field offsets (docs/FORMAT.md).
constexpr std::size_t kOffVersion = 4, kOffHeaderSize = 8, kOffEmitters = 12, kOffVertices = 16,
                      kOffTriangles = 24, kOffFingerprint = 32, kOffFileSize = 40,
                      kOffChecksum = 48, kOffNameBytes = 52, kOffReserved = 56;

using detail::fail;
using detail::load_u32;
using detail::load_u64;
using detail::store_u32;
using detail::store_u64;

// An emitter name as messages show it: control characters (a file may hold any bytes) as \xNN,
// so that every message stays on one line.
std::string shown(const std::string& name) {
  std::string out;
  for (const char ch : name) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u != 0x7f) {
      out += ch;
      continue;
    }
    char escaped[5];
    std::snprintf(escaped, sizeof escaped, "\\x%02x", u);
    out += escaped;
  }
  return out;
}

uint64_t pad4(uint64_t n) {
  return (n + 3) & ~uint64_t{3};
}

// Total file size for the counts (operands bounded by the caller: no overflow).
uint64_t layout_size(uint64_t e, uint64_t v, uint64_t t, uint64_t name_bytes) {
  return kHeaderSize + kRecordSize * e + pad4(name_bytes) + 24 * v + 12 * t + 12 * v * e;
}

bool finite_non_negative(float x) {
  return std::isfinite(x) && x >= 0.f;
}

Status check_values(const EmitterResponses& d, const std::string& name) {
  const std::size_t v_count = d.vertex_count();
  for (std::size_t i = 0; i < d.positions.size(); ++i)
    if (!std::isfinite(d.positions[i]) || !std::isfinite(d.normals[i]))
      return fail(name, "vertex " + std::to_string(i / 3) + ": position or normal not finite");
  for (std::size_t i = 0; i < d.triangles.size(); ++i)
    if (d.triangles[i] >= v_count)
      return fail(name, "triangle " + std::to_string(i / 3) + ": vertex index " +
                            std::to_string(d.triangles[i]) + " out of range");
  for (std::size_t i = 0; i < d.responses.size(); ++i)
    if (!finite_non_negative(d.responses[i])) {
      const std::size_t e = i / 3 / (v_count ? v_count : 1), v = (i / 3) % (v_count ? v_count : 1);
      return fail(name, "emitter " + shown(d.emitters[e].name) + ", vertex " + std::to_string(v) +
                            ": response " + std::to_string(d.responses[i]) +
                            " is negative, NaN or infinite");
    }
  return Status::Ok();
}

}  // namespace

Status validate_emitter_responses(const EmitterResponses& d, const std::string& name) {
  if (d.emitters.empty() || d.emitters.size() > kMaxEmitters)
    return fail(name, std::to_string(d.emitters.size()) + " emitters (must be 1.." +
                          std::to_string(kMaxEmitters) + ")");
  std::set<std::string> names;
  for (const EmitterInfo& e : d.emitters) {
    if (e.name.empty() || e.name.size() > kMaxEmitterNameBytes)
      return fail(name, "emitter name of " + std::to_string(e.name.size()) + " bytes (must be 1.." +
                            std::to_string(kMaxEmitterNameBytes) + ")");
    if (!names.insert(e.name).second)
      return fail(name, "emitter " + shown(e.name) + " appears twice");
    for (float c : e.emission)
      if (!finite_non_negative(c))
        return fail(name, "emitter " + shown(e.name) + ": emission " + std::to_string(c) +
                              " is negative, NaN or infinite");
  }
  if (d.positions.size() % 3 != 0 || d.triangles.size() % 3 != 0)
    return fail(name, "positions and triangles must hold 3 values each");
  const std::size_t v = d.vertex_count();
  if (v > kMaxResponseVertices || d.triangle_count() > kMaxResponseVertices)
    return fail(name, "too many vertices or triangles (at most 2^32 - 1)");
  if (d.normals.size() != d.positions.size())
    return fail(name, "normal count differs from the vertex count");
  if (d.responses.size() != 3 * v * d.emitters.size())
    return fail(name, "response count " + std::to_string(d.responses.size()) + " is not 3 x " +
                          std::to_string(v) + " vertices x " + std::to_string(d.emitters.size()) +
                          " emitters");
  if (Status s = check_values(d, name); !s.ok()) return s;
  if (d.fingerprint != 0 && d.fingerprint != geometry_fingerprint(d.positions.data(), v))
    return fail(name, "fingerprint does not match the positions");
  return Status::Ok();
}

Result<std::vector<unsigned char>> encode_emitter_responses(const EmitterResponses& d,
                                                            const std::string& name) {
  if (Status s = validate_emitter_responses(d, name); !s.ok()) return s;
  uint64_t name_bytes = 0;
  for (const EmitterInfo& e : d.emitters) name_bytes += e.name.size();
  const uint64_t v = d.vertex_count(), t = d.triangle_count(), e_count = d.emitters.size();
  const uint64_t size = layout_size(e_count, v, t, name_bytes);
  std::vector<unsigned char> out;
  try {
    out.assign(static_cast<std::size_t>(size), 0);
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory");
  }
  unsigned char* h = out.data();
  std::memcpy(h, "PRTE", 4);
  store_u32(h + kOffVersion, kEmitterResponsesVersion);
  store_u32(h + kOffHeaderSize, static_cast<uint32_t>(kHeaderSize));
  store_u32(h + kOffEmitters, static_cast<uint32_t>(e_count));
  store_u64(h + kOffVertices, v);
  store_u64(h + kOffTriangles, t);
  store_u64(h + kOffFingerprint, geometry_fingerprint(d.positions.data(), v));
  store_u64(h + kOffFileSize, size);
  store_u32(h + kOffNameBytes, static_cast<uint32_t>(name_bytes));
  unsigned char* at = h + kHeaderSize;
  for (const EmitterInfo& e : d.emitters) {
    store_u32(at, static_cast<uint32_t>(e.name.size()));
    std::memcpy(at + 4, e.emission.data(), 12);
    at += kRecordSize;
  }
  for (const EmitterInfo& e : d.emitters) {
    std::memcpy(at, e.name.data(), e.name.size());
    at += e.name.size();
  }
  at = h + kHeaderSize + kRecordSize * e_count + pad4(name_bytes);
  const auto copy = [&at](const void* src, std::size_t bytes) {
    if (bytes) std::memcpy(at, src, bytes);
    at += bytes;
  };
  copy(d.positions.data(), 4 * d.positions.size());
  copy(d.normals.data(), 4 * d.normals.size());
  copy(d.triangles.data(), 4 * d.triangles.size());
  copy(d.responses.data(), 4 * d.responses.size());
  store_u32(h + kOffChecksum, detail::file_checksum(out.data(), out.size(), kOffChecksum));
  return out;
}

Status write_emitter_responses(const std::string& path, const EmitterResponses& data) {
  Result<std::vector<unsigned char>> bytes = encode_emitter_responses(data, path);
  if (!bytes.ok()) return bytes.status();
  return write_file_atomically(path, bytes->data(), bytes->size());
}

namespace {

// Header checks (docs/FORMAT.md steps 1–4); on success the counts are bounded and consistent.
Status check_header(const unsigned char* b, std::size_t size, const std::string& name) {
  if (size < kHeaderSize)
    return fail(name, "truncated (" + std::to_string(size) + " bytes, header needs 64)");
  if (std::memcmp(b, "PRTE", 4) != 0) return fail(name, "bad magic (not an emitter-response file)");
  if (load_u32(b + kOffVersion) != kEmitterResponsesVersion)
    return fail(name, "unsupported version " + std::to_string(load_u32(b + kOffVersion)));
  if (load_u32(b + kOffHeaderSize) != kHeaderSize) return fail(name, "bad header size");
  const uint64_t file_size = load_u64(b + kOffFileSize);
  if (file_size > size)
    return fail(name, "truncated (" + std::to_string(size) + " of " + std::to_string(file_size) +
                          " bytes)");
  if (file_size < size)
    return fail(name, std::to_string(size - file_size) + " unexpected bytes after the end");
  if (detail::file_checksum(b, size, kOffChecksum) != load_u32(b + kOffChecksum))
    return fail(name, "checksum mismatch (corrupt)");
  const uint64_t e = load_u32(b + kOffEmitters), v = load_u64(b + kOffVertices),
                 t = load_u64(b + kOffTriangles), n = load_u32(b + kOffNameBytes);
  if (load_u64(b + kOffReserved) != 0) return fail(name, "reserved field is not zero");
  if (e < 1 || e > kMaxEmitters) return fail(name, "bad emitter count " + std::to_string(e));
  if (v > kMaxResponseVertices || t > kMaxResponseVertices)
    return fail(name, "vertex or triangle count too large");
  if (n > e * kMaxEmitterNameBytes) return fail(name, "bad name size");
  if (layout_size(e, v, t, n) != file_size)
    return fail(name, "file size does not match the counts in the header");
  return Status::Ok();
}

}  // namespace

Result<EmitterResponses> decode_emitter_responses(const void* bytes, std::size_t size,
                                                  const std::string& name) {
  const unsigned char* b = static_cast<const unsigned char*>(bytes);
  if (Status s = check_header(b, size, name); !s.ok()) return s;
  const uint64_t e = load_u32(b + kOffEmitters), v = load_u64(b + kOffVertices),
                 t = load_u64(b + kOffTriangles), n = load_u32(b + kOffNameBytes);
  EmitterResponses d;
  try {
    d.emitters.resize(e);
    const unsigned char* names = b + kHeaderSize + kRecordSize * e;
    uint64_t name_at = 0;
    for (uint64_t i = 0; i < e; ++i) {
      const unsigned char* record = b + kHeaderSize + kRecordSize * i;
      const uint64_t length = load_u32(record);
      if (length > n - name_at) return fail(name, "emitter names overrun their section");
      d.emitters[i].name.assign(reinterpret_cast<const char*>(names + name_at), length);
      std::memcpy(d.emitters[i].emission.data(), record + 4, 12);
      name_at += length;
    }
    if (name_at != n) return fail(name, "emitter name sizes do not add up to the name section");
    for (uint64_t i = n; i < pad4(n); ++i)
      if (names[i] != 0) return fail(name, "name padding is not zero");
    const unsigned char* at = names + pad4(n);
    const auto take = [&at](auto* dst, std::size_t count) {
      dst->resize(count);
      if (count) std::memcpy(dst->data(), at, 4 * count);
      at += 4 * count;
    };
    take(&d.positions, 3 * v);
    take(&d.normals, 3 * v);
    take(&d.triangles, 3 * t);
    take(&d.responses, 3 * v * e);
  } catch (const std::bad_alloc&) {
    return fail(name, "out of memory");
  }
  d.fingerprint = load_u64(b + kOffFingerprint);
  if (d.fingerprint != geometry_fingerprint(d.positions.data(), v))
    return fail(name, "fingerprint does not match the positions");
  if (Status s = validate_emitter_responses(d, name); !s.ok()) return s;
  return d;
}

Result<EmitterResponses> read_emitter_responses(const std::string& path) {
  std::vector<unsigned char> bytes;
  if (Status s = detail::read_file_bytes(path, &bytes); !s.ok()) return s;
  return decode_emitter_responses(bytes.data(), bytes.size(), path);
}

bool is_emitter_responses_file(const std::string& path) noexcept {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return false;
  char magic[4] = {};
  const bool read = std::fread(magic, 1, 4, f) == 4;
  std::fclose(f);
  return read && std::memcmp(magic, "PRTE", 4) == 0;
}

Result<std::vector<float>> emitter_colors(const EmitterResponses& data,
                                          const std::vector<EmitterColor>& colors) {
  std::vector<float> out(3 * data.emitters.size());
  for (std::size_t e = 0; e < data.emitters.size(); ++e)
    for (int c = 0; c < 3; ++c) out[3 * e + c] = data.emitters[e].emission[c];
  for (const EmitterColor& color : colors) {
    std::size_t e = 0;
    while (e < data.emitters.size() && data.emitters[e].name != color.name) ++e;
    if (e == data.emitters.size()) {
      std::string known;
      for (const EmitterInfo& info : data.emitters)
        known += (known.empty() ? "" : ", ") + shown(info.name);
      return Status::Error("emitter " + shown(color.name) +
                           ": no such emitter (emitters: " + known + ")");
    }
    for (int c = 0; c < 3; ++c) {
      if (!finite_non_negative(color.rgb[c]))
        return Status::Error("emitter " + shown(color.name) + ": colour component " +
                             std::to_string(color.rgb[c]) + " is negative, NaN or infinite");
      out[3 * e + c] = color.rgb[c];
    }
  }
  return out;
}

Status recombine_emitters(const EmitterResponses& data, const std::vector<float>& colors_rgb,
                          float* out_rgb, bool accumulate) {
  const std::size_t e_count = data.emitters.size(), v_count = data.vertex_count();
  if (colors_rgb.size() != 3 * e_count)
    return Status::Error("recombine_emitters: " + std::to_string(colors_rgb.size()) +
                         " colour values for " + std::to_string(e_count) + " emitters");
  for (float c : colors_rgb)
    if (!finite_non_negative(c))
      return Status::Error("recombine_emitters: colour " + std::to_string(c) +
                           " is negative, NaN or infinite");
  if (data.responses.size() != 3 * v_count * e_count)
    return Status::Error("recombine_emitters: response array does not match the counts");
  const float* r = data.responses.data();
  for (std::size_t v = 0; v < v_count; ++v) {
    double sum[3] = {0, 0, 0};
    for (std::size_t e = 0; e < e_count; ++e) {
      const float* rv = r + 3 * (e * v_count + v);
      for (int c = 0; c < 3; ++c) sum[c] += double(colors_rgb[3 * e + c]) * double(rv[c]);
    }
    for (int c = 0; c < 3; ++c) {
      const double base = accumulate ? double(out_rgb[3 * v + c]) : 0.0;
      out_rgb[3 * v + c] = static_cast<float>(base + sum[c]);
    }
  }
  return Status::Ok();
}

}  // namespace prt
