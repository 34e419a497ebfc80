// bench/haar_file_relight.cpp — relight ~50k vertices in colour with K = 200 at N = 32 from a
// *real* baked Haar file, on one core.
//
// Either bakes the scene (shadowed, N = 32, colour albedo, 16-bit, relative threshold T),
// writes it with prt::write_haar_transfer_file and reads it back, or reads an existing file
// (--file). Then: the K-term non-linear lighting of the HDR (prt::relight::project_haar_lighting,
// identity rotation), the thread pinned to one CPU (the first one it may run on, so
// `taskset -c 1` picks CPU 1), and, alternating in the same run, R relights with
// prt::shade_index_lists (the plain per-index list walk: "before") and with
// HaarRelighter::shade (vertex-blocked, dense columns: "after"); prints the median wall and
// thread-CPU time per relight of each, their largest difference, the list entries the lighting
// touches and the file's size.
// Usage: haar_file_relight [--mesh OBJ] [--hdr HDR] [--threshold T] [--bits 8|16]
//                          [--albedo R,G,B] [--file PRT] [--out PRT] [--repeat R] [--terms K]
//                          [--block B] [--dense F]   (HaarRelighterLayout)
#include <sched.h>
#include <time.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "bake/haar_baker.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/haar/relighter.h"
#include "relight/haar_relight.h"
#include "relight/image_io.h"
#include "scene/scene_loader.h"

namespace {

double thread_cpu_seconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string data = PRT_SHARED_DATA_DIR;
  std::string mesh = data + "/meshes/buddha.obj", hdr = data + "/hdri/rooitou_park_1k.hdr";
  std::string file, out = "/tmp/haar_file_relight.prt";
  double threshold = 1e-3, albedo[3] = {0.6, 0.5, 0.4};
  int bits = 16, repeat = 50, terms = 200;
  prt::HaarRelighterLayout layout;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h" || i + 1 >= argc) {
      std::printf(
          "usage: haar_file_relight [--mesh OBJ] [--hdr HDR] [--threshold T] [--bits 8|16]\n"
          "  [--albedo R,G,B] [--file PRT] [--out PRT] [--repeat R] [--terms K] [--block B]\n"
          "  [--dense F]\n");
      return a == "--help" || a == "-h" ? 0 : 2;
    }
    const std::string v = argv[i + 1];
    if (a == "--block")
      layout.block_vertices = std::atoi(v.c_str());
    else if (a == "--dense")
      layout.dense_fraction = std::atof(v.c_str());
    else if (a == "--mesh")
      mesh = v;
    else if (a == "--hdr")
      hdr = v;
    else if (a == "--threshold")
      threshold = std::atof(v.c_str());
    else if (a == "--bits")
      bits = std::atoi(v.c_str());
    else if (a == "--file")
      file = v;
    else if (a == "--out")
      out = v;
    else if (a == "--repeat")
      repeat = std::max(1, std::atoi(v.c_str()));
    else if (a == "--terms")
      terms = std::atoi(v.c_str());
    else if (a == "--albedo")
      std::sscanf(v.c_str(), "%lf,%lf,%lf", &albedo[0], &albedo[1], &albedo[2]);
    else {
      std::fprintf(stderr, "haar_file_relight: unknown option %s\n", a.c_str());
      return 2;
    }
  }
  try {
    if (file.empty()) {
      prt::scene::Scene scene = prt::scene::load_scene(mesh);
      for (glm::vec3& a : scene.albedo)
        a = glm::vec3(float(albedo[0]), float(albedo[1]), float(albedo[2]));
      prt::bake::HaarBakeOptions o;
      o.transport = prt::TransferKind::Shadowed;
      o.cube_size = 32;
      o.compression.quantization =
          bits == 8 ? prt::HaarQuantization::Bits8 : prt::HaarQuantization::Bits16;
      o.compression.relative_threshold = threshold;
      const prt::bake::HaarBakeResult baked = prt::bake::bake_haar_transfer(scene, o);
      std::printf("baked %s: %llu vertices, %.1f s (%.2f Mrays/s, %llu rays)\n", mesh.c_str(),
                  static_cast<unsigned long long>(baked.stats.vertices), baked.stats.seconds_total,
                  baked.stats.mrays_per_second(),
                  static_cast<unsigned long long>(baked.stats.rays));
      const prt::Status s = prt::write_haar_transfer_file(out, baked.file);
      if (!s.ok()) throw std::runtime_error(s.message());
      file = out;
    }
    prt::Result<prt::HaarTransferFile> f = prt::read_haar_transfer_file(file);
    if (!f.ok()) throw std::runtime_error(f.status().message());
    const prt::HaarTransfer& t = f->transfer;
    const double V = double(t.vertex_count);
    std::printf(
        "file %s: %lld vertices, N = %d, %d channels, %d-bit, %.0f B/vertex stored "
        "(%.1f%% of dense float), %.1f terms/vertex (%.2f%% non-zero)\n",
        file.c_str(), static_cast<long long>(t.vertex_count), t.size, t.channels,
        static_cast<int>(t.quantization), double(t.stored_bytes()) / V,
        100.0 * double(t.stored_bytes()) / double(t.dense_bytes()), double(t.entry_count()) / V,
        100.0 * double(t.entry_count()) / V / (6.0 * t.size * t.size));
    const prt::sh::EnvMap env = prt::relight::read_environment(hdr, std::nullopt, nullptr);
    prt::relight::HaarLightingOptions lo;
    lo.terms = terms;
    const prt::SparseLighting lighting =
        prt::relight::project_haar_lighting(env, t.size, {1, 0, 0, 0, 1, 0, 0, 0, 1}, lo);
    uint64_t touched = 0;
    for (uint32_t i : lighting.index) touched += t.offsets[i + 1] - t.offsets[i];

    cpu_set_t set;
    CPU_ZERO(&set);
    if (sched_getaffinity(0, sizeof set, &set) != 0) std::perror("sched_getaffinity");
    int cpu = 0;
    while (cpu < CPU_SETSIZE && !CPU_ISSET(cpu, &set)) ++cpu;
    CPU_ZERO(&set);
    CPU_SET(cpu, &set);
    if (sched_setaffinity(0, sizeof set, &set) != 0) std::perror("sched_setaffinity");
    const double build0 = thread_cpu_seconds();
    const prt::HaarRelighter relighter(std::move(f->transfer), layout);
    const double build_seconds = thread_cpu_seconds() - build0;
    const prt::HaarTransfer& tr = relighter.transfer();
    std::printf(
        "blocked layout: %d vertices/block, dense fraction %.2f: %.0f B/vertex, %llu dense "
        "slices holding %llu entries (incl. zero padding; %llu entries in the lists), built in "
        "%.2f s CPU\n",
        relighter.layout().block_vertices, relighter.layout().dense_fraction,
        double(relighter.blocked_bytes()) / V,
        static_cast<unsigned long long>(relighter.dense_slice_count()),
        static_cast<unsigned long long>(relighter.dense_entry_count()),
        static_cast<unsigned long long>(tr.entry_count()), build_seconds);
    const std::size_t n = 3 * static_cast<std::size_t>(relighter.vertex_count());
    std::vector<float> before(n), after(n);
    if (!prt::shade_index_lists(tr, lighting, before.data()).ok() ||
        !relighter.shade(lighting, after.data()).ok())
      throw std::runtime_error("shade failed");
    double max_diff = 0.0, max_value = 0.0;
    for (std::size_t j = 0; j < n; ++j) {
      max_diff = std::max(max_diff, double(std::fabs(before[j] - after[j])));
      max_value = std::max(max_value, double(std::fabs(before[j])));
    }
    std::vector<double> wall[2], cpu_time[2];
    for (int r = 0; r < repeat; ++r) {
      for (int which = 0; which < 2; ++which) {
        const auto w0 = std::chrono::steady_clock::now();
        const double c0 = thread_cpu_seconds();
        const bool ok = which == 0 ? prt::shade_index_lists(tr, lighting, before.data()).ok()
                                   : relighter.shade(lighting, after.data()).ok();
        if (!ok) throw std::runtime_error("shade failed");
        cpu_time[which].push_back(thread_cpu_seconds() - c0);
        wall[which].push_back(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - w0).count());
      }
    }
    std::printf(
        "relight K = %zu non-linear, RGB, CPU %d; %llu list entries touched (%.2f%% of "
        "%llu); max |after - before| = %.3g (largest value %.3g)\n",
        lighting.term_count(), cpu, static_cast<unsigned long long>(touched),
        100.0 * double(touched) / double(tr.entry_count()),
        static_cast<unsigned long long>(tr.entry_count()), max_diff, max_value);
    const char* names[2] = {"before (shade_index_lists)", "after  (HaarRelighter::shade)"};
    for (int which = 0; which < 2; ++which) {
      std::printf("  %s: median %.3f ms CPU, %.3f ms wall (min %.3f / %.3f) over %d runs\n",
                  names[which], 1e3 * median(cpu_time[which]), 1e3 * median(wall[which]),
                  1e3 * *std::min_element(cpu_time[which].begin(), cpu_time[which].end()),
                  1e3 * *std::min_element(wall[which].begin(), wall[which].end()), repeat);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "haar_file_relight: %s\n", e.what());
    return 1;
  }
  return 0;
}
