// prt/cpca_file.h — the CPCA glossy transfer file (`.prtq`): a CpcaTransfer (prt/cpca.h) on
// disk, byte by byte in docs/GLOSSY_CPCA.md ("File format"). It holds the compressed matrices
// only; positions, frames and materials stay with the glossy transfer it was made from, which
// the geometry fingerprint names.
// Nothing here throws; failures return prt::Status with one line naming the file.
// Compiles as C++17.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prt/cpca.h"
#include "prt/status.h"

namespace prt {

// The file's bytes (exactly cpca.payload_bytes() of them). Errors: cpca_validate's.
Result<std::vector<unsigned char>> encode_cpca_file(const CpcaTransfer& cpca);

// Parses and checks everything (magic, version, sizes, checksum, ids, finiteness).
Result<CpcaTransfer> decode_cpca_file(const void* bytes, std::size_t size,
                                      const std::string& name_for_errors);

// Writes atomically (temporary + rename); reads a whole file.
Status write_cpca_file(const std::string& path, const CpcaTransfer& cpca);
Result<CpcaTransfer> read_cpca_file(const std::string& path);

}  // namespace prt
