// fuzz/fuzz_transfer_file.cpp — libFuzzer target: the coefficient-file reader on arbitrary bytes.
//
// prt::read_transfer_data must reject any malformed buffer with a Status (never crash, over-read,
// hang or hit undefined behaviour). On success the decoded data must pass its own validation and
// re-encode (the reader and the writer agree on what a valid file is). Each input is read as it
// is and with its checksum resealed (fuzz_checksum.h), so that mutations reach the checks behind
// the checksum.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_checksum.h"
#include "one_line_error.h"
#include "prt/formats/transfer_file.h"

namespace {

constexpr std::size_t kChecksumOffset = 64;  // docs/FORMAT.md, coefficient-file header

void check(const unsigned char* data, std::size_t size) {
  const prt::Result<prt::TransferData> result = prt::read_transfer_data(data, size, "fuzz");
  if (!result.ok()) {
    prt::fuzz::check_one_line_error(result.status().message(), "fuzz");
    return;
  }
  if (!prt::validate_transfer_data(*result, "fuzz").ok()) std::abort();
  if (!prt::encode_transfer_file(*result, "fuzz").ok()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
