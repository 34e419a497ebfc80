// adaptive_proof — `prt bake --auto` against the fixed recipe at equal measured error
// (issue 7). Writes docs/adaptive/README.md (or the path given as argv[1]).
//
// Per scene: a reference (fixed interreflected bake, order 8, 2048 samples, solved to 1e-6),
// the --auto bake (tolerance 0.01) and fixed interreflected bakes at the order --auto chose with
// 64 … 1024 samples. The error is the relative RMS of exit radiance over vertices and RGB under
// a band-limited sky (bands 0–5: ambient + a smooth lobe; the same lighting for every bake).
// "Equal error": the cheapest fixed sample count whose measured error is ≤ the --auto error
// (or the best fixed one when none reaches it). Time is bake wall time (2 threads).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "bake/adaptive_baker.h"
#include "bake/procedural_mesh.h"
#include "bake/scene_loader.h"
#include "bake/transfer_baker.h"
#include "prt/transfer_file.h"
#include "sh/zonal.h"

using namespace prt::bake;

namespace {

constexpr int kLightingOrder = 8;
constexpr double kTolerance = 0.01;

std::vector<double> make_sky() {
  const int K = kLightingOrder * kLightingOrder;
  std::vector<double> zonal(kLightingOrder, 0.0), lobe(K), out(3 * K, 0.0);
  for (int l = 0; l < 6; ++l) zonal[l] = 1.5 * std::exp(-0.12 * l * (l + 1));
  const double n = std::sqrt(0.4 * 0.4 + 0.8 * 0.8 + 0.45 * 0.45);
  sh::rotate_zonal(kLightingOrder, zonal.data(), 0.4 / n, 0.8 / n, 0.45 / n, lobe.data());
  const double tint[3] = {1.0, 0.8, 0.6};
  for (int c = 0; c < 3; ++c) {
    for (int k = 0; k < K; ++k) out[c * K + k] = tint[c] * lobe[k];
    out[c * K] += 0.3 * 3.5449077018110318;
  }
  return out;
}

std::size_t file_bytes(const prt::TransferData& data) {
  const std::string path = "/tmp/adaptive_proof_" + std::to_string(getpid()) + ".prt";
  if (!prt::write_transfer_file(path, data).ok()) return 0;
  std::error_code ec;
  const auto bytes = std::filesystem::file_size(path, ec);
  std::filesystem::remove(path, ec);
  return ec ? 0 : static_cast<std::size_t>(bytes);
}

struct Row {
  std::string name;
  std::size_t vertices = 0;
  double auto_seconds = 0, auto_error = 0, predicted = 0, mean_samples = 0;
  int order = 0;
  std::string auto_kind;
  std::size_t auto_bytes = 0, open = 0;
  int fixed_samples = 0;
  double fixed_seconds = 0, fixed_error = 0;
  std::size_t fixed_bytes = 0;
  std::string fixed_table;
};

Row run_scene(const std::string& name, const Scene& scene, const std::vector<double>& sky) {
  Row row;
  row.name = name;
  row.vertices = scene.vertex_count();
  BakeOptions ref;
  ref.kind = prt::TransferKind::Interreflected;
  ref.order = kLightingOrder;
  ref.samples = 2048;
  ref.bounce_tolerance = 1e-6;
  const std::vector<double> b_ref =
      exit_radiance(bake_transfer(scene, ref).data, sky, kLightingOrder);

  AutoBakeOptions o;
  o.tolerance = kTolerance;
  o.lighting = sky;
  o.lighting_order = kLightingOrder;
  const auto t0 = std::chrono::steady_clock::now();
  const AutoBakeResult a = bake_transfer_auto(scene, o);
  row.auto_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  row.auto_error = relative_rms_error(exit_radiance(a.bake.data, sky, kLightingOrder), b_ref);
  row.predicted = a.report.predicted_error;
  row.order = a.report.order;
  row.mean_samples = a.report.mean_samples;
  row.auto_kind = transfer_kind_name(a.bake.data.kind);
  row.auto_bytes = file_bytes(a.bake.data);
  row.open = a.report.open_vertices;

  bool found = false;
  for (int samples : {64, 128, 256, 512, 1024}) {
    BakeOptions f;
    f.kind = prt::TransferKind::Interreflected;
    f.order = row.order;
    f.samples = samples;
    const BakeResult r = bake_transfer(scene, f);
    const double err = relative_rms_error(exit_radiance(r.data, sky, kLightingOrder), b_ref);
    char line[160];
    std::snprintf(line, sizeof line, "%d: %.4f in %.2f s; ", samples, err, r.stats.seconds_total);
    row.fixed_table += line;
    // Keep the first setting at equal error, else the most accurate one so far.
    if (!found || (row.fixed_error > row.auto_error && err < row.fixed_error)) {
      row.fixed_samples = samples;
      row.fixed_seconds = r.stats.seconds_total;
      row.fixed_error = err;
      row.fixed_bytes = file_bytes(r.data);
    }
    found = true;
    if (err <= row.auto_error) break;  // the cheapest fixed setting at equal error
  }
  std::printf("%s: auto %.2f s err %.4f (pred %.4f) | fixed %d: %.2f s err %.4f | %s\n",
              name.c_str(), row.auto_seconds, row.auto_error, row.predicted, row.fixed_samples,
              row.fixed_seconds, row.fixed_error, row.fixed_table.c_str());
  std::fflush(stdout);
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string out =
      argc > 1 ? argv[1] : std::string(PRT_SOURCE_DIR) + "/docs/adaptive/README.md";
  const std::string data = PRT_SHARED_DATA_DIR;
  const std::vector<double> sky = make_sky();
  std::vector<Row> rows;
  rows.push_back(run_scene("convex: UV sphere 64×128",
                           make_uv_sphere({0.f, 1.f, 0.f}, 1.f, 64, 128, false, glm::vec3(0.6f)),
                           sky));
  {
    Scene s = make_quad({-4.f, 0.f, 4.f}, {8.f, 0.f, 0.f}, {0.f, 0.f, -8.f}, 80, 80,
                        glm::vec3(0.6f), "ground");
    append_scene(s, make_uv_sphere({-1.f, 0.7f, 0.f}, 0.7f, 32, 64, false, glm::vec3(0.6f)));
    append_scene(s, make_box({0.8f, 0.f, -0.6f}, {1.8f, 1.2f, 0.6f}, 16, false, glm::vec3(0.6f)));
    append_scene(s, make_uv_sphere({0.5f, 0.4f, 1.8f}, 0.4f, 24, 48, false, glm::vec3(0.6f)));
    rows.push_back(run_scene("plane with 3 objects", s, sky));
  }
  const std::string bunny = data + "/meshes/stanford-bunny.obj";
  if (std::filesystem::exists(bunny))
    rows.push_back(run_scene("Stanford bunny", load_scene(bunny), sky));
  const std::string ship = data + "/meshes/dutch_ship/dutch_ship_medium_1k.gltf";
  if (std::filesystem::exists(ship)) {
    LoadOptions lo;
    lo.albedo_override = glm::vec3(0.6f);
    rows.push_back(run_scene("dutch ship (albedo 0.6)", load_scene(ship, lo), sky));
  }

  std::ofstream f(out);
  f << "# Adaptive baking (`prt bake --auto`) against the fixed recipe\n\n"
    << "Written by `adaptive_proof` (bench/adaptive_proof.cpp). Tolerance " << kTolerance
    << "; error = relative RMS of exit radiance over vertices and RGB under a band-limited sky "
       "(bands 0–5), measured against a fixed interreflected bake at order 8 with 2048 samples "
       "solved to 1e-6. The fixed setting is interreflected at the order --auto chose, with the "
       "fewest samples (64…1024) whose measured error is ≤ the --auto error (or the best one). "
       "Times are bake wall times on this 2-core VM (auto includes analysis and the pilot).\n\n"
    << "| scene | vertices | open (no rays) | auto: kind, order, mean samples | auto time | auto "
       "error (predicted) | fixed samples | fixed time | fixed error | speed-up | bytes auto / "
       "fixed |\n|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const Row& r : rows) {
    char line[512];
    std::snprintf(line, sizeof line,
                  "| %s | %zu | %zu | %s, %d, %.0f | %.2f s | %.4f (%.4f) | %d | %.2f s | %.4f | "
                  "%.2f× | %zu / %zu |\n",
                  r.name.c_str(), r.vertices, r.open, r.auto_kind.c_str(), r.order, r.mean_samples,
                  r.auto_seconds, r.auto_error, r.predicted, r.fixed_samples, r.fixed_seconds,
                  r.fixed_error, r.fixed_seconds / r.auto_seconds, r.auto_bytes, r.fixed_bytes);
    f << line;
  }
  f << "\nFixed sweeps (samples: error in time):\n\n";
  for (const Row& r : rows) f << "- " << r.name << ": " << r.fixed_table << "\n";
  std::printf("wrote %s\n", out.c_str());
  return 0;
}
