// fuzz/fuzz_emitter_responses.cpp — libFuzzer target: the emitter-response reader
// (prt/emitters/emitter_responses.h, `.prte`) on arbitrary bytes, as they are and with their
// checksum resealed (fuzz_checksum.h), then the recombination a relight runs on what it read.
//
// decode_emitter_responses must refuse a malformed buffer with a one-line Status "fuzz.prte: …"
// and never crash, over-read, hang or hit undefined behaviour. What it accepts must pass its own
// validation, have arrays of consistent sizes with triangle indices below the vertex count, give
// each emitter's stored colour back, recombine (every response and colour finite and ≥ 0, so
// every output is ≥ 0 and never NaN; float overflow to +Inf is possible only for values near
// FLT_MAX and is allowed), and re-encode.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_checksum.h"
#include "one_line_error.h"
#include "prt/emitters/emitter_responses.h"

namespace {

constexpr std::size_t kChecksumOffset = 48;  // docs/FORMAT.md, "Emitter responses"

void check(const unsigned char* bytes, std::size_t size) {
  const prt::Result<prt::EmitterResponses> r =
      prt::decode_emitter_responses(bytes, size, "fuzz.prte");
  if (!r.ok()) {
    prt::fuzz::check_one_line_error(r.status().message(), "fuzz.prte");
    return;
  }
  const prt::EmitterResponses& d = *r;
  if (!prt::validate_emitter_responses(d, "fuzz.prte").ok()) std::abort();
  const std::size_t v = d.vertex_count(), e = d.emitter_count();
  if (d.positions.size() != 3 * v || d.normals.size() != 3 * v || d.triangles.size() % 3 != 0 ||
      d.responses.size() != 3 * v * e || e == 0)
    std::abort();
  for (uint32_t index : d.triangles)
    if (index >= v) std::abort();
  const prt::Result<std::vector<float>> colors = prt::emitter_colors(d, {});
  if (!colors.ok() || colors->size() != 3 * e) std::abort();
  for (std::size_t i = 0; i < e; ++i)
    for (int c = 0; c < 3; ++c)
      if ((*colors)[3 * i + c] != d.emitters[i].emission[c]) std::abort();
  std::vector<float> rgb(3 * v);
  if (!prt::recombine_emitters(d, *colors, rgb.data()).ok()) std::abort();
  for (float x : rgb)
    if (std::isnan(x) || x < 0.0f) std::abort();
  if (!prt::encode_emitter_responses(d, "fuzz.prte").ok()) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
