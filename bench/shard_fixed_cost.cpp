// The fixed cost of one shard of a farm bake (`prt bake --shard I/N`, docs/FARM.md): the work
// every shard repeats whatever its share of the rows, step by step in the order a shard takes
// them — load the scene (glTF parse, mesh build and normals), the Morton order of the rows, the
// ray starts of its rows and the Embree BVH over every triangle (and, apart, the single bake's
// RayCaster with every vertex's starts), the compact gather's renumbering tables,
// the part's fingerprint and scene hash — and, for comparison, the sampling of a few rows.
// Prints, per step, the CPU seconds of the whole process (user + sys, every thread) and the wall
// seconds, so that the per-shard overhead (Σ shards − one bake) can be told apart step by step.
//
//   shard_fixed_cost SCENE [ORDER]
//
// Figures: docs/BENCHMARKS.md ("Farm shards at 2M vertices: the fixed cost").
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <tiny_gltf.h>

#include "bake/compact_gather.h"
#include "bake/transfer_part.h"
#include "bake/transfer_part_file.h"
#include "prt/core/memory_budget.h"
#include "prt/formats/geometry_check.h"
#include "scene/ray_caster.h"
#include "scene/ray_offset.h"
#include "scene/scene_loader.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds(const timeval& t) {
  return double(t.tv_sec) + 1e-6 * double(t.tv_usec);
}

double sys_seconds() {  // sys of every thread so far
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return seconds(u.ru_stime);
}

double cpu_seconds() {  // user + sys of every thread so far
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return seconds(u.ru_utime) + seconds(u.ru_stime);
}

struct Step {
  double cpu = cpu_seconds(), sys = sys_seconds();
  Clock::time_point wall = Clock::now();
};

double total_cpu = 0.0;

// `in_shard`: the step is one a shard takes (counted in the total), not a comparison.
void report(const char* what, const Step& s, bool in_shard = true) {
  const double cpu = cpu_seconds() - s.cpu;
  if (in_shard) total_cpu += cpu;
  std::printf("%-44s CPU %7.2f s (sys %5.2f)  wall %7.2f s  peak %7.0f MB\n", what, cpu,
              sys_seconds() - s.sys, std::chrono::duration<double>(Clock::now() - s.wall).count(),
              double(prt::peak_resident_bytes()) / 1e6);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: shard_fixed_cost SCENE [ORDER]\n");
    return 2;
  }
  const int order = argc == 3 ? std::atoi(argv[2]) : 5;
  Step s;
  {  // the parse alone (load_scene below parses again, then builds the meshes and normals)
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    std::string error, warning;
    if (std::string(argv[1]).size() > 4 &&
        std::string(argv[1]).substr(std::string(argv[1]).size() - 4) == ".glb")
      loader.LoadBinaryFromFile(&model, &error, &warning, argv[1]);
  }
  report("tinygltf LoadBinaryFromFile (parse only)", s, false);  // load_scene parses again
  s = Step{};
  const prt::scene::Scene scene = prt::scene::load_scene(argv[1]);
  report("load_scene (parse, meshes, normals)", s);
  const std::size_t V = scene.positions.size(), T = scene.triangles.size();
  std::printf("  %zu vertices, %zu triangles\n", V, T);

  s = Step{};
  const uint64_t fingerprint = prt::geometry_fingerprint(&scene.positions[0].x, V);
  report("geometry_fingerprint", s);

  s = Step{};
  std::vector<uint32_t> rows = prt::bake::make_morton_order(scene.positions);
  report("make_morton_order", s);

  s = Step{};
  const prt::scene::VertexRayStarts starts = prt::scene::compute_vertex_ray_starts(scene);
  report("compute_vertex_ray_starts (alone)", s, false);

  s = Step{};
  const double max_offset = prt::scene::max_vertex_ray_offset(scene);
  report("max_vertex_ray_offset (alone)", s, false);

  s = Step{};
  { const prt::scene::RayCaster all(scene); }
  report("RayCaster, every vertex (single bake)", s, false);

  // A shard's (1 of 8): the starts and nudges of its rows, the whole scene's largest ε.
  const prt::bake::RowRange share = prt::bake::shard_rows(V, {0, 8});
  s = Step{};
  const prt::scene::RayCaster caster(scene, rows.data() + share.first, share.size());
  report("RayCaster, shard 0/8's rows (starts, BVH)", s);

  s = Step{};
  std::vector<double> sums(share.size() * std::size_t(order) * std::size_t(order), 0.0);
  std::vector<float> ao(share.size(), 0.f), bent(3 * share.size(), 0.f);
  report("sums of shard 0/8's rows", s);

  s = Step{};
  const prt::bake::CompactGather gather(rows, scene.triangles, 64, 1.0 / 256, false);
  report("CompactGather tables (a shard's: no solve)", s);

  s = Step{};
  {  // the header of a part that holds no rows (not shard 0: no scene sections), written
    prt::bake::TransferPart part;
    part.shard = {1, 2};
    part.vertices = V;
    part.rows = prt::bake::shard_rows(V, part.shard);
    part.rows.end = part.rows.first;
    prt::bake::BakeOptions options;
    options.kind = prt::TransferKind::Interreflected;
    options.order = order;
    const std::string path = "shard_fixed_cost.tmp.prtpart";
    const prt::Status written =
        prt::write_part_file(path, prt::bake::encode_transfer_part(part, scene, options, "bench"));
    std::remove(path.c_str());
    if (!written.ok()) std::fprintf(stderr, "%s\n", written.message().c_str());
  }
  report("part header (fingerprint, scene hash), written", s);

  std::printf(
      "fixed steps from load_scene on: CPU %.2f s (fingerprint %016llx, %zu starts, %zu sums, "
      "largest offset %.9g, %.9g)\n",
      total_cpu, static_cast<unsigned long long>(fingerprint), starts.offset.size(),
      sums.size() + ao.size() + bent.size(), max_offset, caster.max_ray_offset());
  return 0;
}
