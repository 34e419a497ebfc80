// `prt compress` (glossy transfer → CPCA file) and `prt relight` / `prt info` with the .prtq:
// the compressed file relights like the file it came from (exactly at full rank), and bad input
// is refused with one line and nothing written.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/cpca/compressor.h"
#include "bake/glossy_transfer_baker.h"
#include "cli_test_support.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/glossy_transfer_file.h"
#include "relight/image_io.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"
#include "scene/scene_loader.h"

using namespace prt::test::cli;

namespace {

struct SphereFiles {
  fs::path scene, glossy, env;
};

// A UV sphere with a GGX material, shadowed glossy
// transfer of `order` (the sphere shadows nothing, but its matrices still differ per vertex by
// the frame rotation), and a sky with a small bright sun.
SphereFiles make_sphere(const fs::path& dir, int order) {
  SphereFiles f{dir / "sphere.glb", dir / "sphere.prtg", dir / "sun.exr"};
  prt::scene::write_glb(f.scene.string(),
                        prt::scene::make_uv_sphere({0, 0, 0}, 1.f, 12, 24, false, glm::vec3(0.5f)));
  prt::scene::Scene scene = prt::scene::load_scene(f.scene.string());
  prt::brdf::Material ggx;
  ggx.model = prt::brdf::MaterialModel::kMicrofacet;
  ggx.diffuse = {0.3, 0.2, 0.1};
  ggx.specular = prt::brdf::grey(0.04);
  ggx.alpha_x = ggx.alpha_y = 0.3;
  for (auto& primitive : scene.primitives) primitive.brdf = ggx;
  prt::bake::GlossyBakeOptions options;
  options.order = order;
  options.samples = 32;
  const prt::bake::GlossyBakeResult baked = prt::bake::bake_glossy_transfer(scene, options);
  REQUIRE(prt::write_glossy_transfer_file(f.glossy.string(), baked.data).ok());
  const int w = 64, h = 32;
  std::vector<float> pixels(3 * w * h, 0.1f);
  for (int r = 9; r < 12; ++r)
    for (int c = 7; c < 10; ++c)
      for (int k = 0; k < 3; ++k) pixels[3 * (r * w + c) + k] = 200.f;
  prt::relight::write_image(f.env.string(), w, h, 3, pixels.data());
  return f;
}

// The r, g, b columns of a `prt relight --csv` file.
std::vector<double> csv_radiance(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);  // header: index,x,y,z,r,g,b
  std::vector<double> out;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    for (int column = 0; std::getline(row, cell, ','); ++column)
      if (column >= 4) out.push_back(std::stod(cell));
  }
  return out;
}

std::string relight_csv(const SphereFiles& f, const fs::path& transfer, const fs::path& csv) {
  return prt_cli() + " relight " + f.scene.string() + " " + transfer.string() + " " +
         f.env.string() + " -o " + (csv.parent_path() / (csv.stem().string() + ".png")).string() +
         " --size 48x36 --spp 1 --quiet --window none --csv " + csv.string() + " --eye 0.5,1.5,4";
}

double relative_rms(const std::vector<double>& a, const std::vector<double>& b) {
  double d2 = 0, r2 = 0;
  for (std::size_t i = 0; i < a.size(); ++i) d2 += (a[i] - b[i]) * (a[i] - b[i]), r2 += b[i] * b[i];
  return std::sqrt(d2 / r2);
}

}  // namespace

TEST_CASE("cli: prt compress at full rank relights like the glossy file it came from") {
  // Order 2: D = 16 entries per matrix, --vectors 16 spans every cluster, so the .prtq holds M to
  // float rounding and its relight (CpcaKernel) must equal the .prtg's (GlossyKernel) to float
  // rounding: relative RMS 1e-5 (measured ~1e-7). A wrong frame, material or cluster id of the
  // source section would give errors of order 1.
  const fs::path dir = scratch("cpca_full_rank");
  const SphereFiles f = make_sphere(dir, 2);
  const fs::path q = dir / "sphere.prtq";
  RunResult c = run(prt_cli() + " compress " + f.glossy.string() + " -o " + q.string() +
                    " --clusters 4 --vectors 16 --threads 1");
  INFO(c.err);
  REQUIRE(c.exit_code == 0);
  CHECK(c.out.find("4 clusters x 16 vectors") != std::string::npos);
  RunResult a = run(relight_csv(f, f.glossy, dir / "g.csv"));
  RunResult b = run(relight_csv(f, q, dir / "q.csv"));
  INFO(a.err << b.err);
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  const std::vector<double> eg = csv_radiance(dir / "g.csv"), eq = csv_radiance(dir / "q.csv");
  REQUIRE(eg.size() == eq.size());
  REQUIRE(eg.size() > 300);
  CHECK(relative_rms(eq, eg) < 1e-5);
  RunResult info = run(prt_cli() + " info " + q.string());
  REQUIRE(info.exit_code == 0);
  CHECK(info.out.find("glossy CPCA") != std::string::npos);
  CHECK(info.out.find("geometry, frames and materials included") != std::string::npos);
}

TEST_CASE("cli: a lossy .prtq relights images, turntables and CSVs close to the .prtg") {
  // Order 4 with 2 vectors per cluster: lossy (matrix error 0.56). The relit relative RMS must
  // be below the matrix error that prt compress reports — an empirical relation, not a bound:
  // the BRDF and the lighting filter what CPCA drops (here 0.25 against 0.56; docs/GLOSSY_CPCA.md
  // measures 2-6x on real bakes) — and not zero (the .prtq is really used). The rigorous
  // per-vertex bound is tested in tests/prt/glossy/test_glossy_relighter_paths.cpp.
  const fs::path dir = scratch("cpca_lossy");
  const SphereFiles f = make_sphere(dir, 4);
  const fs::path q = dir / "sphere.prtq";
  RunResult c = run(prt_cli() + " compress " + f.glossy.string() + " -o " + q.string() +
                    " --clusters 4 --vectors 2");
  REQUIRE(c.exit_code == 0);
  const std::string key = "relative RMS matrix error ";
  const std::size_t at = c.out.find(key);
  REQUIRE(at != std::string::npos);
  const double matrix_error = std::stod(c.out.substr(at + key.size()));
  RunResult a = run(relight_csv(f, f.glossy, dir / "g.csv"));
  RunResult b = run(relight_csv(f, q, dir / "q.csv"));
  REQUIRE(a.exit_code == 0);
  REQUIRE(b.exit_code == 0);
  const double relit = relative_rms(csv_radiance(dir / "q.csv"), csv_radiance(dir / "g.csv"));
  INFO("matrix error " << matrix_error << ", relit error " << relit);
  CHECK(relit > 1e-6);
  CHECK(relit < matrix_error);
  RunResult t =
      run(prt_cli() + " relight " + f.scene.string() + " " + q.string() + " " + f.env.string() +
          " -o " + (dir / "t.png").string() + " --size 48x36 --spp 1 --quiet --turntable 3");
  INFO(t.err);
  REQUIRE(t.exit_code == 0);
  for (const char* frame : {"t_000.png", "t_001.png", "t_002.png"}) CHECK(fs::exists(dir / frame));
}

TEST_CASE("cli: prt compress minimises the relit metric by default, the matrix error on request") {
  // The same lossy setting twice: --metric relit (the default) and --metric matrix. Each must
  // minimise what it says: the plain matrix error is lower with --metric matrix, and each run
  // names the error it reports. That the relit metric lowers the EXPECTED relit error (over
  // views and lightings) is tested in tests/bake/test_cpca_relit_metric.cpp; one eye under one sky
  // is a single sample of it (measured: 0.28 against 0.26 relit CSV error, with 2 vectors for 4
  // clusters, so either may win at a single view). The compressor is k-means with a seeded
  // start, a local search: at one seed the relit run may land on a clustering whose matrix error
  // is lower by chance (seed 1 of this sphere: 0.5647 against 0.5687), so the matrix errors are
  // summed over five seeds, where the metric's own choice wins clearly.
  const fs::path dir = scratch("cpca_metric");
  const SphereFiles f = make_sphere(dir, 4);
  double matrix[2] = {0, 0};
  const char* metrics[2] = {"", " --metric matrix"};
  for (int i = 0; i < 2; ++i) {
    for (int seed = 1; seed <= 5; ++seed) {
      const fs::path q = dir / ((i == 0 ? "relit" : "matrix") + std::to_string(seed) + ".prtq");
      RunResult c = run(prt_cli() + " compress " + f.glossy.string() + " -o " + q.string() +
                        " --clusters 4 --vectors 2 --seed " + std::to_string(seed) + metrics[i]);
      INFO(c.err);
      REQUIRE(c.exit_code == 0);
      const std::string key = "relative RMS matrix error ";
      const std::size_t at = c.out.find(key);
      REQUIRE(at != std::string::npos);
      matrix[i] += std::stod(c.out.substr(at + key.size()));
      CHECK(c.out.find(i == 0 ? "relit-metric error" : ", matrix error") != std::string::npos);
    }
  }
  INFO("matrix error summed over 5 seeds: metric relit " << matrix[0] << ", metric matrix "
                                                         << matrix[1]);
  CHECK(matrix[1] < matrix[0]);
  RunResult bad = run(prt_cli() + " compress " + f.glossy.string() + " -o " +
                      (dir / "x.prtq").string() + " --metric pixels");
  CHECK(bad.exit_code != 0);
  CHECK_FALSE(fs::exists(dir / "x.prtq"));
}

TEST_CASE("cli: prt compress and prt relight refuse bad CPCA input with one line") {
  const fs::path dir = scratch("cpca_refusals");
  const SphereFiles f = make_sphere(dir, 2);
  const fs::path out = dir / "out" / "x.prtq";
  fs::create_directories(out.parent_path());
  auto nothing_written = [&] { CHECK(files_in(out.parent_path()).empty()); };
  // Not a glossy transfer file.
  require_one_line_error(run(prt_cli() + " compress " + f.env.string() + " -o " + out.string()),
                         f.env.string());
  nothing_written();
  // The output is the input (under a .prtq name): never overwritten.
  const fs::path renamed = dir / "in.prtq";
  fs::copy_file(f.glossy, renamed);
  const std::string before = slurp(renamed);
  RunResult same = run(prt_cli() + " compress " + renamed.string() + " -o " + renamed.string());
  require_one_line_error(same, "overwrites an input");
  CHECK(slurp(renamed) == before);
  // A wrong extension, conflicting or out-of-range options.
  require_one_line_error(run(prt_cli() + " compress " + f.glossy.string() + " -o " +
                             (dir / "out" / "x.prtg").string()),
                         ".prtq");
  require_one_line_error(run(prt_cli() + " compress " + f.glossy.string() + " -o " + out.string() +
                             " --vectors 4 --target-error 0.01"),
                         "--target-error");
  require_one_line_error(
      run(prt_cli() + " compress " + f.glossy.string() + " -o " + out.string() + " --clusters 0"),
      "--clusters");
  // A target the allowed vectors cannot reach: an error naming the file, nothing written.
  RunResult unreachable = run(prt_cli() + " compress " + f.glossy.string() + " -o " + out.string() +
                              " --clusters 1 --target-error 1e-9 --max-vectors 1");
  require_one_line_error(unreachable, f.glossy.string());
  nothing_written();
  // A .prtq without its source section cannot be relit; nor one of another mesh.
  auto glossy = prt::read_glossy_transfer_file(f.glossy.string());
  REQUIRE(glossy.ok());
  prt::CpcaOptions o;
  o.clusters = 2;
  o.vectors = 2;
  auto cpca = prt::cpca_compress(*glossy, o);
  REQUIRE(cpca.ok());
  const fs::path bare = dir / "bare.prtq";
  REQUIRE(prt::write_cpca_file(bare.string(), *cpca).ok());
  const fs::path image = dir / "out" / "r.png";
  require_one_line_error(run(prt_cli() + " relight " + f.scene.string() + " " + bare.string() +
                             " " + f.env.string() + " -o " + image.string()),
                         "source section");
  nothing_written();
  const fs::path other_scene = dir / "other.glb";
  prt::scene::write_glb(other_scene.string(),
                        prt::scene::make_uv_sphere({0, 0, 0}, 2.f, 12, 24, false, glm::vec3(0.5f)));
  const fs::path good = dir / "good.prtq";
  REQUIRE(prt::write_cpca_file(good.string(), *cpca, *glossy).ok());
  RunResult mismatch = run(prt_cli() + " relight " + other_scene.string() + " " + good.string() +
                           " " + f.env.string() + " -o " + image.string());
  require_one_line_error(mismatch, good.string());
  nothing_written();
  // --csv without --eye is refused for a .prtq as for a .prtg.
  require_one_line_error(
      run(prt_cli() + " relight " + f.scene.string() + " " + good.string() + " " + f.env.string() +
          " -o " + image.string() + " --csv " + (dir / "out" / "v.csv").string()),
      "--eye");
  nothing_written();
}

namespace {

// The rows of a `prt info --csv` file, as numbers (the header row apart).
std::vector<std::vector<double>> csv_rows(const std::string& text, std::string* header) {
  std::stringstream in(text);
  std::getline(in, *header);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::string cell;
    rows.emplace_back();
    while (std::getline(row, cell, ',')) rows.back().push_back(std::stod(cell));
  }
  return rows;
}

}  // namespace

TEST_CASE("cli: prt info of a .prtq states its error, metric and the source bake's settings") {
  const fs::path dir = scratch("cpca_info");
  const SphereFiles f = make_sphere(dir, 3);
  const fs::path q = dir / "sphere.prtq";
  RunResult c = run(prt_cli() + " compress " + f.glossy.string() + " -o " + q.string() +
                    " --clusters 4 --vectors 3 --seed 7");
  REQUIRE(c.exit_code == 0);
  const std::string key = "relit-metric error ";
  REQUIRE(c.out.find(key) != std::string::npos);
  const double reported = std::stod(c.out.substr(c.out.find(key) + key.size()));
  RunResult info = run(prt_cli() + " info " + q.string());
  INFO(info.out << info.err);
  REQUIRE(info.exit_code == 0);
  CHECK(info.out.find("in the relit metric (what it minimised)") != std::string::npos);
  CHECK(info.out.find("--clusters 4 --vectors 3") != std::string::npos);
  CHECK(info.out.find("seed 7") != std::string::npos);
  // The bake's settings (make_sphere bakes 32 samples per vertex at order 3, shadowed).
  CHECK(info.out.find("glossy shadowed, order 3, 32 samples per vertex") != std::string::npos);
  CHECK(info.out.find("(sphere.prtg)") != std::string::npos);
  RunResult json = run(prt_cli() + " info " + q.string() + " --json");
  REQUIRE(json.exit_code == 0);
  const nlohmann::json j = nlohmann::json::parse(json.out);
  CHECK(j["format_version"] == prt::kCpcaFileVersion);
  CHECK(j["compression"]["metric"] == "relit");
  // The stored error is the one compress printed (to its 4 printed digits).
  CHECK(j["compression"]["metric_relative_rms_error"].get<double>() ==
        Approx(reported).epsilon(1e-3));
  CHECK(j["source_bake"]["samples_per_vertex"] == 32);
}

TEST_CASE("cli: prt info --csv reads a .prtq: the .prtg's rows with the matrices reconstructed") {
  // Order 2 at full rank (D = 16, 16 vectors): the reconstructed matrices equal the .prtg's to
  // float rounding (1e-5 absolute on entries of order 0.1-1); geometry and frames are copied.
  const fs::path dir = scratch("cpca_info_csv");
  const SphereFiles f = make_sphere(dir, 2);
  const fs::path q = dir / "sphere.prtq";
  REQUIRE(run(prt_cli() + " compress " + f.glossy.string() + " -o " + q.string() +
              " --clusters 4 --vectors 16 --quiet")
              .exit_code == 0);
  RunResult g = run(prt_cli() + " info --csv " + f.glossy.string());
  RunResult c = run(prt_cli() + " info --csv " + q.string());
  INFO(c.err);
  REQUIRE(g.exit_code == 0);
  REQUIRE(c.exit_code == 0);
  std::string gh, ch;
  const auto gr = csv_rows(g.out, &gh), cr = csv_rows(c.out, &ch);
  CHECK(ch.rfind("index,x,y,z,nx,ny,nz,tx,ty,tz,tw,material,cluster,m0_0_0,", 0) == 0);
  REQUIRE(gr.size() == cr.size());
  REQUIRE(gr.size() > 100);
  double worst = 0;
  for (std::size_t v = 0; v < gr.size(); ++v) {
    REQUIRE(cr[v].size() == gr[v].size() + 1);  // + cluster
    for (std::size_t k = 0; k < 12; ++k) CHECK(cr[v][k] == gr[v][k]);
    CHECK(cr[v][12] >= 0);
    CHECK(cr[v][12] < 4);
    for (std::size_t k = 12; k < gr[v].size(); ++k)
      worst = std::max(worst, std::fabs(cr[v][k + 1] - gr[v][k]));
  }
  CHECK(worst < 1e-5);
}
