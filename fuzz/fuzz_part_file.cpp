// fuzz/fuzz_part_file.cpp — libFuzzer target: the farm's part files, read by the generic
// container reader (prt/formats/part_file.h, read_part_file) and decoded as bake parts
// (bake/transfer_part_file.h, decode_transfer_part: SH, Haar, glossy, subsurface and
// form-factor parts; no scene needed), from a scratch file (the reader maps a path). Each input
// is read as it is (the checksum check itself) and as a resealed copy whose layout id is this
// prt's (bytes 72..79) and whose CRC-32C (bytes 64..67) is recomputed, so that mutations reach
// the header, section table and section checks behind them.
//
// read_part_file must refuse a malformed file with a one-line Status "PATH: …" and
// decode_transfer_part with a one-line BakeError "PATH: …"; neither may crash, over-read, hang,
// allocate what a header merely claims or hit undefined behaviour. What they accept must hold
// part_file_invariants.h.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/transfer_part_file.h"
#include "fuzz_checksum.h"
#include "fuzz_input_file.h"
#include "one_line_error.h"
#include "part_file_invariants.h"
#include "prt/formats/part_file.h"

namespace {

constexpr std::size_t kChecksumOffset = 64;  // docs/FORMAT.md, "Part files"
constexpr std::size_t kLayoutOffset = 72;

void check(const unsigned char* bytes, std::size_t size) {
  const std::string path = prt::fuzz::write_scratch_file(".prtpart", bytes, size);
  prt::PartFile part;
  const prt::Status status = prt::read_part_file(path, &part);
  if (!status.ok()) {
    prt::fuzz::check_one_line_error(status.message(), path);
    return;
  }
  prt::fuzz::check_part_invariants(part, size);
  prt::bake::TransferPartFile decoded;
  try {
    decoded = prt::bake::decode_transfer_part(part, path);
  } catch (const std::runtime_error& e) {
    prt::fuzz::check_one_line_error(e.what(), path);
    return;
  }
  prt::fuzz::check_decoded_part(decoded, part, size);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  check(data, size);
  std::vector<unsigned char> copy(data, data + size);
  if (size >= kLayoutOffset + 8) {
    const uint64_t layout = prt::bake::part_layout_id();
    for (int i = 0; i < 8; ++i)
      copy[kLayoutOffset + i] = static_cast<unsigned char>(layout >> 8 * i);
  }
  const std::vector<unsigned char> sealed =
      prt::fuzz::resealed(copy.data(), copy.size(), kChecksumOffset);
  check(sealed.data(), sealed.size());
  return 0;
}
