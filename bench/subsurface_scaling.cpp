// subsurface_scaling — the subsurface sum (bake/subsurface/dipole_gather.h): hierarchical
// against direct (error and time) at ~10k vertices for several ε, and the hierarchical sum's
// time against vertex count on subdivided spheres (n log n). Figures in docs/BENCHMARKS.md.
//   subsurface_scaling [--quick]
// The irradiance samples carry a synthetic order-3 transfer vector (the clamped cosine about
// the vertex normal, rotated: the unshadowed transfer), so only the sum is timed, not rays.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "bake/subsurface/dipole_gather.h"
#include "sh/basis.h"

using namespace prt;
using namespace prt::bake;

namespace {

// A UV sphere of radius 50 mm with about n vertices, unshadowed order-3 transfer.
SubsurfaceSamples sphere(int n) {
  const int rings = static_cast<int>(std::sqrt(n / 2.0)), segments = 2 * rings;
  SubsurfaceSamples s;
  s.K = 9;
  const double r = 50.0, pi = 3.14159265358979323846;
  const double zonal[3] = {0.8862269 / pi, 1.0233267 / pi, 0.4954159 / pi};  // clamped cos / π
  for (int i = 0; i <= rings; ++i) {
    const double theta = pi * i / rings;
    const int count = (i == 0 || i == rings) ? 1 : segments;
    for (int j = 0; j < count; ++j) {
      const double phi = 2 * pi * j / segments;
      const double x = std::sin(theta) * std::cos(phi), y = std::cos(theta),
                   z = std::sin(theta) * std::sin(phi);
      s.positions.push_back({r * x, r * y, r * z});
      // Area of the vertex's band share: 2π r² (cos θ0 − cos θ1)/count over its ring.
      const double t0 = pi * std::max(0.0, i - 0.5) / rings;
      const double t1 = pi * std::min<double>(rings, i + 0.5) / rings;
      s.areas.push_back(2 * pi * r * r * (std::cos(t0) - std::cos(t1)) / count);
      s.material.push_back(0);
      double y_k[9];
      sh::evaluate(3, x, y, z, y_k);
      for (int k = 0; k < 9; ++k) {
        const int l = k == 0 ? 0 : (k < 4 ? 1 : 2);
        s.transfer.push_back(zonal[l] * std::sqrt(4 * pi / (2 * l + 1)) * y_k[k]);
      }
    }
  }
  return s;
}

double seconds(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double relative_rms(const std::vector<double>& a, const std::vector<double>& ref) {
  double num = 0, den = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    num += (a[i] - ref[i]) * (a[i] - ref[i]);
    den += ref[i] * ref[i];
  }
  return std::sqrt(num / den);
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const std::vector<subsurface::DipoleMaterial> marble = {
      *subsurface::make_dipole(subsurface::find_subsurface_preset("marble")->coefficients)};
  const SubsurfaceSamples s10 = sphere(quick ? 2000 : 10000);
  std::printf("hierarchical vs direct, marble, sphere 100 mm, %zu vertices, order 3\n",
              s10.positions.size());
  SubsurfaceGatherOptions direct;
  direct.reference = true;
  auto t0 = std::chrono::steady_clock::now();
  const std::vector<double> ref = gather_subsurface(s10, marble, direct);
  std::printf("  direct        %7.2f s\n", seconds(t0));
  for (double eps : {0.05, 0.2, 0.5, 1.0, 2.0}) {
    SubsurfaceGatherOptions o;
    o.epsilon = eps;
    t0 = std::chrono::steady_clock::now();
    const std::vector<double> h = gather_subsurface(s10, marble, o);
    const double t = seconds(t0);
    const double e = relative_rms(h, ref);
    std::printf("  eps %-5.2f     %7.2f s  relative RMS %.2e\n", eps, t, e);
    if (!(e < 0.01) && eps <= 0.2) {
      std::printf("FAILED: eps %.2f above 1%%\n", eps);
      return 1;
    }
  }
  std::printf("hierarchical time against vertex count (eps 0.2)\n");
  for (int n : quick ? std::vector<int>{2000, 8000} : std::vector<int>{5000, 20000, 80000, 320000}) {
    const SubsurfaceSamples s = sphere(n);
    SubsurfaceGatherOptions o;
    o.epsilon = 0.2;
    SubsurfaceGatherStats st;
    t0 = std::chrono::steady_clock::now();
    gather_subsurface(s, marble, o, &st);
    const double t = seconds(t0);
    const double nn = static_cast<double>(s.positions.size());
    std::printf("  %7zu vertices %8.2f s  %.3g us per vertex  per n log2 n %.3g ns  "
                "(nodes %llu, node uses %llu, samples %llu)\n",
                s.positions.size(), t, 1e6 * t / nn, 1e9 * t / (nn * std::log2(nn)),
                static_cast<unsigned long long>(st.nodes),
                static_cast<unsigned long long>(st.node_evaluations),
                static_cast<unsigned long long>(st.sample_evaluations));
  }
  return 0;
}
