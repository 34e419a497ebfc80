// fuzz/fuzz_cpca_file.cpp — libFuzzer target: the CPCA glossy transfer reader
// (prt/formats/cpca_file.h, `.prtq`, with its optional source section) on arbitrary bytes, as
// they are and with the outer checksum resealed (fuzz_checksum.h). (The source section is a
// glossy transfer file with its own checksum: fuzz_glossy_file covers what lies behind it.)
//
// decode_cpca_file_with_source must refuse a malformed buffer with a one-line Status
// "fuzz.prtq…" and never crash, over-read, hang or hit undefined behaviour. What it accepts must
// pass cpca_validate, have arrays of the sizes its counts give, reconstruct to finite matrices
// (means, bases and weights are finite floats; the sum of K + 1 finite floats times finite
// weights in double cannot overflow), and re-encode.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_checksum.h"
#include "one_line_error.h"
#include "prt/formats/cpca_file.h"

namespace {

constexpr std::size_t kChecksumOffset = 56;  // docs/GLOSSY_CPCA.md, "File format"

void check(const unsigned char* bytes, std::size_t size) {
  const prt::Result<prt::CpcaFile> r = prt::decode_cpca_file_with_source(bytes, size, "fuzz.prtq");
  if (!r.ok()) {
    prt::fuzz::check_one_line_error(r.status().message(), "fuzz.prtq");
    return;
  }
  const prt::CpcaTransfer& t = r->cpca;
  if (!prt::cpca_validate(t).ok()) std::abort();
  const std::size_t d = t.dimension(), q = t.cluster_count, k = t.vector_count;
  const std::size_t n = static_cast<std::size_t>(t.vertex_count);
  if (t.means.size() != q * d || t.basis.size() != q * k * d || t.cluster_of_vertex.size() != n ||
      t.weights.size() != n * k)
    std::abort();
  std::vector<double> x(d);
  for (std::size_t v = 0; v < n && v < 64; ++v) {
    prt::cpca_reconstruct(t, v, x.data());
    for (double value : x)
      if (!std::isfinite(value)) std::abort();
  }
  if (r->has_source) {
    const prt::GlossyTransferData& s = r->source;
    if (s.vertex_count != t.vertex_count || s.order != t.order || s.channels != t.channels)
      std::abort();
    if (!prt::encode_cpca_file(t, s).ok()) std::abort();
  } else if (!prt::encode_cpca_file(t).ok()) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
