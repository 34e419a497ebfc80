// tests/golden/image_compare.h — per-pixel comparison of a render against its golden reference.
//
// A pixel's difference is the largest over its channels of
//   PNG (8-bit, display-encoded): |render − reference| in 8-bit levels (both rounded to
//                 0..255 first, so differences are whole levels);
//   EXR (linear): |render − reference| / max(|reference|, floor), floor = 5% of the reference's
//                 mean channel value (so near-black pixels are judged against the image's
//                 scale, not against zero).
// A pixel is beyond tolerance when its difference exceeds Tolerance::per_pixel. The comparison
// passes when the sizes and channel counts agree, at most Tolerance::outlier_fraction of the
// pixels are beyond it (a few pixels at silhouettes may flip on another CPU), and the mean
// difference is at most Tolerance::mean (a small shift of the whole picture, such as a slightly
// different tone curve, stays under the per-pixel tolerance but not under the mean). Why these
// numbers (measured): tests/golden/README.md.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>

#include "relight/float_image.h"

namespace prt::golden {

enum class PixelMetric {
  Levels8,   // absolute, in 8-bit levels: PNG
  Relative,  // relative to the reference, with a floor: linear EXR
};

struct Tolerance {
  PixelMetric metric = PixelMetric::Levels8;
  double per_pixel = 0;         // levels (Levels8) or a fraction (Relative)
  double outlier_fraction = 0;  // of the pixels, allowed beyond per_pixel
  double mean = 0;              // the largest mean difference over the image, same unit
};

// PNG: 2 levels per pixel, 0.1% of the pixels beyond, mean 0.5 levels; EXR: 0.5% per pixel,
// 0.1% of the pixels beyond, mean 0.1% (README.md says why).
Tolerance tolerance_for(const std::filesystem::path& reference);

struct Comparison {
  bool same_shape = true;     // width, height and channels agree
  std::string shape_problem;  // when not: e.g. "size 96x64, reference 128x96"
  std::size_t pixels = 0;
  std::size_t beyond = 0;     // pixels whose difference exceeds the tolerance
  std::size_t differing = 0;  // pixels whose difference is not exactly 0
  std::size_t allowed = 0;    // pixels allowed beyond (outlier_fraction × pixels, rounded down)
  double max_difference = 0;  // in the metric's unit
  double mean_difference = 0;
  Tolerance tolerance;

  bool passed() const {
    return same_shape && beyond <= allowed && mean_difference <= tolerance.mean;
  }
  // One line: "12288 px, 0 beyond 2 levels (12 allowed), 0 differ, max 0 levels, mean 0 levels
  // (at most 0.5 levels)".
  std::string describe() const;
};

Comparison compare_images(const relight::FloatImage& reference, const relight::FloatImage& render,
                          const Tolerance& tolerance);

// Reads both files (relight::read_image) and compares them with tolerance_for(reference).
Comparison compare_files(const std::filesystem::path& reference,
                         const std::filesystem::path& render);

// A PNG of the size of the images showing where they differ: grey from black (identical) to
// mid-grey (at the tolerance) for pixels within it, red to yellow (twice the tolerance and more)
// for pixels beyond it. Both images must have the same shape.
void write_difference_image(const std::filesystem::path& output,
                            const relight::FloatImage& reference, const relight::FloatImage& render,
                            const Tolerance& tolerance);

}  // namespace prt::golden
