// prt/formats/part_file.h — part files (`.prtpart`, magic "PRTP"): what one shard of a bake farm
// computed for its range of rows, to be merged with the other shards' parts into one output.
//
// A part is a container of tagged byte sections behind a fixed header (docs/FORMAT.md, "Part
// files"): which kind of work it holds (`kind`), which shard of how many (`index` of `count`),
// the fingerprint of the scene's positions (prt/formats/geometry_check.h), the rows it covers
// ([first_row, first_row + row_count) of total_rows), and the sections, whose contents the kind
// defines (bake/transfer_part.h for SH transfer). The whole file is protected by the CRC-32C of
// the coefficient files (prt/formats/crc32c.h), its recorded size and a checked section table,
// so a truncated or corrupt part is refused by name before anything reads its sections.
// Byte order little-endian; sections 16-byte aligned with zero padding; tags unique.
// Compiles as C++17.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "prt/core/status.h"

namespace prt {

// The container's format (2: the layout field; a part of another format is refused as written by
// another prt version).
inline constexpr uint32_t kPartFileVersion = 2;

// What a part holds (the header's kind field).
enum class PartKind : uint32_t {
  ShTransfer = 1,    // diffuse SH transfer: direct transfer, AO, bent normals, compact gather rows
  HaarTransfer = 2,  // Haar transfer: truncated wavelet vectors, or D̂ and gather rows
  FormFactorRows = 3,  // radiosity: rows of senders of the form-factor matrix
  GlossyTransfer = 4,  // glossy transfer matrices: direct matrices, front-face hits
};

// A section's bytes: its own (`bytes`); or `view_size` bytes at `view` owned by someone else (set
// view non-null; `bytes` is then ignored): the writer writes views without a copy, and the reader
// gives views into the file's mapping (PartFile::mapping keeps it alive); or, for the writer
// only, the caller's `pieces` one after another (a section held in several arrays, written
// without joining them; data() is then null).
struct PartPiece {
  const void* data;
  uint64_t size;
};

struct PartSection {
  uint32_t tag = 0;
  std::vector<unsigned char> bytes;
  const void* view = nullptr;
  uint64_t view_size = 0;
  std::vector<PartPiece> pieces;

  const unsigned char* data() const {
    if (!pieces.empty()) return nullptr;
    return view ? static_cast<const unsigned char*>(view) : bytes.data();
  }
  uint64_t size() const {
    if (pieces.empty()) return view ? view_size : bytes.size();
    uint64_t n = 0;
    for (const PartPiece& p : pieces) n += p.size;
    return n;
  }
  // The section's bytes as runs, in order (one run unless `pieces` are set).
  std::vector<PartPiece> runs() const {
    if (!pieces.empty()) return pieces;
    return {{data(), size()}};
  }
};

struct PartFile {
  PartKind kind = PartKind::ShTransfer;
  uint32_t index = 0, count = 1;  // shard `index` (0-based) of `count`
  uint64_t fingerprint = 0;       // geometry_fingerprint of the scene's positions
  uint64_t total_rows = 0, first_row = 0, row_count = 0;
  // The 8 bytes after the magic's version field that say which layout of the sections and which
  // settings table the writer used (the caller's choice, e.g. a hash of its section tags and
  // settings keys): written as given, read back, compared by the caller.
  uint64_t layout = 0;
  std::vector<PartSection> sections;
  std::shared_ptr<const void> mapping;  // read parts: the file's read-only mapping

  // The section with `tag`, or null.
  const PartSection* find(uint32_t tag) const;
};

// Writes `part` atomically (prt/core/atomic_file.h), section by section (no copy of the whole
// file in memory; the checksum is computed first). Errors name `path`.
Status write_part_file(const std::string& path, const PartFile& part);

// Reads and checks a part: maps the file read-only (its sections are views into the mapping,
// which `out->mapping` holds; no copy) and checks size, magic, version, recorded
// size ("truncated"), checksum, header fields (index < count, the row range inside total_rows, a
// known kind) and the section table (inside the file, aligned, in order without overlap, unique
// tags). Errors: one line naming `path`.
// The pages are released after the checksum pass (release_part_pages): the sections' bytes are
// read again from the file when used, so that the parts a merge reads are not all held at once.
Status read_part_file(const std::string& path, PartFile* out);

// Releases the pages wholly inside [data, data + size) of a read part's mapping from this
// process's memory (POSIX: madvise MADV_DONTNEED; the mapping is read-only and private, so the
// bytes are unchanged and a later read brings them back from the file): for bytes that have been
// copied or checked and are not needed again soon. A no-op for a null or empty range and where
// parts are read into a heap buffer. `data` must point into a mapping read_part_file made.
void release_part_pages(const void* data, uint64_t size);

}  // namespace prt
