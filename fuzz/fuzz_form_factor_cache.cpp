// fuzz/fuzz_form_factor_cache.cpp — libFuzzer target: the radiosity form-factor cache reader
// (radiosity/form_factor_cache.h) on arbitrary bytes, from a scratch file (the reader takes a
// path), as they are and with their checksum resealed (fuzz_checksum.h). The caller's key is
// taken from the file's own key field (bytes 16..23), so that mutations get past the key check
// (a wrong key is one comparison, tested in tests/radiosity; so is a revision other than this
// prt's, which the seeds, written by save_form_factors, carry).
//
// load_form_factors must refuse a malformed file with a one-line std::runtime_error "PATH: …" and
// never crash, over-read, hang, allocate what a header merely claims, or hit undefined behaviour.
// What it accepts must be an N × N matrix of finite form factors (the solver divides and sums
// them; a NaN would spread through every patch's radiosity).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_checksum.h"
#include "fuzz_input_file.h"
#include "one_line_error.h"
#include "radiosity/form_factor_cache.h"

namespace {

constexpr std::size_t kChecksumOffset = 48;  // docs/FORMAT.md, "Form-factor cache"
constexpr std::size_t kKeyOffset = 16;

void check(const unsigned char* bytes, std::size_t size) {
  const std::string path = prt::fuzz::write_scratch_file(".ffcache", bytes, size);
  uint64_t key = 0;
  if (size >= kKeyOffset + 8) std::memcpy(&key, bytes + kKeyOffset, 8);
  prt::radiosity::FormFactorMatrix m;
  try {
    m = prt::radiosity::load_form_factors(path, key);
  } catch (const std::runtime_error& e) {
    prt::fuzz::check_one_line_error(e.what(), path);
    return;
  }
  if (m.f.size() != m.size * m.size) std::abort();
  for (float f : m.f)
    if (!std::isfinite(f)) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
