// part_file.cpp — the part container of prt/formats/part_file.h (layout in docs/FORMAT.md).
#include "prt/formats/part_file.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <new>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"
#include "prt/formats/crc32c.h"

namespace prt {
namespace {

using detail::align_up;
using detail::fail;
using detail::load_u32;
using detail::load_u64;
using detail::store_u32;
using detail::store_u64;

constexpr std::size_t kPartHeaderSize = 96;
constexpr std::size_t kPartChecksumOffset = 64;
constexpr std::size_t kSectionRecordSize = 24;  // u32 tag, u32 reserved, u64 offset, u64 size
constexpr uint32_t kMaxSections = 64;
constexpr unsigned char kMagic[4] = {'P', 'R', 'T', 'P'};

// Header field offsets.
constexpr std::size_t kOffVersion = 4, kOffHeaderSize = 8, kOffKind = 12, kOffIndex = 16,
                      kOffCount = 20, kOffFingerprint = 24, kOffTotalRows = 32, kOffFirstRow = 40,
                      kOffRowCount = 48, kOffFileSize = 56, kOffSectionCount = 68,
                      kOffReserved = 72;

bool known_kind(uint32_t kind) {
  return kind == static_cast<uint32_t>(PartKind::ShTransfer) ||
         kind == static_cast<uint32_t>(PartKind::HaarTransfer) ||
         kind == static_cast<uint32_t>(PartKind::FormFactorRows) ||
         kind == static_cast<uint32_t>(PartKind::GlossyTransfer);
}

constexpr unsigned char kZeros[16] = {};

// The bytes [0, table_end) of a part: header, section table, padding.
uint64_t table_end(uint32_t sections) {
  return align_up(kPartHeaderSize + uint64_t{sections} * kSectionRecordSize);
}

// Checks what must hold before the sections can be read from a `size`-byte file whose first
// table_end bytes are `head`: magic, version, header size, recorded size, the section table's
// places (each section right after the previous, aligned, inside the file, the last ending the
// file) and unique tags.
Status check_structure(const std::vector<unsigned char>& head, uint64_t size,
                       const std::string& name) {
  const unsigned char* b = head.data();
  const Status recorded = detail::check_recorded_size(name, load_u64(b + kOffFileSize), size);
  if (!recorded.ok()) return recorded;
  const uint32_t sections = load_u32(b + kOffSectionCount);
  uint64_t end = table_end(sections);
  for (uint32_t s = 0; s < sections; ++s) {
    const unsigned char* rec = b + kPartHeaderSize + s * kSectionRecordSize;
    const uint64_t offset = load_u64(rec + 8), bytes = load_u64(rec + 16);
    for (uint32_t t = 0; t < s; ++t)
      if (load_u32(b + kPartHeaderSize + t * kSectionRecordSize) == load_u32(rec))
        return fail(name, "section tag " + std::to_string(load_u32(rec)) + " appears twice");
    if (load_u32(rec + 4) != 0) return fail(name, "reserved section field is not zero");
    if (offset != end || bytes > size - offset)
      return fail(name, "section " + std::to_string(s) + " lies outside its place in the file");
    end = align_up(offset + bytes);
  }
  if (end != size) return fail(name, "bytes after the last section");
  return Status::Ok();
}

// The header's fields, after the checksum: kind, shard, row range, reserved bytes.
Status check_fields(const unsigned char* b, const std::string& name) {
  if (!known_kind(load_u32(b + kOffKind)))
    return fail(name, "unknown part kind " + std::to_string(load_u32(b + kOffKind)));
  const uint32_t index = load_u32(b + kOffIndex), count = load_u32(b + kOffCount);
  if (count == 0 || index >= count)
    return fail(name, "shard " + std::to_string(index) + "/" + std::to_string(count) +
                          " is not a shard (index must be below the count)");
  const uint64_t total = load_u64(b + kOffTotalRows), first = load_u64(b + kOffFirstRow),
                 rows = load_u64(b + kOffRowCount);
  if (first > total || rows > total - first) return fail(name, "row range outside the rows");
  for (std::size_t off = kOffReserved; off < kPartHeaderSize; ++off)
    if (b[off] != 0) return fail(name, "reserved header bytes are not zero");
  return Status::Ok();
}

Status read_failure(const std::string& name, std::FILE* f) {
  const bool eof = std::feof(f) != 0;
  std::fclose(f);
  return fail(
      name, eof ? "truncated while reading" : std::string("cannot read: ") + std::strerror(errno));
}

}  // namespace

const PartSection* PartFile::find(uint32_t tag) const {
  for (const PartSection& s : sections)
    if (s.tag == tag) return &s;
  return nullptr;
}

Status write_part_file(const std::string& path, const PartFile& part) {
  if (part.count == 0 || part.index >= part.count || part.sections.size() > kMaxSections)
    return fail(path, "invalid part (shard index, count or sections)");
  try {
    const uint32_t sections = static_cast<uint32_t>(part.sections.size());
    std::vector<unsigned char> head(table_end(sections), 0);
    uint64_t size = head.size();
    std::vector<uint64_t> offsets;
    for (const PartSection& s : part.sections) {
      offsets.push_back(size);
      size = align_up(size + s.size());
    }
    unsigned char* b = head.data();
    std::memcpy(b, kMagic, 4);
    store_u32(b + kOffVersion, kPartFileVersion);
    store_u32(b + kOffHeaderSize, kPartHeaderSize);
    store_u32(b + kOffKind, static_cast<uint32_t>(part.kind));
    store_u32(b + kOffIndex, part.index);
    store_u32(b + kOffCount, part.count);
    store_u64(b + kOffFingerprint, part.fingerprint);
    store_u64(b + kOffTotalRows, part.total_rows);
    store_u64(b + kOffFirstRow, part.first_row);
    store_u64(b + kOffRowCount, part.row_count);
    store_u64(b + kOffFileSize, size);
    store_u32(b + kOffSectionCount, sections);
    for (uint32_t s = 0; s < sections; ++s) {
      unsigned char* rec = b + kPartHeaderSize + s * kSectionRecordSize;
      store_u32(rec, part.sections[s].tag);
      store_u64(rec + 8, offsets[s]);
      store_u64(rec + 16, part.sections[s].size());
    }
    // The checksum over the file as it will be written (its own field zero), then the file.
    uint32_t crc = crc32c(b, head.size());
    for (uint32_t s = 0; s < sections; ++s) {
      const uint64_t n = part.sections[s].size();
      crc = crc32c(part.sections[s].data(), n, crc);
      crc = crc32c(kZeros, align_up(offsets[s] + n) - (offsets[s] + n), crc);
    }
    store_u32(b + kPartChecksumOffset, crc);
    return replace_file_atomically(path, [&](const std::string& temporary) {
      std::FILE* f = std::fopen(temporary.c_str(), "wb");
      if (f == nullptr)
        return fail(path, "cannot create " + temporary + ": " + std::strerror(errno));
      bool ok = std::fwrite(b, 1, head.size(), f) == head.size();
      for (uint32_t s = 0; s < sections && ok; ++s) {
        const uint64_t n = part.sections[s].size(),
                       pad = align_up(offsets[s] + n) - (offsets[s] + n);
        ok = std::fwrite(part.sections[s].data(), 1, n, f) == n &&
             std::fwrite(kZeros, 1, pad, f) == pad;
      }
      int saved_errno = errno;
      ok = (std::fflush(f) == 0) && ok;
      if (ok) saved_errno = errno;
      ok = (std::fclose(f) == 0) && ok;
      if (!ok) return fail(path, "cannot write " + temporary + ": " + std::strerror(saved_errno));
      return Status::Ok();
    });
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory");
  }
}

Status read_part_file(const std::string& path, PartFile* out) {
  std::error_code ec;
  const uint64_t size = std::filesystem::file_size(path, ec);
  if (ec) return fail(path, "cannot read: " + ec.message());
  if (size < kPartHeaderSize)
    return fail(path, "truncated: " + std::to_string(size) + " bytes, not a part file");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) return fail(path, std::string("cannot open: ") + std::strerror(errno));
  try {
    std::vector<unsigned char> head(kPartHeaderSize);
    if (std::fread(head.data(), 1, head.size(), f) != head.size()) return read_failure(path, f);
    const unsigned char* b = head.data();
    Status st = Status::Ok();
    if (std::memcmp(b, kMagic, 4) != 0)
      st = fail(path, "bad magic (not a .prtpart part file)");
    else if (load_u32(b + kOffVersion) != kPartFileVersion)
      st = fail(path, "part file version " + std::to_string(load_u32(b + kOffVersion)) +
                          " (this prt reads version " + std::to_string(kPartFileVersion) + ")");
    else if (load_u32(b + kOffHeaderSize) != kPartHeaderSize)
      st = fail(path, "bad header size");
    else if (load_u32(b + kOffSectionCount) > kMaxSections)
      st = fail(path, "too many sections");
    else if (table_end(load_u32(b + kOffSectionCount)) > size)
      st = fail(path, "section table outside the file");
    if (st.ok()) {
      const uint32_t sections = load_u32(b + kOffSectionCount);
      head.resize(table_end(sections));
      if (std::fread(head.data() + kPartHeaderSize, 1, head.size() - kPartHeaderSize, f) !=
          head.size() - kPartHeaderSize)
        return read_failure(path, f);
      st = check_structure(head, size, path);
    }
    if (!st.ok()) {
      std::fclose(f);
      return st;
    }
    b = head.data();
    PartFile p;
    const uint32_t sections = load_u32(b + kOffSectionCount);
    const uint32_t stored = load_u32(b + kPartChecksumOffset);
    std::vector<unsigned char> zeroed = head;
    store_u32(zeroed.data() + kPartChecksumOffset, 0);
    uint32_t crc = crc32c(zeroed.data(), zeroed.size());
    unsigned char pad[16];
    for (uint32_t s = 0; s < sections; ++s) {
      const unsigned char* rec = b + kPartHeaderSize + s * kSectionRecordSize;
      const uint64_t offset = load_u64(rec + 8), bytes = load_u64(rec + 16);
      PartSection section;
      section.tag = load_u32(rec);
      section.bytes.resize(bytes);
      const uint64_t n = align_up(offset + bytes) - (offset + bytes);
      if (std::fread(section.bytes.data(), 1, bytes, f) != bytes || std::fread(pad, 1, n, f) != n)
        return read_failure(path, f);
      crc = crc32c(section.bytes.data(), bytes, crc);
      crc = crc32c(pad, n, crc);
      p.sections.push_back(std::move(section));
    }
    std::fclose(f);
    if (crc != stored) {
      char text[96];
      std::snprintf(text, sizeof text, "checksum mismatch (stored 0x%08x, computed 0x%08x)", stored,
                    crc);
      return fail(path, text);
    }
    const Status fields = check_fields(b, path);
    if (!fields.ok()) return fields;
    p.kind = static_cast<PartKind>(load_u32(b + kOffKind));
    p.index = load_u32(b + kOffIndex);
    p.count = load_u32(b + kOffCount);
    p.fingerprint = load_u64(b + kOffFingerprint);
    p.total_rows = load_u64(b + kOffTotalRows);
    p.first_row = load_u64(b + kOffFirstRow);
    p.row_count = load_u64(b + kOffRowCount);
    *out = std::move(p);
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    std::fclose(f);
    return fail(path, "out of memory");
  }
}

}  // namespace prt
