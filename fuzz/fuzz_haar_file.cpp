// fuzz/fuzz_haar_file.cpp — libFuzzer target: the Haar-wavelet coefficient reader
// (prt/formats/haar_transfer_file.h, kind 3 of the `.prt` container) on arbitrary bytes, as they
// are and with their checksum resealed (fuzz_checksum.h), then the relighter on what it read.
//
// read_haar_transfer_data must refuse a malformed buffer with a one-line Status "fuzz.prt: …" and
// never crash, over-read, hang or hit undefined behaviour. What it accepts must pass its own
// validation, re-encode, and relight: the blocked relighter (HaarRelighter, with small blocks so
// that several blocks and dense columns occur) and the plain list walk (shade_index_lists) both
// succeed on a lighting that keeps every wavelet index the file uses, and, when no dequantised
// value exceeds 1e30 in magnitude (so no sum can overflow), agree within 1e-4 of Σ|T·L| per
// output (float sums of the same terms in another order).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "fuzz_checksum.h"
#include "one_line_error.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/haar/approximation.h"
#include "prt/haar/relighter.h"

namespace {

constexpr std::size_t kChecksumOffset = 64;  // docs/FORMAT.md, coefficient-file header

void relight(const prt::HaarTransfer& t) {
  prt::SparseLighting lighting;
  lighting.size = t.size;
  const std::size_t indices = t.offsets.size() - 1;  // 6N²
  for (std::size_t i = 0; i < indices; ++i) {
    if (t.offsets[i + 1] == t.offsets[i]) continue;
    lighting.index.push_back(static_cast<uint32_t>(i));
    const float value = 1.0f / static_cast<float>(1 + i % 7);
    lighting.rgb.insert(lighting.rgb.end(), {value, 0.5f * value, 2.0f * value});
  }
  const std::size_t n = static_cast<std::size_t>(t.vertex_count);
  std::vector<float> blocked(3 * n), lists(3 * n);
  prt::HaarRelighterLayout layout;
  layout.block_vertices = 4;
  layout.dense_fraction = 0.5;
  const prt::HaarRelighter relighter(t, layout);
  if (!relighter.shade(lighting, blocked.data()).ok()) std::abort();
  if (!prt::shade_index_lists(t, lighting, lists.data()).ok()) std::abort();
  // Σ|T·L| per output, in double, from the lists.
  std::vector<double> bound(3 * n, 0.0);
  for (std::size_t term = 0; term < lighting.index.size(); ++term) {
    const uint32_t i = lighting.index[term];
    for (uint64_t e = t.offsets[i]; e < t.offsets[i + 1]; ++e) {
      for (int c = 0; c < 3; ++c) {
        const double value = t.dequantized_value(e, t.channels == 3 ? c : 0);
        if (!(std::fabs(value) <= 1e30)) return;  // huge or non-finite: sums may overflow
        bound[3 * t.vertices[e] + c] += std::fabs(value * lighting.rgb[3 * term + c]);
      }
    }
  }
  for (std::size_t i = 0; i < 3 * n; ++i)
    if (!(std::fabs(double(blocked[i]) - lists[i]) <= 1e-4 * bound[i] + 1e-30)) std::abort();
}

void check(const unsigned char* bytes, std::size_t size) {
  const prt::Result<prt::HaarTransferFile> r =
      prt::read_haar_transfer_data(bytes, size, "fuzz.prt");
  if (!r.ok()) {
    prt::fuzz::check_one_line_error(r.status().message(), "fuzz.prt");
    return;
  }
  if (!prt::validate_haar_transfer_file(*r, "fuzz.prt").ok()) std::abort();
  const prt::HaarTransfer& t = r->transfer;
  if (t.offsets.size() != 6 * std::size_t(t.size) * t.size + 1 ||
      t.vertex_step.size() != static_cast<std::size_t>(t.vertex_count) ||
      t.offsets.back() != t.entry_count())
    std::abort();
  if (!prt::encode_haar_transfer_file(*r, "fuzz.prt").ok()) std::abort();
  relight(t);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
