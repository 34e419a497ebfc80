// bench_bake — the baker's speed against the pure ray rate, on a real mesh.
//
//   bench_bake [MESH] [--samples N] [--threads T] [--orders 5,10]
//
// For each order: a shadowed bake (bake_transfer) and, before it, the same rays cast with no SH
// work (the same Owen-scrambled directions, rtcOccluded16 packets sharing the vertex origin,
// same vertex blocks). Prints wall time, Mrays/s, the bake/pure ratio, and memory: peak RSS
// (getrusage) after the first bake vs the output file (f32) plus Embree's peak (BVH) bytes.
// Default mesh: ../shared/data/meshes/stanford-bunny.obj. Figures go in docs/BENCHMARKS.md.
#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include "bake/sampling.h"
#include "bake/transfer_baker.h"
#include "prt/formats/transfer_file.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

double mib(std::size_t bytes) {
  return static_cast<double>(bytes) / 1048576.0;
}

double peak_rss_mib() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_maxrss) / 1024.0;  // Linux: KiB
}

// User + system CPU seconds of the process so far.
double cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// The baker's ray pattern without any SH work; returns seconds (rays = V × samples).
double cast_pure_rays(const prt::scene::Scene& scene, const prt::scene::RayCaster& caster,
                      int samples, uint64_t seed, uint64_t* occluded_total) {
  const std::size_t V = scene.positions.size(), block = 64;
  std::atomic<uint64_t> occluded{0};
  const Clock::time_point t0 = Clock::now();
  tbb::parallel_for(std::size_t(0), (V + block - 1) / block, [&](std::size_t b) {
    glm::vec3 dirs[16];
    bool occ[16];
    uint64_t count = 0;
    for (std::size_t v = b * block; v < std::min(V, (b + 1) * block); ++v) {
      const glm::vec3 n = glm::normalize(scene.normals[v]);
      const glm::vec3 o = caster.vertex_origin(static_cast<uint32_t>(v));
      for (int first = 0; first < samples; first += 16) {
        prt::bake::generate_cosine_directions(n, seed, v, static_cast<uint32_t>(first), 16, dirs);
        caster.occluded_packet(o, dirs, 16, std::numeric_limits<float>::infinity(), occ);
        for (int i = 0; i < 16; ++i) count += occ[i];
      }
    }
    occluded += count;
  });
  const double s = seconds_since(t0);
  *occluded_total = occluded.load();
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh = std::string(PRT_SHARED_DATA_DIR) + "/meshes/stanford-bunny.obj";
  int samples = 1024, threads = 2;
  std::vector<int> orders = {5, 10};
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--samples" && i + 1 < argc) {
      samples = std::atoi(argv[++i]);
    } else if (a == "--threads" && i + 1 < argc) {
      threads = std::atoi(argv[++i]);
    } else if (a == "--orders" && i + 1 < argc) {
      orders.clear();
      for (char* tok = std::strtok(argv[++i], ","); tok; tok = std::strtok(nullptr, ","))
        orders.push_back(std::atoi(tok));
    } else if (a[0] != '-') {
      mesh = a;
    } else {
      std::fprintf(stderr, "usage: bench_bake [MESH] [--samples N] [--threads T] [--orders a,b]\n");
      return 2;
    }
  }
  const double baseline_rss = peak_rss_mib();
  try {
    std::optional<tbb::global_control> limit;
    if (threads > 0) limit.emplace(tbb::global_control::max_allowed_parallelism, threads);
    Clock::time_point t = Clock::now();
    const prt::scene::Scene scene = prt::scene::load_scene(mesh);
    const double load_s = seconds_since(t);
    std::printf(
        "mesh %s: %zu vertices, %zu triangles (load %.2f s, peak RSS after loading %.1f MiB); "
        "%d samples, %d threads\n",
        mesh.c_str(), scene.positions.size(), scene.triangles.size(), load_s, peak_rss_mib(),
        samples, threads);
    const double rays =
        static_cast<double>(scene.positions.size()) * prt::bake::round_up_to_packet(samples);
    double pure_s = 0, pure_cpu = 0;
    std::size_t bvh_bytes = 0;
    {
      t = Clock::now();
      const prt::scene::RayCaster caster(scene);
      const double build_s = seconds_since(t);
      bvh_bytes = caster.embree_peak_bytes();
      uint64_t occluded = 0;
      cast_pure_rays(scene, caster, 64, 1, &occluded);  // warm-up
      const double cpu0 = cpu_seconds();
      pure_s = cast_pure_rays(scene, caster, prt::bake::round_up_to_packet(samples), 1, &occluded);
      pure_cpu = cpu_seconds() - cpu0;
      std::printf("BVH build %.3f s, Embree peak %.1f MiB\n", build_s, mib(bvh_bytes));
      std::printf(
          "pure rays (occluded16, no SH): wall %.3f s, %.2f Mrays/s; CPU %.3f s, %.2f Mrays per "
          "CPU-second (%.1f%% occluded)\n",
          pure_s, rays / pure_s * 1e-6, pure_cpu, rays / pure_cpu * 1e-6,
          100.0 * static_cast<double>(occluded) / rays);
    }
    bool first = true;
    for (const int order : orders) {
      prt::bake::BakeOptions o;
      o.kind = prt::TransferKind::Shadowed;
      o.order = order;
      o.samples = samples;
      o.threads = threads;
      t = Clock::now();
      const double cpu0 = cpu_seconds();
      const prt::bake::BakeResult r = prt::bake::bake_transfer(scene, o);
      const double wall = seconds_since(t), cpu = cpu_seconds() - cpu0;
      const double rss = peak_rss_mib();
      const double mrays = r.stats.mrays_per_second();
      std::printf(
          "order %2d: wall %.3f s (sampling pass %.3f s), %.2f Mrays/s = %.0f%% of the pure "
          "ray rate; CPU %.3f s, %.2f Mrays per CPU-second = %.0f%% of pure\n",
          order, wall, r.stats.seconds_rays, mrays, 100.0 * mrays / (rays / pure_s * 1e-6), cpu,
          rays / cpu * 1e-6, 100.0 * pure_cpu / cpu);
      if (first) {
        first = false;
        const auto bytes = prt::encode_transfer_file(r.data, "bench");
        const double file_mib = bytes.ok() ? mib(bytes.value().size()) : 0.0;
        const double budget = file_mib + mib(r.stats.bvh_bytes);
        std::printf(
            "memory after order %d: peak RSS %.1f MiB (%.1f MiB at start: code and libraries); "
            "output file %.1f MiB + BVH %.1f MiB = %.1f MiB; ratio %.2f (%.2f above the start)\n",
            order, rss, baseline_rss, file_mib, mib(r.stats.bvh_bytes), budget, rss / budget,
            (rss - baseline_rss) / budget);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "bench_bake: %s\n", e.what());
    return 1;
  }
  return 0;
}
