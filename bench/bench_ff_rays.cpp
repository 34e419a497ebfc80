// bench_ff_rays — closest-hit throughput of the ray form factors' access pattern (per patch:
// cosine-distributed rays from points on the patch) through scene::RayCaster's single rays,
// streams (rtcIntersect1M, incoherent and coherent hints) and 16-wide packets (shared origin,
// compared with single rays from that same origin). One thread; rays per thread-CPU-second
// (CLOCK_THREAD_CPUTIME_ID, so other processes' load does not count). Also checks that every
// query mode finds the same hits. Figures in docs/BENCHMARKS.md.
// Usage: bench_ff_rays SCENE MAX_EDGE [RAYS_PER_PATCH] [PATCH_STRIDE]
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "numerics/constants.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"

namespace {

double thread_seconds() {
  timespec t;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

struct Rays {
  std::vector<glm::vec3> origins, shared_origins, dirs;
};

// `per_patch` rays from every `stride`-th patch: uniform points, cosine directions.
Rays make_rays(const std::vector<prt::radiosity::Patch>& patches,
               const prt::scene::RayCaster& caster, int per_patch, int stride) {
  Rays r;
  std::mt19937_64 engine(1);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (std::size_t i = 0; i < patches.size(); i += std::size_t(stride)) {
    const prt::radiosity::Patch& p = patches[i];
    const glm::dvec3 n = p.normal;
    const glm::dvec3 t = std::abs(n.x) > 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0);
    const glm::dvec3 b1 = glm::normalize(glm::cross(t, n)), b2 = glm::cross(n, b1);
    const glm::vec3 centre =
        caster.surface_origin(uint32_t(i), glm::vec3(p.centroid), glm::vec3(p.normal));
    for (int k = 0; k < per_patch; ++k) {
      const double s = std::sqrt(u(engine)), v = u(engine);
      const glm::dvec3 x =
          p.corners[0] * (1 - s) + p.corners[1] * (s * (1 - v)) + p.corners[2] * (s * v);
      const double r2 = u(engine), phi = 2 * prt::numerics::kPi * u(engine);
      const glm::dvec3 d = b1 * (std::sqrt(r2) * std::cos(phi)) +
                           b2 * (std::sqrt(r2) * std::sin(phi)) + n * std::sqrt(1 - r2);
      r.origins.push_back(caster.surface_origin(uint32_t(i), glm::vec3(x), glm::vec3(p.normal)));
      r.shared_origins.push_back(centre);
      r.dirs.push_back(glm::vec3(glm::normalize(d)));
    }
  }
  return r;
}

using Hits = std::vector<prt::scene::RayCaster::Hit>;

void report(const char* name, std::size_t rays, const std::function<void(Hits*)>& run,
            const Hits* expected) {
  Hits hits(rays);
  double best = 1e300;
  for (int repeat = 0; repeat < 3; ++repeat) {
    const double t0 = thread_seconds();
    run(&hits);
    best = std::min(best, thread_seconds() - t0);
  }
  std::size_t differ = 0;
  if (expected)
    for (std::size_t i = 0; i < rays; ++i)
      differ += hits[i].hit != (*expected)[i].hit || hits[i].triangle != (*expected)[i].triangle;
  std::printf("%-34s %8.2f M rays/CPU-s  (%zu rays, %zu differ from single rays)\n", name,
              double(rays) / best * 1e-6, rays, differ);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_ff_rays SCENE MAX_EDGE [RAYS_PER_PATCH] [PATCH_STRIDE]\n");
    return 2;
  }
  const prt::scene::Scene scene =
      prt::scene::subdivide_to_edge_length(prt::scene::load_scene(argv[1]), std::atof(argv[2]));
  const int per_patch = argc > 3 ? std::atoi(argv[3]) : 256;
  const int stride = argc > 4 ? std::atoi(argv[4]) : 8;
  const prt::scene::RayCaster caster(scene);
  const std::vector<prt::radiosity::Patch> patches = prt::radiosity::make_patches(scene);
  const Rays r = make_rays(patches, caster, per_patch, stride);
  const std::size_t n = r.dirs.size();
  const float inf = std::numeric_limits<float>::infinity();
  std::printf("%zu patches, %d rays from every %d-th patch\n", patches.size(), per_patch, stride);
  const auto singles = [&](const std::vector<glm::vec3>& origins) {
    return [&, origins_ptr = &origins](Hits* out) {
      for (std::size_t i = 0; i < n; ++i)
        (*out)[i] = caster.intersect((*origins_ptr)[i], r.dirs[i], 0.f, inf);
    };
  };
  Hits single(n), single_shared(n);
  singles(r.origins)(&single);
  singles(r.shared_origins)(&single_shared);
  report("single rays (rtcIntersect1)", n, singles(r.origins), &single);
  for (int batch : {16, 64, 256}) {
    for (bool coherent : {false, true}) {
      const std::string name = std::string("stream of ") + std::to_string(batch) +
                               (coherent ? " (coherent)" : " (incoherent)");
      report(
          name.c_str(), n,
          [&](Hits* out) {
            for (std::size_t i = 0; i < n; i += std::size_t(batch)) {
              const int count = int(std::min<std::size_t>(std::size_t(batch), n - i));
              caster.intersect_stream(&r.origins[i], &r.dirs[i], count, inf, coherent, &(*out)[i]);
            }
          },
          &single);
    }
  }
  report("single rays, shared origin", n, singles(r.shared_origins), &single_shared);
  report(
      "packets of 16, shared origin", n,
      [&](Hits* out) {
        for (std::size_t i = 0; i < n; i += 16) {
          const int count = int(std::min<std::size_t>(16, n - i));
          caster.intersect_packet(r.shared_origins[i], &r.dirs[i], count, inf, &(*out)[i]);
        }
      },
      &single_shared);
  return 0;
}
