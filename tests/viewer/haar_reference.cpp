// The C++ side of the JavaScript Haar test (check_haar_js.mjs): prints, as JSON, what the library
// computes on fixed inputs, so that web/haar.js can be compared with it on the same inputs:
//   * a 64×32 lat-long map (smooth sky, a coloured band and a small bright sun) resampled to the
//     8-cube and the 16-cube (prt::resample_to_cube): the page's two cubes;
//   * for five rotations (identity included): the matrix, the rotated 8-cube
//     (relight::make_rotated_cube), its Haar coefficients (prt::transform_cube) and the
//     non-linear selections of K = 1, 7, 50, 200 and all terms (prt::select_nonlinear);
//   * sparse transfer of 40 vertices, grey and RGB, 8-bit, 16-bit and float32 (built with
//     prt::HaarTransferBuilder from pseudo-random sparse vertices): its lists, and the exit
//     radiance prt::HaarRelighter::shade gives with two of the lightings above.
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "prt/haar/approximation.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transfer.h"
#include "prt/haar/transform.h"
#include "relight/haar_relight.h"
#include "sh/env_map.h"
#include "sh/rotation.h"

namespace {

constexpr int kSize = 8;
constexpr double kPi = 3.14159265358979323846;

template <class T>
void print_array(const T* v, std::size_t n) {
  std::printf("[");
  for (std::size_t i = 0; i < n; ++i) std::printf("%s%.9g", i ? "," : "", double(v[i]));
  std::printf("]");
}

template <class V>
void print_vector(const V& v) {
  print_array(v.data(), v.size());
}

prt::sh::EnvMap test_map() {
  prt::sh::EnvMap env;
  env.width = 64;
  env.height = 32;
  env.rgb.resize(3 * 64 * 32);
  for (int row = 0; row < 32; ++row)
    for (int col = 0; col < 64; ++col) {
      const double theta = kPi * (row + 0.5) / 32, phi = 2 * kPi * ((col + 0.5) / 64 - 0.5);
      const double y = std::cos(theta), x = std::sin(theta) * std::cos(phi);
      float* p = &env.rgb[3 * (row * 64 + col)];
      p[0] = float(0.2 + 0.5 * std::max(0.0, y) + 0.1 * x);
      p[1] = float(0.25 + 0.4 * std::max(0.0, y) + (row == 17 ? 0.8 : 0.0));
      p[2] = float(0.3 + 0.6 * std::max(0.0, y) + 0.05 * std::sin(3 * phi));
      if (row >= 8 && row < 10 && col >= 40 && col < 43) p[0] = 60, p[1] = 50, p[2] = 40;  // sun
    }
  return env;
}

uint64_t next(uint64_t* state) {
  *state = *state * 6364136223846793005ull + 1442695040888963407ull;
  return *state >> 33;
}

prt::HaarTransfer test_transfer(int channels, prt::HaarQuantization quantization) {
  const int total = 6 * kSize * kSize;
  prt::HaarTransferBuilder builder(kSize, channels, quantization);
  uint64_t state = 12345 + channels * 7 + static_cast<int>(quantization);
  for (int v = 0; v < 40; ++v) {
    prt::SparseVertexTransfer vertex;
    for (int i = 0; i < total; ++i) {
      // Coarse indices (q < 16) are kept by most vertices, fine ones by few.
      const int q = i % (kSize * kSize);
      if (next(&state) % 100 >= (q < 16 ? 90u : 15u)) continue;
      vertex.index.push_back(uint32_t(i));
      for (int c = 0; c < channels; ++c)
        vertex.values.push_back(float((double(next(&state) % 20001) / 10000.0 - 1.0) / (1 + q)));
    }
    if (!builder.add_vertex(vertex).ok()) std::abort();
  }
  prt::Result<prt::HaarTransfer> t = builder.finish();
  if (!t.ok()) std::abort();
  return std::move(t).value();
}

void print_lighting(const prt::SparseLighting& l) {
  std::printf("{\"index\":");
  print_vector(l.index);
  std::printf(",\"rgb\":");
  print_vector(l.rgb);
  std::printf("}");
}

}  // namespace

int main() {
  const prt::sh::EnvMap env = test_map();
  const prt::Result<prt::CubeMap> cube = prt::resample_to_cube(env, kSize);
  const prt::Result<prt::CubeMap> fine = prt::resample_to_cube(env, 2 * kSize);
  if (!cube.ok() || !fine.ok()) return 1;
  std::printf("{\"size\":%d,\"fine_size\":%d,\"cube\":", kSize, 2 * kSize);
  print_vector(cube->rgb);
  std::printf(",\"fine\":");
  print_vector(fine->rgb);
  std::printf(",\"rotations\":[");
  const double angles[][3] = {{0, 0, 0}, {90, 0, 0}, {30, 20, 10}, {-135, 75, -40}, {200, -89, 33}};
  const int64_t terms[] = {1, 7, 50, 200, 0};
  std::vector<prt::SparseLighting> lightings;
  for (int r = 0; r < 5; ++r) {
    const std::array<double, 9> m =
        prt::sh::rotation_from_yaw_pitch_roll(angles[r][0], angles[r][1], angles[r][2]);
    const prt::CubeMap rotated = prt::relight::make_rotated_cube(env, kSize, m);
    const prt::Result<prt::WaveletCube> wavelets = prt::transform_cube(rotated);
    if (!wavelets.ok()) return 1;
    std::printf("%s{\"yaw_pitch_roll\":", r ? "," : "");
    print_array(angles[r], 3);
    std::printf(",\"matrix\":[");
    for (int i = 0; i < 9; ++i) std::printf("%s%.17g", i ? "," : "", m[i]);
    std::printf("],\"cube\":");
    print_vector(rotated.rgb);
    std::printf(",\"wavelets\":");
    print_vector(wavelets->rgb);
    std::printf(",\"selections\":[");
    for (int k = 0; k < 5; ++k) {
      const prt::SparseLighting l = terms[k] > 0 ? prt::select_nonlinear(*wavelets, terms[k])
                                                 : prt::keep_all_terms(*wavelets);
      std::printf("%s{\"terms\":%lld,\"lighting\":", k ? "," : "", (long long)terms[k]);
      print_lighting(l);
      std::printf("}");
      if (r == 2 && (k == 2 || k == 4)) lightings.push_back(l);
    }
    std::printf("]}");
  }
  std::printf("],\"transfers\":[");
  bool first = true;
  for (int channels : {1, 3})
    for (prt::HaarQuantization q : {prt::HaarQuantization::Bits8, prt::HaarQuantization::Bits16,
                                    prt::HaarQuantization::Float32}) {
      prt::HaarTransfer t = test_transfer(channels, q);
      std::printf("%s{\"channels\":%d,\"bits\":%d,\"vertex_count\":%lld,\"offsets\":",
                  first ? "" : ",", channels, static_cast<int>(q), (long long)t.vertex_count);
      first = false;
      print_vector(t.offsets);
      std::printf(",\"vertices\":");
      print_vector(t.vertices);
      std::printf(",\"values\":");
      if (q == prt::HaarQuantization::Bits8) print_vector(t.values_i8);
      if (q == prt::HaarQuantization::Bits16) print_vector(t.values_i16);
      if (q == prt::HaarQuantization::Float32) print_vector(t.values_f32);
      std::printf(",\"steps\":");
      print_vector(t.vertex_step);
      std::printf(",\"shaded\":[");
      const prt::HaarRelighter relighter(std::move(t));
      for (std::size_t k = 0; k < lightings.size(); ++k) {
        std::vector<float> out(3 * 40);
        if (!relighter.shade(lightings[k], out.data()).ok()) return 1;
        std::printf("%s{\"lighting\":", k ? "," : "");
        print_lighting(lightings[k]);
        std::printf(",\"radiance\":");
        print_vector(out);
        std::printf("}");
      }
      std::printf("]}");
    }
  std::printf("]}\n");
  return 0;
}
