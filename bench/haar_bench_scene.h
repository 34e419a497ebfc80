// bench/haar_bench_scene.h — the scene and lights the Haar-vs-SH benchmarks share
// (bench/haar_vs_sh.cpp, bench/haar_bytes_per_vertex.cpp), so both measure the same setup.
// Frame: glTF's (+Y up); lat-long maps as in sh/env_map.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/haar/transfer.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"
#include "sh/env_map.h"

namespace prt::bench {

// bunny_small.obj on a 40×40-segment ground quad twice the bunny's footprint; albedo 0.8 grey.
inline prt::scene::Scene make_bunny_on_plane(const std::string& shared_data_dir) {
  prt::scene::Scene scene = prt::scene::load_scene(shared_data_dir + "/meshes/bunny_small.obj");
  const glm::vec3 lo = scene.bounds_min(), hi = scene.bounds_max();
  const float ext = std::max(hi.x - lo.x, hi.z - lo.z);
  const glm::vec3 c = 0.5f * (lo + hi);
  prt::scene::append_scene(
      scene, prt::scene::make_quad({c.x - ext, lo.y, c.z + ext}, {2 * ext, 0, 0}, {0, 0, -2 * ext},
                                   40, 40, glm::vec3(0.8f), "ground"));
  for (glm::vec3& a : scene.albedo) a = glm::vec3(0.8f);
  return scene;
}

// A 512×256 lat-long map: dim uniform sky 0.05 and a 16×12-texel rectangle of radiance 200
// at 40° elevation toward −Z+X (about 0.2% of the sphere): a small, bright area light.
inline prt::sh::EnvMap make_area_light() {
  prt::sh::EnvMap env;
  env.layout = prt::sh::EnvLayout::LatLong;
  env.width = 512;
  env.height = 256;
  env.rgb.assign(3 * 512 * 256, 0.05f);
  for (int y = 50; y < 62; ++y)
    for (int x = 160; x < 176; ++x)
      for (int c = 0; c < 3; ++c) env.rgb[3 * (y * 512 + x) + c] = 200.f;
  return env;
}

// The float32 wavelet coefficients of an unquantised transfer, vertex-major: V × 6N² values
// (zero where a vertex stores no coefficient). Grey (1-channel) transfer.
inline std::vector<float> dense_wavelet_coefficients(const prt::HaarTransfer& t,
                                                     std::size_t vertex_count, int cube_size) {
  const std::size_t W = std::size_t(6) * cube_size * cube_size;
  std::vector<float> dense(vertex_count * W, 0.f);
  for (std::size_t i = 0; i < W; ++i)
    for (uint64_t e = t.offsets[i]; e < t.offsets[i + 1]; ++e)
      dense[t.vertices[e] * W + i] = t.values_f32[e];
  return dense;
}

}  // namespace prt::bench
