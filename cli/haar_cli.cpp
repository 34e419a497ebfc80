// cli/haar_cli.cpp — see haar_cli.h.
#include "haar_cli.h"

#include <cstdio>

#include "bake/haar_baker.h"
#include "bake/transfer_baker.h"
#include "command_registry.h"
#include "progress_reporter.h"
#include "prt/formats/haar_transfer_file.h"
#include "relight/haar_relight.h"
#include "run_record.h"

namespace prt::cli {

void add_haar_bake_options(CLI::App* cmd, HaarBakeArguments* a) {
  cmd->add_option("--basis", a->basis, "sh | haar (all-frequency Haar wavelets on a cube map)")
      ->check(CLI::IsMember({"sh", "haar"}))
      ->capture_default_str();
  cmd->add_option("--cube", a->cube, "Haar: cube size N (power of two, 8..128)")
      ->capture_default_str();
  auto* threshold = cmd->add_option("--haar-threshold", a->threshold,
                                    "Haar: keep terms ≥ X × the vertex's largest (default 0.001)");
  auto* terms = cmd->add_option("--haar-terms", a->terms, "Haar: keep the M largest per vertex");
  threshold->excludes(terms);
  cmd->add_option("--haar-bits", a->bits, "Haar: quantisation 8 | 16 (32 = unquantised floats)")
      ->check(CLI::IsMember({8, 16, 32}))
      ->capture_default_str();
  cmd->add_option("--haar-supersample", a->supersample, "Haar: S×S jittered rays per texel")
      ->capture_default_str();
}

bake::HaarBakeOptions haar_bake_options(prt::TransferKind kind, const HaarBakeArguments& a,
                                        uint64_t seed, int threads, int bounces, double tolerance,
                                        uint64_t memory_limit) {
  bake::HaarBakeOptions o;
  o.transport = kind;
  o.cube_size = a.cube;
  o.supersample = a.supersample;
  o.compression.relative_threshold = a.threshold >= 0 ? a.threshold : (a.terms > 0 ? 0.0 : 1e-3);
  o.compression.max_terms_per_vertex = a.terms;
  o.compression.quantization = a.bits == 8    ? prt::HaarQuantization::Bits8
                               : a.bits == 16 ? prt::HaarQuantization::Bits16
                                              : prt::HaarQuantization::Float32;
  o.seed = seed;
  o.threads = threads;
  o.bounces = bounces;
  o.bounce_tolerance = tolerance;
  o.memory_limit = memory_limit;
  return o;
}

void run_haar_bake(const scene::Scene& scene, const std::string& output, prt::TransferKind kind,
                   const HaarBakeArguments& a, uint64_t seed, int threads, int bounces,
                   double tolerance, bool quiet, uint64_t memory_limit) {
  const bake::HaarBakeOptions o =
      haar_bake_options(kind, a, seed, threads, bounces, tolerance, memory_limit);
  ProgressReporter progress(quiet);
  const bake::HaarBakeResult r = bake::bake_haar_transfer(scene, o, &progress);
  const prt::Status written = prt::write_haar_transfer_file(output, r.file);
  if (!written.ok()) throw CommandError(written.message());
  const bake::HaarBakeStatistics& st = r.stats;
  run_record().phase("rays", st.seconds_rays);
  if (st.seconds_solve > 0) run_record().phase("interreflection solve", st.seconds_solve);
  run_record().phase("bake", st.seconds_total);
  if (quiet) return;
  std::printf(
      "baked %s Haar transfer of %s: %llu vertices, cube %d (%d coefficients), %u channel%s; "
      "%llu rays in %.2f s (%.2f Mrays/s)",
      bake::transfer_kind_name(kind), scene.source_path.c_str(),
      static_cast<unsigned long long>(st.vertices), a.cube, 6 * a.cube * a.cube,
      r.file.info.channels, r.file.info.channels == 1 ? "" : "s",
      static_cast<unsigned long long>(st.rays), st.seconds_rays, st.mrays_per_second());
  if (kind == prt::TransferKind::Interreflected)
    std::printf("; interreflection %d iterations, residual %.2g (%.2f s)%s", st.solver_iterations,
                st.solver_residual, st.seconds_solve, st.solver_converged ? "" : " NOT CONVERGED");
  const double per_vertex = st.vertices ? double(st.entries) / double(st.vertices) : 0.0;
  const double stored = static_cast<double>(st.stored_bytes);
  const double dense = static_cast<double>(st.dense_bytes);
  const double vertices = static_cast<double>(st.vertices);
  std::printf(
      "; kept %.1f terms per vertex (%.2f%%); stored %.2f MB vs %.2f MB dense (%.1f%%, %.0f "
      "bytes/vertex, %d-bit); wrote %s.\n",
      per_vertex, 100.0 * per_vertex / (6.0 * a.cube * a.cube), stored * 1e-6, dense * 1e-6,
      dense > 0 ? 100.0 * stored / dense : 0.0, vertices > 0 ? stored / vertices : 0.0, a.bits,
      output.c_str());
}

void add_haar_relight_options(CLI::App* cmd, HaarRelightArguments* a) {
  cmd->add_option("--terms", a->terms, "Haar files: lighting terms K (0 = all)")
      ->capture_default_str();
  cmd->add_option("--approx", a->approx, "Haar files: nonlinear | linear")
      ->check(CLI::IsMember({"nonlinear", "linear"}))
      ->capture_default_str();
}

bool relight_if_haar(const relight::RelightRequest& request, const HaarRelightArguments& a,
                     bool quiet) {
  if (!prt::is_haar_transfer_file(request.transfer_path)) return false;
  if (a.terms < 0)
    throw UsageError("--terms " + std::to_string(a.terms) + ": must be >= 0 (0 = all)");
  relight::HaarLightingOptions options;
  options.terms = a.terms;
  options.linear = a.approx == "linear";
  const relight::RelightSummary s = relight::run_haar_relight(request, options);
  const int64_t coefficients = int64_t{6} * s.order * s.order;  // summary.order = cube size
  if (a.terms > coefficients)
    std::fprintf(stderr,
                 "prt relight: warning: --terms %lld is more than the %lld wavelet coefficients "
                 "of the cube (size %d): all of them were used\n",
                 static_cast<long long>(a.terms), static_cast<long long>(coefficients), s.order);
  if (quiet) return true;
  std::printf("relit %zu vertices (%s); shading %.2f ms, rendering %.3f s", s.vertex_count,
              s.window_note.c_str(), 1e3 * s.shade_seconds, s.render_seconds);
  if (s.negative_vertices > 0)
    std::printf("; %zu vertices got negative radiance", s.negative_vertices);
  std::printf(".\n%s\nwrote:", relight::describe_view(request, s).c_str());
  for (const std::string& file : s.files_written) std::printf(" %s", file.c_str());
  std::printf("\n");
  return true;
}

}  // namespace prt::cli
