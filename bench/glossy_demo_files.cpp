// Writes the glossy demo scenes and their glossy transfer files (for `prt relight` pictures in
// docs/GLOSSY.md), and times the glossy shading kernel (docs/BENCHMARKS.md, "Glossy runtime").
//
//   glossy_demo_files OUT_DIR [ORDER]
// writes OUT_DIR/sphere.glb with sphere_glossy.prtg (isotropic Ward, α 0.2, ρ_s 0.5 over a
// reddish ρ_d) and sphere_lambert.prtg (Lambert, the same ρ_d, through the glossy path), and
// OUT_DIR/plate.glb (8 × 8, facing +Y, tangent +X) with plate_brushed_x.prtg (anisotropic Ward
// α_x 0.45 along the tangent, α_y 0.06) and plate_brushed_z.prtg (the two swapped): shadowed
// glossy transfer, ORDER (default 8), 512 samples per vertex (256 for the plate). Then prints the
// single-thread shading rate of each file's vertices at its order (isotropic table vs matrix), in
// thread CPU time. Files already in OUT_DIR are read instead of baked again.
#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "bake/glossy_transfer_baker.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/glossy/relighter.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"

namespace {

// Thread CPU time in seconds (the machine may be shared: wall time would count the others).
double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

prt::GlossyTransferData bake_file(const std::string& scene_path, const prt::brdf::Material& m,
                                  int order, const std::string& out, int samples = 512) {
  if (std::filesystem::exists(out)) {  // made by an earlier run: time the shading only
    prt::Result<prt::GlossyTransferData> read = prt::read_glossy_transfer_file(out);
    if (read.ok()) return std::move(read).value();
  }
  prt::scene::Scene scene = prt::scene::load_scene(scene_path);
  for (auto& primitive : scene.primitives) primitive.brdf = m;
  prt::bake::GlossyBakeOptions options;
  options.order = order;
  options.samples = samples;
  const auto start = std::chrono::steady_clock::now();
  prt::bake::GlossyBakeResult r = prt::bake::bake_glossy_transfer(scene, options);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const prt::Status s = prt::write_glossy_transfer_file(out, r.data);
  std::printf("%s: %s, %zu vertices, order %d, baked in %.2f s%s%s\n", out.c_str(),
              prt::brdf::describe(m).c_str(), std::size_t(r.data.vertex_count), order, seconds,
              s.ok() ? "" : ": ", s.ok() ? "" : s.message().c_str());
  return std::move(r.data);
}

void time_shading(const prt::GlossyTransferData& data, prt::BrdfProjectionMethod method,
                  const char* name) {
  prt::BrdfProjectionOptions options;
  options.method = method;
  double start = cpu_seconds();
  auto relighter = prt::GlossyRelighter::create(data, options);
  const double build = cpu_seconds() - start;
  if (!relighter.ok()) {
    std::printf("  %s: %s\n", name, relighter.status().message().c_str());
    return;
  }
  const int order = int(data.order);
  std::vector<double> coefficients(3 * std::size_t(order) * order, 0.1);
  auto light = prt::ShLighting::from_coefficients(order, coefficients.data());
  std::vector<float> out(3 * data.vertex_count);
  const float eye[3] = {0.3f, 2.f, 4.f};
  int repeats = 0;
  start = cpu_seconds();
  double seconds = 0;
  while (seconds < 1.0) {
    (void)relighter->shade(*light, eye, 0, data.vertex_count, out.data());
    ++repeats;
    seconds = cpu_seconds() - start;
  }
  const double per_frame = seconds / repeats;
  std::printf(
      "  %-15s order %2d: relighter built in %.3f CPU-s; %zu vertices in %.2f CPU-ms "
      "(%.2f M vertices/s, one thread)\n",
      name, order, build, std::size_t(data.vertex_count), 1e3 * per_frame,
      double(data.vertex_count) / per_frame * 1e-6);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: glossy_demo_files OUT_DIR [ORDER]\n");
    return 2;
  }
  const std::string dir = argv[1];
  const int order = argc > 2 ? std::atoi(argv[2]) : 8;
  const std::string sphere = dir + "/sphere.glb", plate = dir + "/plate.glb";
  prt::scene::write_glb(sphere, prt::scene::make_uv_sphere({0, 0, 0}, 1.f, 64, 128, false,
                                                           glm::vec3(0.5f), "sphere"));
  prt::scene::write_glb(plate, prt::scene::make_quad({-4.f, 0, 4.f}, {8, 0, 0}, {0, 0, -8}, 128,
                                                     128, glm::vec3(0.5f), "plate"));
  prt::brdf::Material glossy;
  glossy.model = prt::brdf::MaterialModel::kWard;
  glossy.diffuse = {0.25, 0.06, 0.04};
  glossy.specular = prt::brdf::grey(0.5);
  glossy.alpha_x = glossy.alpha_y = 0.2;
  prt::brdf::Material lambert;
  lambert.diffuse = glossy.diffuse;
  prt::brdf::Material brushed = glossy;
  brushed.diffuse = prt::brdf::grey(0.05);
  brushed.specular = {0.9, 0.8, 0.6};
  brushed.alpha_x = 0.45;
  brushed.alpha_y = 0.06;
  using M = prt::BrdfProjectionMethod;
  const auto g = bake_file(sphere, glossy, order, dir + "/sphere_glossy.prtg");
  const auto l = bake_file(sphere, lambert, order, dir + "/sphere_lambert.prtg");
  const auto b = bake_file(plate, brushed, order, dir + "/plate_brushed_x.prtg", 256);
  std::swap(brushed.alpha_x, brushed.alpha_y);
  bake_file(plate, brushed, order, dir + "/plate_brushed_z.prtg", 256);
  time_shading(l, M::kAuto, "lambert zonal");
  time_shading(g, M::kIsotropicTable, "ward table");
  time_shading(g, M::kZonal, "ward zonal");
  time_shading(g, M::kMatrix, "ward matrix");
  time_shading(b, M::kMatrix, "brushed matrix");
  return 0;
}
