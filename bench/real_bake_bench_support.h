// bench/real_bake_bench_support.h — what the benchmarks on real glossy bakes (glossy_cpca_real,
// glossy_cpca_frame) share: thread CPU time, a comma-separated list argument, exiting on an
// error Result, the light probes of ../shared/data, eye points around a mesh and the relative
// RMS of two exit-radiance arrays.
#pragma once

#include <time.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "prt/glossy/transfer.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/image_io.h"

namespace prt::bench {

inline std::string shared_data_dir() {
  const char* env = std::getenv("PRT_SHARED_DATA_DIR");
  return env != nullptr ? env : PRT_SHARED_DATA_DIR;
}

// Seconds of CPU time of the calling thread.
inline double thread_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

// "16,32,64" → {16, 32, 64}.
inline std::vector<uint32_t> list_arg(const char* text) {
  std::vector<uint32_t> out;
  for (const char* p = text; *p != 0;) {
    char* end = nullptr;
    out.push_back(static_cast<uint32_t>(std::strtoul(p, &end, 10)));
    if (end == p) break;
    p = *end == ',' ? end + 1 : end;
  }
  return out;
}

// The value, or the message on stderr and exit(1).
template <typename T>
T require(prt::Result<T> r) {
  if (!r.ok()) {
    std::fprintf(stderr, "%s\n", r.status().message().c_str());
    std::exit(1);
  }
  return std::move(r).value();
}

// The light probe ../shared/data/probes/NAME projected to SH order `order`.
inline prt::ShLighting load_probe(const std::string& name, int order) {
  const prt::sh::EnvMap map =
      prt::relight::read_environment(shared_data_dir() + "/probes/" + name, std::nullopt);
  return require(prt::ShLighting::from_env_map(map, order));
}

// Three eye points 2.5 bounding radii from the centre of the mesh's bounding box, in the
// directions (0.3, 0.5, 1), (−1, 0.4, 0.2) and (0.2, 0.9, −0.8).
inline std::vector<std::array<float, 3>> eye_points(const prt::GlossyTransferData& d) {
  float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
  for (std::size_t v = 0; v < d.vertex_count; ++v)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], d.positions[3 * v + a]);
      hi[a] = std::max(hi[a], d.positions[3 * v + a]);
    }
  const double r = 0.5 * std::sqrt(double(hi[0] - lo[0]) * (hi[0] - lo[0]) +
                                   double(hi[1] - lo[1]) * (hi[1] - lo[1]) +
                                   double(hi[2] - lo[2]) * (hi[2] - lo[2]));
  std::vector<std::array<float, 3>> eyes;
  for (const auto& dir :
       {std::array<double, 3>{0.3, 0.5, 1.0}, {-1.0, 0.4, 0.2}, {0.2, 0.9, -0.8}}) {
    const double len = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
    std::array<float, 3> e{};
    for (int a = 0; a < 3; ++a) e[a] = float(0.5 * (lo[a] + hi[a]) + 2.5 * r * dir[a] / len);
    eyes.push_back(e);
  }
  return eyes;
}

// sqrt(Σ (a − ref)² / Σ ref²) in double.
inline double relative_rms(const std::vector<float>& a, const std::vector<float>& ref) {
  double err = 0, norm = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    err += (double(a[i]) - ref[i]) * (double(a[i]) - ref[i]);
    norm += double(ref[i]) * ref[i];
  }
  return std::sqrt(err / norm);
}

}  // namespace prt::bench
