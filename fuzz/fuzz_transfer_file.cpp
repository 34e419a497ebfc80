// fuzz/fuzz_transfer_file.cpp — libFuzzer target: the coefficient-file reader on arbitrary bytes.
//
// prt::read_transfer_data must reject any malformed buffer with a Status (never crash, over-read,
// hang or hit undefined behaviour). On success the decoded data must pass its own validation and
// re-encode (the reader and the writer agree on what a valid file is).
#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "prt/formats/transfer_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const prt::Result<prt::TransferData> result = prt::read_transfer_data(data, size, "fuzz");
  if (!result.ok()) {
    if (result.status().message().empty()) std::abort();  // an error must say what is wrong
    return 0;
  }
  if (!prt::validate_transfer_data(*result, "fuzz").ok()) std::abort();
  if (!prt::encode_transfer_file(*result, "fuzz").ok()) std::abort();
  return 0;
}
