// 2D non-standard Haar transform in quadtree order; see prt/haar/transform.h.
#include "prt/haar/transform.h"

#include <string>

namespace prt {

HaarCoefficientInfo describe_haar_coefficient(int size, int q) noexcept {
  HaarCoefficientInfo info;
  if (q == 0) {
    info.support_size = size;
    return info;
  }
  int j = 0;
  while ((int64_t{1} << (2 * (j + 1))) <= q) ++j;
  const int level_count = 1 << (2 * j);  // 4^j positions per band
  const int offset = q - level_count;
  const int side = 1 << j;
  const int position = offset % level_count;
  info.level = j;
  info.band = offset / level_count;
  info.support_size = size / side;
  info.support_row = (position / side) * info.support_size;
  info.support_col = (position % side) * info.support_size;
  return info;
}

double evaluate_haar_basis(int size, int q, int row, int col) noexcept {
  const HaarCoefficientInfo info = describe_haar_coefficient(size, q);
  const int s = info.support_size;
  const int r = row - info.support_row, c = col - info.support_col;
  if (r < 0 || c < 0 || r >= s || c >= s) return 0.0;
  const double amplitude = 1.0 / s;
  if (info.band < 0) return amplitude;
  const double horizontal = c < s / 2 ? 1.0 : -1.0;
  const double vertical = r < s / 2 ? 1.0 : -1.0;
  if (info.band == 0) return amplitude * horizontal;
  if (info.band == 1) return amplitude * vertical;
  return amplitude * horizontal * vertical;
}

void forward_haar_2d(float* data, int size, int stride) {
  const size_t n2 = static_cast<size_t>(size) * size;
  std::vector<double> avg(n2);
  for (size_t t = 0; t < n2; ++t) avg[t] = data[t * stride];
  // avg holds the current cur×cur averages, row-major with row length cur. Each step writes
  // the new half×half averages to the front of avg; the write position y·half + x never
  // passes a position still to be read, so the compaction is safe in place.
  for (int cur = size; cur > 1; cur /= 2) {
    const int half = cur / 2;
    const size_t base = static_cast<size_t>(half) * half;  // 4^j, the level's first index
    for (int y = 0; y < half; ++y) {
      for (int x = 0; x < half; ++x) {
        const size_t top = static_cast<size_t>(2 * y) * cur + 2 * x, bottom = top + cur;
        const double p00 = avg[top], p01 = avg[top + 1];
        const double p10 = avg[bottom], p11 = avg[bottom + 1];
        const size_t pos = static_cast<size_t>(y) * half + x;
        data[(base + pos) * stride] = static_cast<float>(0.5 * ((p00 - p01) + (p10 - p11)));
        data[(2 * base + pos) * stride] = static_cast<float>(0.5 * ((p00 + p01) - (p10 + p11)));
        data[(3 * base + pos) * stride] = static_cast<float>(0.5 * ((p00 - p01) - (p10 - p11)));
        avg[pos] = 0.5 * ((p00 + p01) + (p10 + p11));
      }
    }
  }
  data[0] = static_cast<float>(avg[0]);
}

void inverse_haar_2d(float* data, int size, int stride) {
  const size_t n2 = static_cast<size_t>(size) * size;
  std::vector<double> avg(n2);
  avg[0] = data[0];
  // Expand half×half averages to cur×cur, walking positions backwards so every write lands at
  // or after the position being read and before no unread one.
  for (int cur = 2; cur <= size; cur *= 2) {
    const int half = cur / 2;
    const size_t base = static_cast<size_t>(half) * half;
    for (int y = half - 1; y >= 0; --y) {
      for (int x = half - 1; x >= 0; --x) {
        const size_t pos = static_cast<size_t>(y) * half + x;
        const double a = avg[pos];
        const double dh = data[(base + pos) * stride];
        const double dv = data[(2 * base + pos) * stride];
        const double dd = data[(3 * base + pos) * stride];
        const size_t top = static_cast<size_t>(2 * y) * cur + 2 * x, bottom = top + cur;
        avg[top] = 0.5 * ((a + dh) + (dv + dd));
        avg[top + 1] = 0.5 * ((a - dh) + (dv - dd));
        avg[bottom] = 0.5 * ((a + dh) - (dv + dd));
        avg[bottom + 1] = 0.5 * ((a - dh) - (dv - dd));
      }
    }
  }
  for (size_t t = 0; t < n2; ++t) data[t * stride] = static_cast<float>(avg[t]);
}

namespace {
template <class From, class To>
Result<To> transform_faces(const From& in, bool forward) {
  const int n = in.size;
  if (!is_valid_cube_size(n)) {
    return Status::Error("haar transform: cube size " + std::to_string(n) +
                         " is not a power of two in [8, 128]");
  }
  const size_t face_values = static_cast<size_t>(n) * n * 3;
  if (in.rgb.size() != face_values * kCubeFaceCount) {
    return Status::Error("haar transform: rgb holds " + std::to_string(in.rgb.size()) +
                         " values, expected 6*N*N*3");
  }
  To out;
  out.size = n;
  out.rgb = in.rgb;
  for (int face = 0; face < kCubeFaceCount; ++face) {
    for (int c = 0; c < 3; ++c) {
      float* base = out.rgb.data() + face * face_values + c;
      if (forward) {
        forward_haar_2d(base, n, 3);
      } else {
        inverse_haar_2d(base, n, 3);
      }
    }
  }
  return out;
}
}  // namespace

Result<WaveletCube> transform_cube(const CubeMap& cube) {
  return transform_faces<CubeMap, WaveletCube>(cube, true);
}

Result<CubeMap> inverse_transform_cube(const WaveletCube& wavelets) {
  return transform_faces<WaveletCube, CubeMap>(wavelets, false);
}

}  // namespace prt
