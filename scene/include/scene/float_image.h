// scene/float_image.h — a decoded image as float samples, and the size cap every reader applies.
//
// Pixels are row-major, row 0 at the top, `channels` interleaved floats per texel. The readers
// (scene/image_codec.h here; relight/image_io.h, relight/radiance_hdr.h, relight/pfm_image.h
// above) refuse images with more than a caller-given number of texels before allocating
// anything; kMaxImageTexels is the default.
#pragma once

#include <cstddef>
#include <vector>

namespace prt::scene {

struct FloatImage {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;  // row-major, row 0 at the top
};

// 2^28 texels: 16384 × 16384, twice the largest environment maps in use (16384 × 8192). As float
// RGB that is 3 GiB; anything larger is refused as absurd rather than attempted.
inline constexpr std::size_t kMaxImageTexels = std::size_t{1} << 28;

}  // namespace prt::scene
