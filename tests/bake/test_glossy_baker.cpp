// The glossy transfer-matrix bake (bake/glossy_transfer_baker.h): the unoccluded matrix against
// the SH rotation restricted to the hemisphere, Lambert through the glossy path against the
// diffuse bake (shadowed and interreflected), thread-count independence, the BRDF projection
// against the directional albedo, and the file written by the bake read back.
#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/glossy_transfer_baker.h"
#include "bake/transfer_baker.h"
#include "numerics/constants.h"
#include "prt/brdf/blinn_phong.h"
#include "prt/core/memory_budget.h"
#include "prt/formats/glossy_transfer_file.h"
#include "prt/glossy/brdf_projection.h"
#include "scene/procedural_mesh.h"
#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/zonal.h"
#include "support/test_data.h"

using prt::bake::bake_glossy_transfer;
using prt::bake::GlossyBakeOptions;

namespace {

using prt::numerics::kPi;

// Hemisphere Gram matrix H_ik = ∫_{z>0} y_i y_k dω by the midpoint rule on (z, φ): the integrand
// is a polynomial in z times trigonometric terms of degree < 2n in φ, so 64 azimuths are exact
// and 4000 heights leave an O(1e-7) error.
std::vector<double> hemisphere_gram(int order) {
  const int K = order * order, nz = 4000, nphi = 64;
  std::vector<double> h(std::size_t(K) * K, 0.0), y(static_cast<std::size_t>(K));
  const double w = (1.0 / nz) * (2.0 * kPi / nphi);
  for (int a = 0; a < nz; ++a) {
    const double z = (a + 0.5) / nz, r = std::sqrt(1.0 - z * z);
    for (int b = 0; b < nphi; ++b) {
      const double phi = 2.0 * kPi * (b + 0.5) / nphi;
      prt::sh::evaluate(order, r * std::cos(phi), r * std::sin(phi), z, y.data());
      for (int i = 0; i < K; ++i)
        for (int k = 0; k < K; ++k) h[i * K + k] += w * y[i] * y[k];
    }
  }
  return h;
}

// The local frame of vertex v of a glossy file: F = [t b n] (columns), world = F · local.
std::array<double, 9> frame_transposed(const prt::GlossyTransferData& d, std::size_t v) {
  const float* n = &d.normals[3 * v];
  const float* t = &d.tangents[4 * v];
  const double w = t[3];
  const double b[3] = {w * (n[1] * t[2] - n[2] * t[1]), w * (n[2] * t[0] - n[0] * t[2]),
                       w * (n[0] * t[1] - n[1] * t[0])};
  // Fᵀ row-major: row 0 = t, row 1 = b, row 2 = n.
  return {t[0], t[1], t[2], b[0], b[1], b[2], n[0], n[1], n[2]};
}

// The exact unoccluded matrix: M_ij = ∫_{H+} y_i(ω) y_j(Fω) dω = Σ_k H_ik D_jk, with
// y_j(Fω) = Σ_k D_jk y_k(ω), D_jk = [Rotation(Fᵀ) e_j]_k (sh/rotation.h: coefficients of
// f(Fω) from those of f).
std::vector<double> exact_unoccluded(int order, const std::array<double, 9>& ft,
                                     const std::vector<double>& gram) {
  const int K = order * order;
  const prt::sh::Rotation rot(order, ft);
  std::vector<double> d(std::size_t(K) * K), e(static_cast<std::size_t>(K)),
      out(static_cast<std::size_t>(K));
  for (int j = 0; j < K; ++j) {
    std::fill(e.begin(), e.end(), 0.0);
    e[j] = 1.0;
    rot.apply(e.data(), out.data());
    for (int k = 0; k < K; ++k) d[j * K + k] = out[k];
  }
  std::vector<double> m(std::size_t(K) * K, 0.0);
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < K; ++j)
      for (int k = 0; k < K; ++k) m[i * K + j] += gram[i * K + k] * d[j * K + k];
  return m;
}

// (ρ/π) · Σ_l z_l · M_c[(l,0), :]: the diffuse exit transfer a Lambert vertex gets through b.
std::vector<double> lambert_row(const prt::GlossyTransferData& d, std::size_t v, int c,
                                double rho) {
  const int n = static_cast<int>(d.order), K = n * n;
  std::vector<double> t(static_cast<std::size_t>(K), 0.0);
  for (int l = 0; l < n; ++l) {
    const double z = rho / kPi * prt::sh::clamped_cosine_zonal_coefficient(l);
    for (int j = 0; j < K; ++j)
      t[j] +=
          z * d.matrices[prt::glossy_matrix_index(v, c, prt::sh::index(l, 0), j, d.channels, K)];
  }
  return t;
}

// ‖cos⁺ − its order-n projection‖₂ = √(2π/3 − Σ_l z_l²): by Cauchy–Schwarz (‖V·y_j‖₂ ≤ 1) the
// most the truncated clamped cosine of the glossy path can differ from the diffuse bake's exact
// cosine, per coefficient, before the factor ρ/π.
double cosine_truncation(int order) {
  double s = 2.0 * kPi / 3.0;
  for (int l = 0; l < order; ++l) s -= std::pow(prt::sh::clamped_cosine_zonal_coefficient(l), 2);
  return std::sqrt(std::max(s, 0.0));
}

// A floor with a box standing on it: shadowed and unshadowed vertices, sharp edges.
prt::scene::Scene floor_and_box(glm::vec3 albedo) {
  prt::scene::Scene s = prt::scene::make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f},
                                              6, 6, albedo, "floor");
  prt::scene::append_scene(
      s, prt::scene::make_box({-0.5f, 0.f, -0.5f}, {0.5f, 1.f, 0.5f}, 2, false, albedo, "box"));
  return s;
}

// The Blinn-Phong material of the glossy cases: diffuse 0.3, specular 0.4, exponent 20.
prt::brdf::Material test_phong() {
  prt::brdf::Material phong;
  phong.model = prt::brdf::MaterialModel::kBlinnPhong;
  phong.diffuse = prt::brdf::grey(0.3);
  phong.specular = prt::brdf::grey(0.4);
  phong.exponent = 20;
  return phong;
}

// floor_and_box of albedo (0.7, 0.5, 0.3), the box Blinn-Phong (test_phong).
prt::scene::Scene phong_floor_and_box() {
  prt::scene::Scene s = floor_and_box(glm::vec3(0.7f, 0.5f, 0.3f));
  s.primitives[1].brdf = test_phong();
  return s;
}

// Two bounces at order 3 with `samples` directions a vertex, the rest default.
GlossyBakeOptions two_bounces(int samples) {
  GlossyBakeOptions o;
  o.order = 3;
  o.samples = samples;
  o.bounces = 2;
  return o;
}

}  // namespace

TEST_CASE("glossy bake: an unoccluded vertex's matrix is the SH rotation on the hemisphere",
          "[glossy_bake]") {
  // A tilted quad: normal not on an axis, file tangents along an edge, so F is a generic
  // rotation; nothing occludes the upper hemisphere of any vertex.
  prt::scene::Scene s = prt::scene::make_quad({0.f, 0.f, 0.f}, {1.f, 0.3f, 0.2f},
                                              {-0.2f, 0.5f, 1.f}, 1, 1, glm::vec3(0.5f));
  const glm::vec3 e = glm::normalize(glm::vec3(1.f, 0.3f, 0.2f));
  s.tangents.assign(s.positions.size(),
                    glm::vec4(e - glm::dot(e, s.normals[0]) * s.normals[0], -1.f));
  for (glm::vec4& t : s.tangents) t = glm::vec4(glm::normalize(glm::vec3(t)), -1.f);
  GlossyBakeOptions o;
  o.order = 4;
  o.samples = 4096;
  const auto r = bake_glossy_transfer(s, o);
  const int K = 16;
  const std::vector<double> gram = hemisphere_gram(o.order);
  double worst = 0.0, worst_if_unrotated = 0.0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const auto exact = exact_unoccluded(o.order, frame_transposed(r.data, v), gram);
    for (int i = 0; i < K; ++i)
      for (int j = 0; j < K; ++j) {
        const double m = r.data.matrices[prt::glossy_matrix_index(v, 0, i, j, 1, K)];
        worst = std::max(worst, std::fabs(m - exact[i * K + j]));
        worst_if_unrotated = std::max(worst_if_unrotated, std::fabs(m - gram[i * K + j]));
      }
  }
  // 4096 scrambled-Sobol samples of a smooth integrand (|y_i y_j| ≤ ~3): measured 2.2e-4 at
  // most; the bound 2e-3 is far below what a wrong frame would give (the unrotated Gram matrix
  // differs by 0.72).
  INFO("max |M - exact| = " << worst << ", against the unrotated Gram " << worst_if_unrotated);
  CHECK(worst < 2e-3);
  CHECK(worst_if_unrotated > 0.1);
  CHECK(r.data.channels == 1);
  CHECK_FALSE(r.data.interreflected);
  CHECK(r.stats.rays == 4u * 4096u);
}

TEST_CASE("glossy bake: Lambert through the glossy path equals the shadowed diffuse transfer",
          "[glossy_bake]") {
  const double rho = 0.5;
  const prt::scene::Scene s = floor_and_box(glm::vec3(float(rho)));
  const int order = 5, K = 25;
  prt::bake::BakeOptions d;
  d.kind = prt::TransferKind::Shadowed;
  d.order = order;
  d.samples = 2048;
  const auto diffuse = prt::bake::bake_transfer(s, d);
  GlossyBakeOptions o;
  o.order = order;
  o.samples = 2048;
  const auto glossy = bake_glossy_transfer(s, o);
  // Bound: the clamped cosine truncated at order n (ρ/π · its L2 residual, Cauchy–Schwarz) plus
  // the MC error of both bakes at 2048 samples (4e-3; measured: 1.9e-3 over all vertices,
  // 9e-4 far from the box).
  const double bound = rho / kPi * cosine_truncation(order) + 4e-3;
  double worst = 0.0, worst_open = 0.0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const auto t = lambert_row(glossy.data, v, 0, rho);
    double err = 0.0;
    for (int j = 0; j < K; ++j)
      err = std::max(err, std::fabs(t[j] - diffuse.data.coefficients[v * K + j]));
    worst = std::max(worst, err);
    if (s.positions[v].y == 0.f && std::fabs(s.positions[v].x) > 1.5f)
      worst_open = std::max(worst_open, err);  // far from the box: nearly unoccluded
  }
  INFO("max |Lambert·M − T| = " << worst << " (bound " << bound << "), far vertices "
                                << worst_open);
  CHECK(worst < bound);
  // Where nothing (or little) occludes, V·y_j is band-limited and the two agree to MC noise.
  CHECK(worst_open < 5e-3);
}

TEST_CASE("glossy bake: Lambert interreflection equals the diffuse interreflected transfer",
          "[glossy_bake]") {
  const double rho = 0.6;
  const prt::scene::Scene s =
      prt::scene::make_spherical_cavity(1.f, 1.0f, 6, 12, glm::vec3(float(rho)));
  const int order = 4, K = 16;
  prt::bake::BakeOptions d;
  d.kind = prt::TransferKind::Interreflected;
  d.order = order;
  d.samples = 1024;
  d.bounces = -1;
  const auto diffuse = prt::bake::bake_transfer(s, d);
  GlossyBakeOptions o;
  o.order = order;
  o.samples = 1024;
  o.bounces = -1;
  const auto glossy = bake_glossy_transfer(s, o);
  REQUIRE(glossy.stats.converged);
  REQUIRE(glossy.data.interreflected);
  // And the direct part alone, to show the bounces matter here.
  GlossyBakeOptions o0 = o;
  o0.bounces = 0;
  const auto shadowed = bake_glossy_transfer(s, o0);
  double worst = 0.0, bounce_part = 0.0, scale = 0.0;
  for (std::size_t v = 0; v < s.positions.size(); ++v) {
    const auto t = lambert_row(glossy.data, v, 0, rho);
    const auto t0 = lambert_row(shadowed.data, v, 0, rho);
    for (int j = 0; j < K; ++j) {
      worst = std::max(worst, std::fabs(t[j] - diffuse.data.coefficients[v * K + j]));
      bounce_part = std::max(bounce_part, std::fabs(t[j] - t0[j]));
      scale = std::max(scale, double(std::fabs(diffuse.data.coefficients[v * K + j])));
    }
  }
  // Bound: the truncation bound of the shadowed case amplified by the bounces (1/(1 − ρ)), plus
  // MC noise. That bound is loose (Cauchy–Schwarz); the measured difference (4.6e-3) is also
  // checked against the interreflected part itself (3.8e-2), so a bounce that is missing, doubled
  // or gathered from the wrong rows fails.
  const double bound = rho / kPi * cosine_truncation(order) / (1.0 - rho) + 5e-3;
  INFO("max |Lambert·M − T| = " << worst << " (bound " << bound << "), bounce part " << bounce_part
                                << ", max |T| " << scale);
  CHECK(worst < bound);
  CHECK(worst < 0.25 * bounce_part);
}

TEST_CASE("glossy bake: bit-identical for any thread count, seed-dependent", "[glossy_bake]") {
  prt::scene::Scene s = phong_floor_and_box();
  GlossyBakeOptions o = two_bounces(64);
  o.threads = 1;
  const auto one = bake_glossy_transfer(s, o);
  o.threads = 2;
  const auto two = bake_glossy_transfer(s, o);
  CHECK(one.data.channels == 3);
  CHECK(one.stats.hits > 0);
  CHECK(one.data.matrices == two.data.matrices);
  o.seed = 2;
  const auto other = bake_glossy_transfer(s, o);
  CHECK(other.data.matrices != one.data.matrices);
  // The materials: floor Lambert with its albedo, box Blinn-Phong.
  REQUIRE(one.data.materials.size() == 2);
  CHECK(one.data.materials[0].lambertian());
  CHECK(one.data.materials[1].model == prt::brdf::MaterialModel::kBlinnPhong);
  CHECK(one.data.material_of_vertex.back() == 1);
  // The file round trip of a bake.
  const auto path = prt::test::output_path("glossy_bake.prtg").string();
  REQUIRE(prt::write_glossy_transfer_file(path, one.data).ok());
  const auto back = prt::read_glossy_transfer_file(path);
  REQUIRE(back.ok());
  CHECK(back.value().matrices == one.data.matrices);
}

TEST_CASE("glossy bake: the BRDF projection's b_0 is the directional albedo over sqrt(4 pi)",
          "[glossy_bake]") {
  prt::brdf::Material m;
  m.model = prt::brdf::MaterialModel::kBlinnPhong;
  m.diffuse = prt::brdf::grey(0.2);
  m.specular = {0.6, 0.4, 0.2};
  m.exponent = 30;
  // The projection the bake's bounces use: the runtime's, with the bake's default options.
  const auto made = prt::BrdfProjection::create(m, 3, prt::bake::GlossyBakeOptions{}.projection);
  REQUIRE(made.ok());
  const prt::BrdfProjection& proj = made.value();
  const auto brdf = prt::brdf::make_brdf(m);
  REQUIRE(brdf.ok());
  std::vector<float> b(27), scratch(proj.scratch_floats() + 1);
  // Node and off-node directions (the latter read by interpolation).
  for (const glm::vec3 wo : {glm::vec3(0.f, 0.f, 1.f), glm::normalize(glm::vec3(0.6f, 0.3f, 0.7f)),
                             glm::normalize(glm::vec3(-0.9f, 0.2f, 0.3f))}) {
    const float w[3] = {wo.x, wo.y, wo.z};
    proj.evaluate(w, b.data(), scratch.data());
    const prt::brdf::Rgb a = prt::brdf::directional_albedo(*brdf.value(), {wo.x, wo.y, wo.z}, 128);
    const double s = std::sqrt(4.0 * kPi);
    // Quadrature at 1° elevation nodes, linear interpolation between them: within 3% of the
    // albedo (the bound the bake's former sampled table met too).
    CHECK(b[0] * s == Approx(a.r).epsilon(0.03));
    CHECK(b[9] * s == Approx(a.g).epsilon(0.03));
    CHECK(b[18] * s == Approx(a.b).epsilon(0.03));
  }
  const float below[3] = {0.f, 0.f, -1.f};
  proj.evaluate(below, b.data(), scratch.data());
  CHECK(*std::max_element(b.begin(), b.end()) == 0.f);
}

// Converged means the last bounce reached the tolerance, whether the bounces were counted or
// solved for: in the spherical cavity (ρ 0.6, each bounce about 0.6 of the one before) one
// bounce is far from it, a solve reaches it.
TEST_CASE("glossy bake: converged only when the last bounce reached the tolerance",
          "[glossy_bake]") {
  const prt::scene::Scene s = prt::scene::make_spherical_cavity(1.f, 1.0f, 6, 12, glm::vec3(0.6f));
  GlossyBakeOptions o;
  o.order = 3;
  o.samples = 64;
  o.bounces = 1;
  const auto one = bake_glossy_transfer(s, o);
  REQUIRE(one.stats.bounce_change.size() == 1);
  CHECK(one.stats.bounce_change[0] > o.bounce_tolerance);
  CHECK_FALSE(one.stats.converged);
  CHECK(one.data.metadata_json.find("\"converged\":false") != std::string::npos);
  o.bounces = -1;
  const auto solved = bake_glossy_transfer(s, o);
  CHECK(solved.stats.converged);
  CHECK(solved.stats.bounce_change.back() <= o.bounce_tolerance);
  CHECK(solved.data.metadata_json.find("\"converged\":true") != std::string::npos);
  // Counted bounces that happen to reach the tolerance are converged too.
  o.bounces = solved.stats.bounces;
  CHECK(bake_glossy_transfer(s, o).stats.converged);
}

// A material that reflects 1.9x what arrives (set directly, past the loaders' furnace check)
// makes the bounces grow: the bake throws one line instead of returning them.
TEST_CASE("glossy bake: diverging bounces throw", "[glossy_bake]") {
  prt::scene::Scene s = prt::scene::make_spherical_cavity(1.f, 0.3f, 8, 16, glm::vec3(0.6f));
  prt::brdf::Material hot;
  hot.model = prt::brdf::MaterialModel::kMicrofacet;
  hot.fresnel = prt::brdf::FresnelMode::kSchlick;
  hot.alpha_x = hot.alpha_y = 0.81;
  hot.diffuse = prt::brdf::grey(0.95);
  hot.specular = prt::brdf::grey(0.95);
  for (auto& p : s.primitives) p.brdf = hot;
  GlossyBakeOptions o;
  o.order = 3;
  o.samples = 64;
  o.bounces = 40;
  try {
    const auto r = bake_glossy_transfer(s, o);
    std::string changes;
    for (double c : r.stats.bounce_change) changes += std::to_string(c) + " ";
    FAIL("no exception; bounce changes " << changes);
  } catch (const prt::bake::BakeError& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find("glossy interreflection diverges") != std::string::npos);
    CHECK(what.find('\n') == std::string::npos);
  }
}

namespace {

std::vector<unsigned char> file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<unsigned char>(std::istreambuf_iterator<char>(in), {});
}

bool temporaries_left(const std::string& path) {
  const std::filesystem::path p(path);
  for (const auto& e : std::filesystem::directory_iterator(p.parent_path()))
    if (e.path().filename().string().rfind(p.filename().string() + ".tmp-", 0) == 0) return true;
  return false;
}

// Bakes `s` with `o` to `path` and checks that o.memory_limit refuses it: one line naming
// `reason`, and neither the file nor a temporary left behind.
void check_refused_with_no_file(const prt::scene::Scene& s, const GlossyBakeOptions& o,
                                const std::string& path, const std::string& reason) {
  try {
    prt::bake::bake_glossy_transfer_to_file(s, o, path);
    FAIL("a limit of " << o.memory_limit << " bytes was accepted");
  } catch (const prt::MemoryBudgetExceeded& e) {
    const std::string what = e.what();
    INFO(what);
    CHECK(what.find('\n') == std::string::npos);
    CHECK(what.find(reason) != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_FALSE(temporaries_left(path));
}

// True when a streamed bake's scratch file (prt-glossy-scratch-*) is left in PATH's folder.
bool scratch_left(const std::string& path) {
  for (const auto& e :
       std::filesystem::directory_iterator(std::filesystem::path(path).parent_path()))
    if (e.path().filename().string().rfind("prt-glossy-scratch-", 0) == 0) return true;
  return false;
}

// At o.memory_limit the in-memory bake is over the limit and the streamed one to `path` runs
// within it, its file read back whole; returns the streamed bake's statistics.
prt::bake::GlossyBakeStatistics check_only_streamed_fits(const prt::scene::Scene& s,
                                                         const GlossyBakeOptions& o,
                                                         const std::string& path) {
  CHECK_THROWS_AS(bake_glossy_transfer(s, o), prt::MemoryBudgetExceeded);
  const auto r = prt::bake::bake_glossy_transfer_to_file(s, o, path);
  CHECK(r.stats.peak_charged_bytes < o.memory_limit);
  REQUIRE(prt::read_glossy_transfer_file(path).ok());
  return r.stats;
}

}  // namespace

// The streamed file against the in-memory bake written whole: every byte but the metadata's
// (its timings differ run to run), so the in-memory file is written with the streamed bake's
// metadata and the two files must then be identical.
TEST_CASE("glossy bake: the streamed file is byte-identical to the in-memory bake's",
          "[glossy_bake]") {
  prt::scene::Scene s = phong_floor_and_box();
  for (const int bounces : {0, 2}) {
    for (const int threads : {1, 2}) {
      GlossyBakeOptions o;
      o.order = bounces == 0 ? 5 : 3;
      o.samples = 64;
      o.bounces = bounces;
      o.threads = threads;
      o.precision = bounces == 0 ? prt::Precision::F32 : prt::Precision::F16;
      const std::string streamed = prt::test::output_path("glossy_streamed_bake.prtg").string();
      const std::string whole = prt::test::output_path("glossy_whole_bake.prtg").string();
      const auto st = prt::bake::bake_glossy_transfer_to_file(s, o, streamed);
      CHECK(st.data.matrices.empty());
      auto mem = bake_glossy_transfer(s, o);
      mem.data.metadata_json = st.data.metadata_json;
      REQUIRE(prt::write_glossy_transfer_file(whole, mem.data).ok());
      INFO("bounces " << bounces << ", threads " << threads);
      const auto a = file_bytes(streamed), b = file_bytes(whole);
      CHECK(a.size() > 50 * 1000);  // the matrices are there
      CHECK(a == b);
      CHECK_FALSE(temporaries_left(streamed));
    }
  }
}

// A limit below what the bake must hold stops it before the work, in one line, and leaves no
// file; a limit between the streamed bake's needs and the in-memory bake's lets only the
// streamed one run (a 61 × 61 floor at order 5: 9.3 MB of matrices in memory, about 1 MB of
// blocks in flight and geometry streamed).
TEST_CASE("glossy bake: a too-small memory limit is refused in one line with no file",
          "[glossy_bake]") {
  const prt::scene::Scene s = prt::scene::make_quad(
      {-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f}, 60, 60, glm::vec3(0.5f), "floor");
  GlossyBakeOptions o;
  o.order = 5;
  o.samples = 16;
  o.threads = 2;
  const std::string path = prt::test::output_path("glossy_refused_bake.prtg").string();
  std::filesystem::remove(path);
  o.memory_limit = 64 * 1024;
  check_refused_with_no_file(s, o, path, "the memory limit is 64.0 KB");
  o.memory_limit = 4 << 20;
  check_only_streamed_fits(s, o, path);
  CHECK(std::filesystem::file_size(path) > 9 * 1000 * 1000);
}

// Bounces that read a CPCA compression of the previous bounce: with one cluster and as many
// vectors as a vertex's matrices have entries (243) the compression spans everything, so the
// result equals the plain bounces to float rounding (1e-5 of the largest entry: the
// reconstruction's rounding is ~1e-7 relative, and two bounces add it twice); with one vector it
// must differ by more (the compressed transfer is really what the gather reads).
TEST_CASE("glossy bake: bounces over compressed transfer converge to the plain ones at full rank",
          "[glossy_bake]") {
  prt::scene::Scene s = phong_floor_and_box();
  GlossyBakeOptions o = two_bounces(64);
  const auto plain = bake_glossy_transfer(s, o);
  REQUIRE(plain.data.channels == 3);
  const auto max_difference = [&](const prt::GlossyTransferData& d) {
    double worst = 0, scale = 0;
    for (std::size_t i = 0; i < d.matrices.size(); ++i) {
      worst = std::max(worst, double(std::fabs(d.matrices[i] - plain.data.matrices[i])));
      scale = std::max(scale, double(std::fabs(plain.data.matrices[i])));
    }
    return worst / scale;
  };
  o.bounce_cpca_clusters = 1;
  o.bounce_cpca_vectors = 243;
  const auto full = bake_glossy_transfer(s, o);
  CHECK(max_difference(full.data) < 1e-5);
  CHECK(full.stats.bounce_cpca_bytes > 0);
  o.bounce_cpca_vectors = 1;
  CHECK(max_difference(bake_glossy_transfer(s, o).data) > 1e-4);
}

// The compact hits (8 bytes: triangle and 16-bit barycentrics, the sample implied by a bit mask)
// against the same rays with float barycentrics. Per hit a weight moves by ≤ 1/131070 (β₀ by
// ≤ 1/65535), so a radiance row by ≤ 3.1e-5 · max|M| · max|b| (b ≤ 1 here: ρ and the Phong lobe
// are below 1); a bounce entry (2π/N) Σ y_i r_j by ≤ 3.1e-5 · 2π · max|y_i| · max|M|, and two
// bounces add that twice. The difference must also be non-zero: the quantised path is the one in
// use. The gather is exactly 8 bytes a hit + N/8 bytes a vertex (16 a hit with float copies).
TEST_CASE("glossy bake: compact hits give the float hits' solution within the quantisation bound",
          "[glossy_bake]") {
  prt::scene::Scene s = phong_floor_and_box();
  GlossyBakeOptions o = two_bounces(128);
  const auto compact = bake_glossy_transfer(s, o);
  o.exact_hits = true;
  const auto exact = bake_glossy_transfer(s, o);
  REQUIRE(compact.stats.hits == exact.stats.hits);
  REQUIRE(compact.stats.hits > 1000);
  const uint64_t V = s.positions.size();
  CHECK(compact.stats.gather_bytes == 8 * compact.stats.hits + V * 128 / 8);
  CHECK(exact.stats.gather_bytes == 16 * exact.stats.hits + V * 128 / 8);
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < exact.data.matrices.size(); ++i) {
    worst = std::max(worst, double(std::fabs(compact.data.matrices[i] - exact.data.matrices[i])));
    scale = std::max(scale, double(std::fabs(exact.data.matrices[i])));
  }
  const double y_max = 1.0925484;  // max |y_i| over the sphere, bands 0..2 (Y₂,±₁ and Y₂,−₂)
  const double bound = 2 * 3.1e-5 * 2 * kPi * y_max * scale;
  INFO("max |compact − float| = " << worst << ", bound " << bound << ", max |M| " << scale);
  CHECK(worst <= bound);
  CHECK(worst > 0.0);
}

// Streamed interreflected bakes hold one bounce of matrices: a limit below it is refused in one
// line with no file and no temporary; a limit that the in-memory bake (two bounces and S) exceeds
// but the streamed one does not lets only the streamed one run, within the limit, and the
// scratch files are gone after. A 31 × 31 floor and a box, order 5, 3 channels: 7.5 KB a vertex
// per bounce, 8.0 MB for M, 18.3 MB for the in-memory bake's matrices.
TEST_CASE("glossy bake: streamed interreflection holds one bounce, and a limit below it is refused",
          "[glossy_bake]") {
  prt::scene::Scene s = prt::scene::make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f},
                                              30, 30, glm::vec3(0.7f, 0.5f, 0.3f), "floor");
  prt::scene::append_scene(s, prt::scene::make_box({-0.5f, 0.f, -0.5f}, {0.5f, 1.f, 0.5f}, 4, false,
                                                   glm::vec3(0.6f), "box"));
  GlossyBakeOptions o;
  o.order = 5;
  o.samples = 16;
  o.bounces = 1;
  o.threads = 2;
  const std::string path = prt::test::output_path("glossy_ir_refused.prtg").string();
  std::filesystem::remove(path);
  o.memory_limit = 6 << 20;
  check_refused_with_no_file(s, o, path, "the glossy matrices of the bounce read");
  o.memory_limit = 12 << 20;
  const prt::bake::GlossyBakeStatistics stats = check_only_streamed_fits(s, o, path);
  CHECK(stats.hits > 0);
  CHECK(stats.peak_charged_bytes > s.positions.size() * 3 * 625 * 4);
  CHECK(prt::read_glossy_transfer_file(path).value().channels == 3);
  CHECK_FALSE(scratch_left(path));
}

// The last charge of a streamed interreflected bake is the last block's hits, during the ray
// pass, when the output's temporary and the scratch files already exist: a limit one byte below
// the unlimited bake's peak must stop it there, in one line naming the hits, with no file, no
// temporary and no scratch file left; at the peak it runs. Float and binary16 bounces.
TEST_CASE(
    "glossy bake: a streamed interreflected bake over its limit in the ray pass leaves nothing",
    "[glossy_bake]") {
  prt::scene::Scene s = prt::scene::make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f},
                                              16, 16, glm::vec3(0.7f, 0.5f, 0.3f), "floor");
  prt::scene::append_scene(s, prt::scene::make_box({-0.5f, 0.f, -0.5f}, {0.5f, 1.f, 0.5f}, 2, false,
                                                   glm::vec3(0.6f), "box"));
  const std::string path = prt::test::output_path("glossy_ir_pass_refused.prtg").string();
  for (const prt::Precision bounce : {prt::Precision::F32, prt::Precision::F16}) {
    INFO("bounce precision " << (bounce == prt::Precision::F16 ? "f16" : "f32"));
    GlossyBakeOptions o;
    o.order = 3;
    o.samples = 32;
    o.bounces = 1;
    o.threads = 2;
    o.bounce_precision = bounce;
    o.memory_limit = 0;
    std::filesystem::remove(path);
    const uint64_t peak =
        prt::bake::bake_glossy_transfer_to_file(s, o, path).stats.peak_charged_bytes;
    std::filesystem::remove(path);
    o.memory_limit = peak - 1;  // one byte below the peak
    check_refused_with_no_file(s, o, path, "the glossy bounces' ray hits");
    CHECK_FALSE(scratch_left(path));
    o.memory_limit = peak;
    CHECK(prt::bake::bake_glossy_transfer_to_file(s, o, path).stats.peak_charged_bytes == peak);
    CHECK(std::filesystem::exists(path));
    std::filesystem::remove(path);
  }
}

// A binary16 bounce (GlossyBakeOptions::bounce_precision F16): the gather reads M rounded to
// 2⁻¹¹ relative. Bound: a hit's row Σ_a β_a Σ_i b_i M_ij moves by ≤ 2⁻¹¹ · K · max|b| · max|M|
// (b ≤ 1 here), a bounce entry by 2π · max|y| times that, and two bounces add it twice (the
// second also reads the first's error, which the same bound covers, the bounce being a
// contraction). It must differ from the float bounce (the binary16 copy is really what is read),
// charge less (650 vertices: the 0.5 KB a vertex saved outweigh the larger blocks in flight),
// be the same bytes at 1 and 2 threads, and be refused in memory.
TEST_CASE("glossy bake: a binary16 bounce stays within its rounding bound of the float one",
          "[glossy_bake]") {
  prt::scene::Scene s = prt::scene::make_quad({-2.f, 0.f, 2.f}, {4.f, 0.f, 0.f}, {0.f, 0.f, -4.f},
                                              24, 24, glm::vec3(0.7f, 0.5f, 0.3f), "floor");
  prt::scene::append_scene(s, prt::scene::make_box({-0.5f, 0.f, -0.5f}, {0.5f, 1.f, 0.5f}, 2, false,
                                                   glm::vec3(0.6f), "box"));
  s.primitives[1].brdf = test_phong();
  GlossyBakeOptions o = two_bounces(64);
  o.threads = 1;
  const std::string path = prt::test::output_path("glossy_half_bounce.prtg").string();
  const auto plain = prt::bake::bake_glossy_transfer_to_file(s, o, path);
  const auto f32 = prt::read_glossy_transfer_file(path);
  REQUIRE(f32.ok());
  o.bounce_precision = prt::Precision::F16;
  CHECK_THROWS_AS(bake_glossy_transfer(s, o), prt::bake::BakeError);
  const auto half = prt::bake::bake_glossy_transfer_to_file(s, o, path);
  const auto bytes_one = file_bytes(path);
  const auto f16 = prt::read_glossy_transfer_file(path);
  REQUIRE(f16.ok());
  o.threads = 2;
  prt::bake::bake_glossy_transfer_to_file(s, o, path);
  CHECK(file_bytes(path) == bytes_one);
  CHECK(half.stats.peak_charged_bytes < plain.stats.peak_charged_bytes);
  const auto& a = f32.value().matrices;
  const auto& b = f16.value().matrices;
  REQUIRE(a.size() == b.size());
  double worst = 0, scale = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, double(std::fabs(a[i] - b[i])));
    scale = std::max(scale, double(std::fabs(a[i])));
  }
  const double bound = 2 * std::ldexp(1.0, -11) * 9 * 2 * kPi * 1.0925484 * scale;
  INFO("max |f16 bounce − f32 bounce| = " << worst << ", bound " << bound << ", max |M| " << scale);
  CHECK(worst <= bound);
  CHECK(worst > 0.0);
}
