// fuzz/fuzz_glossy_file.cpp — libFuzzer target: the glossy transfer reader
// (prt/formats/glossy_transfer_file.h, `.prtg`) on arbitrary bytes, as they are and with their
// checksum resealed (fuzz_checksum.h) so that mutations reach the checks behind it.
//
// read_glossy_transfer_data must refuse a malformed buffer with a one-line Status "fuzz.prtg: …"
// (never crash, over-read, hang or hit undefined behaviour). What it accepts must pass its own
// validation (sizes consistent with order, channels and vertex count; finite numbers; indices in
// range), re-encode, and read back from its re-encoding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_checksum.h"
#include "one_line_error.h"
#include "prt/formats/glossy_transfer_file.h"

namespace {

constexpr std::size_t kChecksumOffset = 72;  // docs/FORMAT.md, glossy transfer header

void check(const unsigned char* bytes, std::size_t size) {
  const prt::Result<prt::GlossyTransferData> r =
      prt::read_glossy_transfer_data(bytes, size, "fuzz.prtg");
  if (!r.ok()) {
    prt::fuzz::check_one_line_error(r.status().message(), "fuzz.prtg");
    return;
  }
  const prt::GlossyTransferData& d = *r;
  if (!prt::validate_glossy_transfer_data(d, "fuzz.prtg").ok()) std::abort();
  const std::size_t v = static_cast<std::size_t>(d.vertex_count);
  if (d.positions.size() != 3 * v || d.normals.size() != 3 * v || d.tangents.size() != 4 * v ||
      d.material_of_vertex.size() != v || d.matrices.size() != v * d.channels * d.matrix_floats())
    std::abort();
  const auto again = prt::encode_glossy_transfer_file(d, "fuzz.prtg");
  if (!again.ok()) std::abort();
  if (!prt::read_glossy_transfer_data(again->data(), again->size(), "again").ok()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
