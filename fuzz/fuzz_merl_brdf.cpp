// fuzz/fuzz_merl_brdf.cpp — libFuzzer target: the MERL measured-BRDF reader (prt/brdf/merl.h) on
// arbitrary bytes, from a scratch file (the reader takes a path), then evaluation of what it
// accepted.
//
// A MERL file is a 12-byte header and a fixed 34,992,000-byte table, far beyond what a fuzzer
// can mutate, so byte 0 of the input picks how the file is made:
//   - byte 0 ≠ 1: the rest of the input is the file (header, truncation and size checks);
//   - byte 0 = 1: a table-sized file: bytes 1..12 are the header (zero-padded), the rest (at
//     least one byte, else 0.5) is repeated to fill the table, and byte 1 of the remainder, taken
//     mod 3, makes the file exact, one byte short or one byte long. (Slow: ~35 MB written and read
//     per execution, which is why only one selector value takes this path.)
// MerlBrdf::read must refuse a malformed file with a one-line Status "PATH: …" and never crash,
// over-read or hit undefined behaviour. An accepted BRDF must evaluate to finite, non-negative
// values (the table is finite and clamped at 0) in every direction pair tried, zero below the
// horizon, with pdf ≥ 0.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz_input_file.h"
#include "one_line_error.h"
#include "prt/brdf/merl.h"

namespace {

using prt::brdf::Vec3;

constexpr std::size_t kTableBytes = std::size_t{3} * prt::brdf::kMerlThetaH *
                                    prt::brdf::kMerlThetaD * prt::brdf::kMerlPhiD * sizeof(double);

std::vector<unsigned char> table_sized_file(const uint8_t* data, std::size_t size) {
  std::vector<unsigned char> file(12 + kTableBytes, 0);
  std::memcpy(file.data(), data, size < 12 ? size : 12);
  const double half = 0.5;
  const uint8_t* rest = size > 12 ? data + 12 : reinterpret_cast<const uint8_t*>(&half);
  const std::size_t rest_size = size > 12 ? std::min(size - 12, kTableBytes) : sizeof half;
  // The pattern, then the filled part copied after itself (doubling): a few dozen copies.
  unsigned char* table = file.data() + 12;
  std::memcpy(table, rest, rest_size);
  for (std::size_t filled = rest_size; filled < kTableBytes;) {
    const std::size_t n = std::min(filled, kTableBytes - filled);
    std::memcpy(table + filled, table, n);
    filled += n;
  }
  const int adjust = size > 13 ? rest[1] % 3 : 0;
  if (adjust == 1) file.pop_back();
  if (adjust == 2) file.push_back(0);
  return file;
}

void check_brdf(const prt::brdf::MerlBrdf& brdf) {
  const Vec3 directions[] = {{0, 0, 1},           {0.6, 0, 0.8},      {-0.6, 0, 0.8},
                             {0.36, 0.48, 0.8},   {0.999, 0, 0.0447}, {0, -1, 0},
                             {0.5, 0.5, -0.7071}, {1e-9, 0, 1}};
  for (const Vec3& wi : directions) {
    for (const Vec3& wo : directions) {
      const prt::brdf::Rgb f = brdf.eval(wi, wo);
      for (double c : {f.r, f.g, f.b})
        if (!std::isfinite(c) || c < 0.0) std::abort();
      if ((wi.z <= 0.0 || wo.z <= 0.0) && (f.r != 0.0 || f.g != 0.0 || f.b != 0.0)) std::abort();
      if (!(brdf.pdf(wo, wi) >= 0.0)) std::abort();
    }
  }
}

// How many executions took the table-sized path (printed at exit, for docs/FUZZING.md).
std::size_t table_sized_runs = 0;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const bool registered = [] {
    std::atexit(
        [] { std::fprintf(stderr, "fuzz_merl_brdf: %zu table-sized files\n", table_sized_runs); });
    return true;
  }();
  (void)registered;
  std::string path;
  if (data[0] == 1) {
    ++table_sized_runs;
    const std::vector<unsigned char> file = table_sized_file(data + 1, size - 1);
    path = prt::fuzz::write_scratch_file(".binary", file.data(), file.size());
  } else {
    path = prt::fuzz::write_scratch_file(".binary", data + 1, size - 1);
  }
  const prt::Result<prt::brdf::MerlBrdf> brdf = prt::brdf::MerlBrdf::read(path);
  if (!brdf.ok()) {
    prt::fuzz::check_one_line_error(brdf.status().message(), path);
    return 0;
  }
  check_brdf(*brdf);
  return 0;
}
