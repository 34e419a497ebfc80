// prt/formats/cpca_file.h — the CPCA glossy transfer file (`.prtq`): a CpcaTransfer
// (prt/glossy/cpca_transfer.h) on disk, byte by byte in docs/GLOSSY_CPCA.md ("File format"). It
// holds the compressed matrices only; positions, frames and materials stay with the glossy transfer
// it was made from, which the geometry fingerprint names — unless the file carries them itself in
// its SOURCE SECTION (header flag bit 0, written by `prt compress`): the positions, normals,
// tangents, materials, primitives and metadata of that glossy transfer, so that a `.prtq` relights
// on its own. The section is stored as a glossy transfer file (prt/formats/glossy_transfer_file.h)
// of order 1 whose 1×1 matrices are zero (binary16); its matrices mean nothing and are dropped on
// reading. Nothing here throws; failures return prt::Status with one line naming the file. Compiles
// as C++17.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/transfer.h"

namespace prt {

inline constexpr uint32_t kCpcaFlagSource = 1;  // header flags: a source section follows
inline constexpr uint32_t kCpcaFlagRecord = 2;  // header flags: a compression record follows
// Version 2 added the compression record (flag bit 1); version 1 files (no record) still read.
inline constexpr uint32_t kCpcaFileVersion = 2;

// A `.prtq` with its optional source section. `source` (when has_source) has every field of
// the glossy transfer the CPCA was made from except the matrices (empty); its order, channels,
// vertex count and fingerprint equal the CPCA's.
// `record_json` (version 2, empty when absent) is the compression record: a UTF-8 JSON object
// that `prt compress` writes (its settings, the error it reached and in which metric, and the
// source bake's settings); this layer stores it as text and does not parse it.
struct CpcaFile {
  CpcaTransfer cpca;
  bool has_source = false;
  GlossyTransferData source;
  std::string record_json;
};

// True when `bytes` start with the CPCA magic "PRCP" (size ≥ 4).
bool is_cpca_transfer_file(const void* bytes, std::size_t size);

// The file's bytes (exactly cpca.payload_bytes() of them). Errors: cpca_validate's.
Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& cpca);

// The same with the source section taken from `source` (its matrices are not read; it must
// have the CPCA's vertex count, order and channels, and its geometry fingerprint must equal
// cpca.fingerprint when that is not 0). The file then has 8 + (section) more bytes.
Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& cpca,
                                                    const GlossyTransferData& source);

// Parses and checks everything (magic, version, sizes, checksum, ids, finiteness).
Result<CpcaTransfer> decode_cpca_file(const void* bytes, std::size_t size,
                                      const std::string& name_for_errors);

// Writes atomically (temporary + rename); reads a whole file.
Status write_cpca_file(const std::string& path, const CpcaTransfer& cpca);
Result<CpcaTransfer> read_cpca_file(const std::string& path);

// With the source section (also checks that the section agrees with the CPCA header).
Result<CpcaFile> decode_cpca_file_with_source(const void* bytes, std::size_t size,
                                              const std::string& name_for_errors);
Status write_cpca_file(const std::string& path, const CpcaTransfer& cpca,
                       const GlossyTransferData& source);
// With the source section and a compression record (`record_json` non-empty, at most 1 MiB;
// stored after the source section: u64 size, then the bytes).
Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& cpca,
                                                    const GlossyTransferData& source,
                                                    const std::string& record_json);
Status write_cpca_file(const std::string& path, const CpcaTransfer& cpca,
                       const GlossyTransferData& source, const std::string& record_json);
Result<CpcaFile> read_cpca_file_with_source(const std::string& path);

}  // namespace prt
