// binary_layout.cpp — the pieces the binary files of prt share; see binary_layout.h.
#include "formats/binary_layout.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <numeric>

#include "prt/formats/crc32c.h"

namespace prt::detail {

Status fail(const std::string& name, const std::string& problem) {
  return Status::Error(name + ": " + problem);
}

uint32_t file_checksum(const unsigned char* bytes, std::size_t size, std::size_t checksum_offset) {
  static const unsigned char zeros[4] = {0, 0, 0, 0};
  uint32_t crc = crc32c(bytes, checksum_offset);
  crc = crc32c(zeros, 4, crc);
  return crc32c(bytes + checksum_offset + 4, size - checksum_offset - 4, crc);
}

Status check_recorded_size(const std::string& name, uint64_t recorded, std::size_t size) {
  if (recorded > size) {
    return fail(name, "truncated: header says " + std::to_string(recorded) + " bytes, only " +
                          std::to_string(size) + " present");
  }
  if (recorded < size) {
    return fail(name, std::to_string(size - recorded) + " unexpected bytes after the " +
                          std::to_string(recorded) + " the header announces");
  }
  return Status::Ok();
}

Status check_checksum(const std::string& name, const unsigned char* bytes, std::size_t size,
                      std::size_t checksum_offset) {
  const uint32_t stored = load_u32(bytes + checksum_offset);
  const uint32_t actual = file_checksum(bytes, size, checksum_offset);
  if (stored == actual) return Status::Ok();
  char text[96];
  std::snprintf(text, sizeof text, "checksum mismatch (stored 0x%08x, computed 0x%08x)", stored,
                actual);
  return fail(name, text);
}

Status check_section_table(const std::string& name, int count, const uint64_t* offsets,
                           const uint64_t* sizes, const char* const* names,
                           const uint64_t* expected, uint64_t header_size, uint64_t file_size,
                           uint64_t vertex_count) {
  for (int s = 0; s < count; ++s) {
    if (expected[s] != kAnySize && sizes[s] != expected[s]) {
      return fail(name, std::string(names[s]) + " section holds " + std::to_string(sizes[s]) +
                            " bytes, expected " + std::to_string(expected[s]) + " for " +
                            std::to_string(vertex_count) + " vertices");
    }
    if (sizes[s] == 0) {
      if (offsets[s] != 0) {
        return fail(name, std::string("empty ") + names[s] + " section has an offset");
      }
      continue;
    }
    if (offsets[s] % kSectionAlignment != 0 || offsets[s] < header_size || offsets[s] > file_size ||
        sizes[s] > file_size - offsets[s]) {
      return fail(name, std::string(names[s]) + " section [" + std::to_string(offsets[s]) + ", +" +
                            std::to_string(sizes[s]) + ") lies outside the " +
                            std::to_string(file_size) + "-byte file or is misaligned");
    }
  }
  // Sections must not overlap.
  std::vector<int> by_offset(static_cast<std::size_t>(count));
  std::iota(by_offset.begin(), by_offset.end(), 0);
  std::sort(by_offset.begin(), by_offset.end(),
            [&](int a, int c) { return offsets[a] < offsets[c]; });
  uint64_t previous_end = header_size;
  for (int s : by_offset) {
    if (sizes[s] == 0) continue;
    if (offsets[s] < previous_end) {
      return fail(name, std::string(names[s]) + " section overlaps another");
    }
    previous_end = offsets[s] + sizes[s];
  }
  return Status::Ok();
}

uint64_t primitive_table_bytes(const std::vector<PrimitiveRange>& primitives) {
  uint64_t names = 0;
  for (const PrimitiveRange& p : primitives) names += p.name.size();
  return primitives.size() * kPrimitiveRecordSize + names;
}

void write_primitive_table(unsigned char* table, const std::vector<PrimitiveRange>& primitives) {
  uint64_t name_at = primitives.size() * kPrimitiveRecordSize;
  for (std::size_t i = 0; i < primitives.size(); ++i) {
    const PrimitiveRange& p = primitives[i];
    unsigned char* r = table + i * kPrimitiveRecordSize;
    store_u64(r, p.first_vertex);
    store_u64(r + 8, p.vertex_count);
    store_u64(r + 16, name_at);
    store_u64(r + 24, p.name.size());
    if (!p.name.empty()) std::memcpy(table + name_at, p.name.data(), p.name.size());
    name_at += p.name.size();
  }
}

Status read_primitive_table(const unsigned char* table, uint64_t section_size, uint64_t count,
                            uint64_t vertex_count, bool check_ranges, const std::string& name,
                            std::vector<PrimitiveRange>* out) {
  const uint64_t records = count * kPrimitiveRecordSize, v = vertex_count;
  out->resize(static_cast<std::size_t>(count));
  for (std::size_t i = 0; i < out->size(); ++i) {
    const unsigned char* r = table + i * kPrimitiveRecordSize;
    PrimitiveRange& p = (*out)[i];
    p.first_vertex = load_u64(r);
    p.vertex_count = load_u64(r + 8);
    const uint64_t name_offset = load_u64(r + 16), name_size = load_u64(r + 24);
    if (name_offset < records || name_offset > section_size ||
        name_size > section_size - name_offset) {
      return fail(name,
                  "name of primitive " + std::to_string(i) + " lies outside the primitive table");
    }
    if (check_ranges && (p.first_vertex > v || p.vertex_count > v - p.first_vertex)) {
      return fail(name, "primitive " + std::to_string(i) + " covers vertices beyond the " +
                            std::to_string(v) + " vertices");
    }
    p.name.assign(reinterpret_cast<const char*>(table + name_offset),
                  static_cast<std::size_t>(name_size));
  }
  return Status::Ok();
}

}  // namespace prt::detail
