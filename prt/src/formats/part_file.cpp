// part_file.cpp — the part container of prt/formats/part_file.h (layout in docs/FORMAT.md).
#include "prt/formats/part_file.h"

#if !defined(_WIN32)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

#include <cerrno>
#include <cstdio>
#include <cstring>
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
                      kOffRowCount = 48, kOffFileSize = 56, kOffSectionCount = 68, kOffLayout = 72,
                      kOffReserved = 80;

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
Status check_structure(const unsigned char* b, uint64_t size, const std::string& name) {
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
    store_u64(b + kOffLayout, part.layout);
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
      for (const PartPiece& run : part.sections[s].runs()) crc = crc32c(run.data, run.size, crc);
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
        for (const PartPiece& run : part.sections[s].runs())
          ok = ok && std::fwrite(run.data, 1, run.size, f) == run.size;
        ok = ok && std::fwrite(kZeros, 1, pad, f) == pad;
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

namespace {

#if defined(_WIN32)
// Without POSIX mmap: the whole file read into one heap buffer, freed with the last PartFile.
std::shared_ptr<const void> map_file(const std::string& path, uint64_t* size, Status* st) {
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (f == nullptr) {
    *st = fail(path, std::string("cannot open: ") + std::strerror(errno));
    return nullptr;
  }
  std::fseek(f, 0, SEEK_END);
  const long end = std::ftell(f);
  std::fseek(f, 0, SEEK_SET);
  *size = end > 0 ? static_cast<uint64_t>(end) : 0;
  if (*size < kPartHeaderSize) {
    *st = fail(path, "truncated: " + std::to_string(*size) + " bytes, not a part file");
    std::fclose(f);
    return nullptr;
  }
  std::shared_ptr<unsigned char> bytes(new (std::nothrow) unsigned char[*size],
                                       std::default_delete<unsigned char[]>());
  const bool read = bytes && std::fread(bytes.get(), 1, *size, f) == *size;
  std::fclose(f);
  if (!read) {
    *st = fail(path, bytes ? "cannot read" : "out of memory");
    return nullptr;
  }
  return bytes;
}
#else
// A whole file mapped read-only, unmapped when the last PartFile holding it goes.
std::shared_ptr<const void> map_file(const std::string& path, uint64_t* size, Status* st) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    *st = fail(path, std::string("cannot open: ") + std::strerror(errno));
    return nullptr;
  }
  struct stat info {};
  if (fstat(fd, &info) != 0 || !S_ISREG(info.st_mode)) {
    *st = fail(path, "cannot read: not a regular file");
    close(fd);
    return nullptr;
  }
  *size = static_cast<uint64_t>(info.st_size);
  if (*size < kPartHeaderSize) {
    *st = fail(path, "truncated: " + std::to_string(*size) + " bytes, not a part file");
    close(fd);
    return nullptr;
  }
  // MAP_POPULATE: the pages are read ahead and mapped in one go (every byte is read: checksum).
  void* map = mmap(nullptr, *size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
  const int saved = errno;
  close(fd);
  if (map == MAP_FAILED) {
    *st = fail(path, std::string("cannot map: ") + std::strerror(saved));
    return nullptr;
  }
  const std::size_t bytes = *size;
  return std::shared_ptr<const void>(
      map, [bytes](const void* p) { munmap(const_cast<void*>(p), bytes); });
}
#endif

// Magic, version, header size and the section table's extent, on the mapped header.
Status check_header(const unsigned char* b, uint64_t size, const std::string& path) {
  if (std::memcmp(b, kMagic, 4) != 0) return fail(path, "bad magic (not a .prtpart part file)");
  if (load_u32(b + kOffVersion) != kPartFileVersion)
    return fail(path, "written by another prt version (part file format " +
                          std::to_string(load_u32(b + kOffVersion)) + ", this prt reads format " +
                          std::to_string(kPartFileVersion) + "): bake it again with this prt");
  if (load_u32(b + kOffHeaderSize) != kPartHeaderSize) return fail(path, "bad header size");
  if (load_u32(b + kOffSectionCount) > kMaxSections) return fail(path, "too many sections");
  if (table_end(load_u32(b + kOffSectionCount)) > size)
    return fail(path, "section table outside the file");
  return check_structure(b, size, path);
}

}  // namespace

Status read_part_file(const std::string& path, PartFile* out) {
  try {
    uint64_t size = 0;
    Status st = Status::Ok();
    std::shared_ptr<const void> mapping = map_file(path, &size, &st);
    if (!mapping) return st;
    const unsigned char* b = static_cast<const unsigned char*>(mapping.get());
    st = check_header(b, size, path);
    if (!st.ok()) return st;
    const uint32_t sections = load_u32(b + kOffSectionCount);
    // The checksum in one pass over the mapped bytes: the header and table with the checksum
    // field taken as zero, then every section and its padding (they fill the rest of the file).
    const uint32_t stored = load_u32(b + kPartChecksumOffset);
    std::vector<unsigned char> head(b, b + table_end(sections));
    store_u32(head.data() + kPartChecksumOffset, 0);
    uint32_t crc = crc32c(head.data(), head.size());
    crc = crc32c(b + head.size(), size - head.size(), crc);
    if (crc != stored) {
      char text[96];
      std::snprintf(text, sizeof text, "checksum mismatch (stored 0x%08x, computed 0x%08x)", stored,
                    crc);
      return fail(path, text);
    }
    const Status fields = check_fields(b, path);
    if (!fields.ok()) return fields;
    release_part_pages(b, size);  // read again when the sections are used
    PartFile p;
    for (uint32_t s = 0; s < sections; ++s) {
      const unsigned char* rec = b + kPartHeaderSize + s * kSectionRecordSize;
      PartSection section;
      section.tag = load_u32(rec);
      section.view = b + load_u64(rec + 8);
      section.view_size = load_u64(rec + 16);
      p.sections.push_back(std::move(section));
    }
    p.kind = static_cast<PartKind>(load_u32(b + kOffKind));
    p.index = load_u32(b + kOffIndex);
    p.count = load_u32(b + kOffCount);
    p.fingerprint = load_u64(b + kOffFingerprint);
    p.total_rows = load_u64(b + kOffTotalRows);
    p.first_row = load_u64(b + kOffFirstRow);
    p.row_count = load_u64(b + kOffRowCount);
    p.layout = load_u64(b + kOffLayout);
    p.mapping = std::move(mapping);
    *out = std::move(p);
    return Status::Ok();
  } catch (const std::bad_alloc&) {
    return fail(path, "out of memory");
  }
}

void release_part_pages(const void* data, uint64_t size) {
#if defined(_WIN32)
  (void)data;
  (void)size;
#else
  if (data == nullptr || size == 0) return;
  const long page_size = sysconf(_SC_PAGESIZE);
  const uintptr_t page = page_size > 0 ? static_cast<uintptr_t>(page_size) : 4096;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(data);
  const uintptr_t first = (begin + page - 1) / page * page, end = (begin + size) / page * page;
  if (end > first)
    madvise(reinterpret_cast<void*>(first), end - first, MADV_DONTNEED);  // advice: may fail
#endif
}

}  // namespace prt
