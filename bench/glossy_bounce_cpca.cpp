// glossy_bounce_cpca — the error of glossy bounces that read CPCA-compressed transfer
// (GlossyBakeOptions::bounce_cpca_clusters; docs/GLOSSY.md, "Glossy bakes at scale") against
// the plain bounces, on a scene whose matrices fit in memory.
//
//   glossy_bounce_cpca SCENE ORDER SAMPLES BOUNCES CLUSTERSxVECTORS...
//
// Bakes the shadowed transfer S, the plain interreflected transfer M (BOUNCES Jacobi bounces)
// and, for each CLUSTERSxVECTORS, M' whose bounces gathered from the compression; prints the
// relative RMS error of M' against M over the whole matrices and over the bounced light M − S
// alone, the compressed size against the uncompressed one, and the times. Primitives named
// "sphere" get a Ward BRDF and "box" a Blinn-Phong one (the demo scene's names); the rest keep
// their materials. Same seed everywhere, so the errors are the compression's alone.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "bake/glossy_transfer_baker.h"
#include "scene/scene_loader.h"

namespace {

double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// sqrt(Σ (a − b)² / Σ b²) over the entries, b − base and a − base when base is given (the
// grey S broadcast over the channels).
double relative_rms(const prt::GlossyTransferData& a, const prt::GlossyTransferData& b,
                    const prt::GlossyTransferData* base) {
  const std::size_t kk = b.matrix_floats(), C = b.channels;
  double err = 0, norm = 0;
  for (std::size_t v = 0; v < b.vertex_count; ++v)
    for (std::size_t c = 0; c < C; ++c)
      for (std::size_t e = 0; e < kk; ++e) {
        const std::size_t i = (v * C + c) * kk + e;
        const double s = base ? base->matrices[v * kk + e] : 0.0;
        const double x = double(b.matrices[i]) - s, y = double(a.matrices[i]) - s;
        err += (y - x) * (y - x);
        norm += x * x;
      }
  return std::sqrt(err / norm);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: %s SCENE ORDER SAMPLES BOUNCES CLUSTERSxVECTORS...\n", argv[0]);
    return 2;
  }
  prt::scene::Scene scene = prt::scene::load_scene(argv[1]);
  for (auto& p : scene.primitives) {
    if (p.name.rfind("sphere", 0) == 0) {
      p.brdf = prt::brdf::Material{};
      p.brdf->model = prt::brdf::MaterialModel::kWard;
      p.brdf->diffuse = prt::brdf::grey(0.3);
      p.brdf->specular = prt::brdf::grey(0.3);
      p.brdf->alpha_x = p.brdf->alpha_y = 0.15;
    } else if (p.name.rfind("box", 0) == 0) {
      p.brdf = prt::brdf::Material{};
      p.brdf->model = prt::brdf::MaterialModel::kBlinnPhong;
      p.brdf->diffuse = prt::brdf::grey(0.4);
      p.brdf->specular = prt::brdf::grey(0.3);
      p.brdf->exponent = 30;
    }
  }
  prt::bake::GlossyBakeOptions o;
  o.order = std::atoi(argv[2]);
  o.samples = std::atoi(argv[3]);
  o.bounces = 0;
  auto t0 = std::chrono::steady_clock::now();
  const auto shadowed = prt::bake::bake_glossy_transfer(scene, o);
  std::printf("%s: %llu vertices, order %d, %d samples; shadowed %.1f s\n", argv[1],
              static_cast<unsigned long long>(shadowed.stats.vertices), o.order, o.samples,
              seconds(t0));
  o.bounces = std::atoi(argv[4]);
  t0 = std::chrono::steady_clock::now();
  const auto plain = prt::bake::bake_glossy_transfer(scene, o);
  const double bytes = 4.0 * double(plain.data.matrices.size());
  std::printf("plain: %d bounces, %u channels, %.1f MB of matrices, %.1f s\n", o.bounces,
              plain.data.channels, bytes / 1e6, seconds(t0));
  for (int i = 5; i < argc; ++i) {
    unsigned clusters = 0, vectors = 0;
    if (std::sscanf(argv[i], "%ux%u", &clusters, &vectors) != 2) return 2;
    o.bounce_cpca_clusters = clusters;
    o.bounce_cpca_vectors = vectors;
    t0 = std::chrono::steady_clock::now();
    const auto c = prt::bake::bake_glossy_transfer(scene, o);
    std::printf(
        "%3u clusters x %2u vectors: compressed %.2f MB (%.2f%%); relative RMS error %.4f of M, "
        "%.4f of the bounced light M - S; %.1f s\n",
        clusters, vectors, double(c.stats.bounce_cpca_bytes) / 1e6,
        100.0 * double(c.stats.bounce_cpca_bytes) / bytes,
        relative_rms(c.data, plain.data, nullptr), relative_rms(c.data, plain.data, &shadowed.data),
        seconds(t0));
    std::fflush(stdout);
  }
  return 0;
}
