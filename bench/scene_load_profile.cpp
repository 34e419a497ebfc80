// Where time and memory go before a radiosity solve: loading a scene, subdividing it to an edge
// length (scene/subdivide.h), making the patches (radiosity/patches.h) and building the Embree
// ray caster over them (scene/ray_caster.h) — the steps `prt radiosity SCENE --max-edge L` takes
// before its form factors. Prints, per step, the wall time, the bytes the step's result holds
// (vector capacities; Embree's own memory monitor) and the resident set now and at its peak.
//
//   scene_load_profile SCENE [MAX_EDGE]
//
// Figures: docs/BENCHMARKS.md ("Level and field scenes at scale").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "prt/core/memory_budget.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace {

using Clock = std::chrono::steady_clock;

double resident_mb() {  // the current resident set, /proc/self/statm's second field
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  statm >> pages >> resident;
  return double(resident) * double(sysconf(_SC_PAGESIZE)) / 1e6;
}

template <typename T>
double vector_mb(const std::vector<T>& v) {
  return double(v.capacity() * sizeof(T)) / 1e6;
}

double scene_mb(const prt::scene::Scene& s) {
  return vector_mb(s.positions) + vector_mb(s.normals) + vector_mb(s.albedo) +
         vector_mb(s.texcoords) + vector_mb(s.tangents) + vector_mb(s.triangles);
}

void report(const char* step, Clock::time_point start, double holds_mb) {
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  std::printf("%-26s %8.2f s  holds %8.1f MB  resident %8.1f MB  peak %8.1f MB\n", step, seconds,
              holds_mb, resident_mb(), double(prt::peak_resident_bytes()) / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: scene_load_profile SCENE [MAX_EDGE]\n");
    return 2;
  }
  report("start", Clock::now(), 0.0);
  Clock::time_point t = Clock::now();
  prt::scene::Scene scene = prt::scene::load_scene(argv[1]);
  report("load_scene", t, scene_mb(scene));
  std::printf("  %zu vertices, %zu triangles, %zu primitives\n", scene.positions.size(),
              scene.triangles.size(), scene.primitives.size());
  if (argc == 3) {
    t = Clock::now();
    scene = prt::scene::subdivide_to_edge_length(scene, std::atof(argv[2]));
    report("subdivide_to_edge_length", t, scene_mb(scene));
    std::printf("  %zu vertices, %zu triangles\n", scene.positions.size(), scene.triangles.size());
  }
  t = Clock::now();
  const std::vector<prt::radiosity::Patch> patches = prt::radiosity::make_patches(scene);
  report("make_patches", t, vector_mb(patches));
  std::printf("  %zu patches of %zu bytes\n", patches.size(), sizeof(prt::radiosity::Patch));
  t = Clock::now();
  const prt::scene::RayCaster caster(scene);
  report("RayCaster", t, double(caster.embree_bytes()) / 1e6);
  std::printf("  Embree peak %.1f MB; vertex ray starts %.1f MB\n",
              double(caster.embree_peak_bytes()) / 1e6,
              vector_mb(caster.vertex_ray_starts().offset) +
                  vector_mb(caster.vertex_ray_starts().unreachable_height));
  return 0;
}
