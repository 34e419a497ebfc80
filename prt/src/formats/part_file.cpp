// part_file.cpp — the part container of prt/formats/part_file.h (layout in docs/FORMAT.md).
#include "prt/formats/part_file.h"

#include <cstring>
#include <new>

#include "formats/binary_layout.h"
#include "prt/core/atomic_file.h"

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
  return kind == static_cast<uint32_t>(PartKind::ShTransfer);
}

// Checks the fields of the header and the section table of the `size` bytes at `b`.
Status check_layout(const unsigned char* b, std::size_t size, const std::string& name) {
  if (size < kPartHeaderSize)
    return fail(name, "truncated: " + std::to_string(size) + " bytes, not a part file");
  if (std::memcmp(b, kMagic, 4) != 0) return fail(name, "bad magic (not a .prtpart part file)");
  if (load_u32(b + kOffVersion) != kPartFileVersion)
    return fail(name, "part file version " + std::to_string(load_u32(b + kOffVersion)) +
                          " (this prt reads version " + std::to_string(kPartFileVersion) + ")");
  if (load_u32(b + kOffHeaderSize) != kPartHeaderSize) return fail(name, "bad header size");
  const Status recorded = detail::check_recorded_size(name, load_u64(b + kOffFileSize), size);
  if (!recorded.ok()) return recorded;
  const Status crc = detail::check_checksum(name, b, size, kPartChecksumOffset);
  if (!crc.ok()) return crc;
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
  const uint32_t sections = load_u32(b + kOffSectionCount);
  if (sections > kMaxSections) return fail(name, "too many sections");
  uint64_t end = align_up(kPartHeaderSize + uint64_t{sections} * kSectionRecordSize);
  if (end > size) return fail(name, "section table outside the file");
  for (uint32_t s = 0; s < sections; ++s) {
    const unsigned char* rec = b + kPartHeaderSize + s * kSectionRecordSize;
    const uint64_t offset = load_u64(rec + 8), bytes = load_u64(rec + 16);
    for (uint32_t t = 0; t < s; ++t)
      if (load_u32(b + kPartHeaderSize + t * kSectionRecordSize) == load_u32(rec))
        return fail(name, "section tag " + std::to_string(load_u32(rec)) + " appears twice");
    if (load_u32(rec + 4) != 0) return fail(name, "reserved section field is not zero");
    if (offset != end || offset % detail::kSectionAlignment != 0 || bytes > size - offset)
      return fail(name, "section " + std::to_string(s) + " lies outside its place in the file");
    end = align_up(offset + bytes);
  }
  if (end != size) return fail(name, "bytes after the last section");
  return Status::Ok();
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
    uint64_t size = align_up(kPartHeaderSize + part.sections.size() * kSectionRecordSize);
    std::vector<uint64_t> offsets;
    for (const PartSection& s : part.sections) {
      offsets.push_back(size);
      size = align_up(size + s.bytes.size());
    }
    std::vector<unsigned char> b(size, 0);
    std::memcpy(b.data(), kMagic, 4);
    store_u32(&b[kOffVersion], kPartFileVersion);
    store_u32(&b[kOffHeaderSize], kPartHeaderSize);
    store_u32(&b[kOffKind], static_cast<uint32_t>(part.kind));
    store_u32(&b[kOffIndex], part.index);
    store_u32(&b[kOffCount], part.count);
    store_u64(&b[kOffFingerprint], part.fingerprint);
    store_u64(&b[kOffTotalRows], part.total_rows);
    store_u64(&b[kOffFirstRow], part.first_row);
    store_u64(&b[kOffRowCount], part.row_count);
    store_u64(&b[kOffFileSize], size);
    store_u32(&b[kOffSectionCount], static_cast<uint32_t>(part.sections.size()));
    for (std::size_t s = 0; s < part.sections.size(); ++s) {
      unsigned char* rec = &b[kPartHeaderSize + s * kSectionRecordSize];
      store_u32(rec, part.sections[s].tag);
      store_u64(rec + 8, offsets[s]);
      store_u64(rec + 16, part.sections[s].bytes.size());
      if (!part.sections[s].bytes.empty())
        std::memcpy(&b[offsets[s]], part.sections[s].bytes.data(), part.sections[s].bytes.size());
    }
    store_u32(&b[kPartChecksumOffset],
              detail::file_checksum(b.data(), b.size(), kPartChecksumOffset));
    return write_file_atomically(path, b.data(), b.size());
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory");
  }
}

Status read_part_file(const std::string& path, PartFile* out) {
  try {
    std::vector<unsigned char> b;
    const Status read = detail::read_file_bytes(path, &b);
    if (!read.ok()) return read;
    const Status layout = check_layout(b.data(), b.size(), path);
    if (!layout.ok()) return layout;
    PartFile p;
    p.kind = static_cast<PartKind>(load_u32(&b[kOffKind]));
    p.index = load_u32(&b[kOffIndex]);
    p.count = load_u32(&b[kOffCount]);
    p.fingerprint = load_u64(&b[kOffFingerprint]);
    p.total_rows = load_u64(&b[kOffTotalRows]);
    p.first_row = load_u64(&b[kOffFirstRow]);
    p.row_count = load_u64(&b[kOffRowCount]);
    const uint32_t sections = load_u32(&b[kOffSectionCount]);
    for (uint32_t s = 0; s < sections; ++s) {
      const unsigned char* rec = &b[kPartHeaderSize + s * kSectionRecordSize];
      const uint64_t offset = load_u64(rec + 8), bytes = load_u64(rec + 16);
      PartSection section;
      section.tag = load_u32(rec);
      section.bytes.assign(b.begin() + static_cast<std::ptrdiff_t>(offset),
                           b.begin() + static_cast<std::ptrdiff_t>(offset + bytes));
      p.sections.push_back(std::move(section));
    }
    *out = std::move(p);
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory");
  }
}

}  // namespace prt
