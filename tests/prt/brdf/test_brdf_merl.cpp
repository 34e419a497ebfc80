// The MERL reader against files this test writes itself from an analytic model (no measured
// data is bundled): exact values at cell centres, albedo close to the model's, refused files.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "brdf_test_support.h"
#include "prt/brdf/energy_check.h"
#include "prt/brdf/lambert.h"
#include "prt/brdf/material.h"
#include "prt/brdf/merl.h"
#include "prt/brdf/microfacet.h"
#include "sh/constants.h"

using namespace prt::brdf;
using brdf_test::Rng;

namespace {

using prt::sh::kPi;
constexpr int kH = 90, kD = 90, kP = 180;
const double kScale[3] = {1.0 / 1500.0, 1.15 / 1500.0, 1.66 / 1500.0};

// The reference material: a coloured Lambert plus an isotropic GGX lobe with Schlick Fresnel.
Microfacet reference_glossy() {
  MicrofacetParams p;
  p.alpha_x = p.alpha_y = 0.3;
  p.fresnel = FresnelMode::kSchlick;
  p.f0 = {0.6, 0.5, 0.3};
  return Microfacet::create(p).value();
}

Lambert reference_diffuse() {
  const Rgb rho{0.3, 0.2, 0.1};
  prt::Result<Lambert> l = Lambert::create(rho);
  return std::move(l).value();
}

struct Reference {
  Lambert diffuse = reference_diffuse();
  Microfacet glossy = reference_glossy();
  Rgb eval(const Vec3& wi, const Vec3& wo) const {
    return diffuse.eval(wi, wo) + glossy.eval(wi, wo);
  }
};

// Directions at the centre of cell (ih, id, ip), rotated by phi_h about the normal, written out
// from the format's definition (independently of the reader): θ_h = ((ih + ½)/90)² π/2,
// θ_d = (id + ½)/90 · π/2, φ_d = (ip + ½)/180 · π; ωi = Rz(φ_h) Ry(θ_h) d, ωo its mirror
// about h = Rz(φ_h) Ry(θ_h) ẑ.
void cell_directions(int ih, int id, int ip, double phi_h, Vec3& wi, Vec3& wo) {
  const double th = std::pow((ih + 0.5) / kH, 2.0) * kPi / 2.0;
  const double td = (id + 0.5) / kD * kPi / 2.0;
  const double pd = (ip + 0.5) / kP * kPi;
  const Vec3 d = spherical_direction(std::cos(td), pd);
  const double ct = std::cos(th), st = std::sin(th), cp = std::cos(phi_h), sp = std::sin(phi_h);
  const Vec3 r{ct * d.x + st * d.z, d.y, -st * d.x + ct * d.z};  // Ry(θ_h) d
  wi = {cp * r.x - sp * r.y, sp * r.x + cp * r.y, r.z};          // Rz(φ_h)
  const Vec3 h{cp * st, sp * st, ct};
  wo = reflect(wi, h);
}

std::string output_path(const std::string& name) {
  return std::string(PRT_TEST_OUTPUT_DIR) + "/" + name;
}

void write_file(const std::string& path, const int32_t dims[3], const std::vector<double>& table,
                std::size_t byte_limit = SIZE_MAX) {
  std::vector<char> bytes(12 + table.size() * sizeof(double));
  std::memcpy(bytes.data(), dims, 12);
  std::memcpy(bytes.data() + 12, table.data(), table.size() * sizeof(double));
  if (byte_limit < bytes.size()) bytes.resize(byte_limit);
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

std::vector<double> reference_table() {
  const Reference ref;
  const std::size_t cells = std::size_t{kH} * kD * kP;
  std::vector<double> t(3 * cells);
  for (int ih = 0; ih < kH; ++ih) {
    for (int id = 0; id < kD; ++id) {
      for (int ip = 0; ip < kP; ++ip) {
        Vec3 wi, wo;
        cell_directions(ih, id, ip, 0.0, wi, wo);
        const Rgb f = ref.eval(wi, wo);
        const std::size_t i = (std::size_t(ih) * kD + id) * kP + ip;
        // Cells with a direction below the horizon hold −1, the database's "no data" marker.
        const bool valid = wi.z > 0.0 && wo.z > 0.0;
        t[i] = valid ? f.r / kScale[0] : -1.0;
        t[cells + i] = valid ? f.g / kScale[1] : -1.0;
        t[2 * cells + i] = valid ? f.b / kScale[2] : -1.0;
      }
    }
  }
  return t;
}

const int32_t kDims[3] = {kH, kD, kP};

}  // namespace

TEST_CASE("a MERL file written from an analytic model reads back exactly at cell centres",
          "[brdf][merl]") {
  const std::string path = output_path("reference.binary");
  write_file(path, kDims, reference_table());
  const prt::Result<MerlBrdf> merl = MerlBrdf::read(path);
  REQUIRE(merl.ok());
  const Reference ref;
  Rng rng{77};
  int checked = 0;
  for (int k = 0; k < 20000; ++k) {
    const int ih = int(rng.uniform() * kH), id = int(rng.uniform() * kD),
              ip = int(rng.uniform() * kP);
    Vec3 wi, wo;
    cell_directions(ih, id, ip, 2.0 * kPi * rng.uniform(), wi, wo);
    if (wi.z <= 1e-6 || wo.z <= 1e-6) continue;
    const Rgb want = ref.eval(wi, wo), got = merl->eval(wi, wo);
    INFO("cell " << ih << " " << id << " " << ip);
    // The scale factors round-trip through f/scale·scale: a few ulps.
    REQUIRE(got.r == Approx(want.r).epsilon(1e-9));
    REQUIRE(got.g == Approx(want.g).epsilon(1e-9));
    REQUIRE(got.b == Approx(want.b).epsilon(1e-9));
    // Reciprocity of the lookup: swapping the directions moves φ_d by π.
    REQUIRE(merl->eval(wo, wi).g == got.g);
    ++checked;
  }
  CHECK(checked > 5000);

  // Between centres the lookup is nearest-cell, so the albedo differs from the model's only by
  // the discretisation: measured 0.01% at θo = 30°, 0.03% at 60°; tolerance 0.5%. 512² samples
  // each (cosine-weighted for the MERL table).
  for (double deg : {30.0, 60.0}) {
    const Vec3 wo = spherical_direction(std::cos(deg * kPi / 180.0), 0.3);
    const Rgb a_merl = directional_albedo(*merl, wo, 512, 5);
    const Rgb a_ref =
        directional_albedo(ref.diffuse, wo, 512, 5) + directional_albedo(ref.glossy, wo, 512, 5);
    INFO("theta_o = " << deg << ": MERL " << a_merl.r << " " << a_merl.g << " " << a_merl.b
                      << ", model " << a_ref.r << " " << a_ref.g << " " << a_ref.b);
    CHECK(a_merl.r == Approx(a_ref.r).epsilon(0.005));
    CHECK(a_merl.b == Approx(a_ref.b).epsilon(0.005));
  }
  std::remove(path.c_str());
}

TEST_CASE("MERL: unmeasured (negative) cells evaluate as zero", "[brdf][merl]") {
  const std::string path = output_path("negative.binary");
  write_file(path, kDims, std::vector<double>(3 * std::size_t{kH} * kD * kP, -1.0));
  const prt::Result<MerlBrdf> merl = MerlBrdf::read(path);
  REQUIRE(merl.ok());
  const Rgb f = merl->eval(spherical_direction(0.5, 0.1), spherical_direction(0.8, 2.0));
  CHECK(f.r == 0.0);
  CHECK(f.b == 0.0);
  std::remove(path.c_str());
}

TEST_CASE("MERL: bad files are refused with a message naming the file", "[brdf][merl]") {
  const std::size_t full = 3 * std::size_t{kH} * kD * kP;
  std::vector<double> table(full, 100.0);
  struct Case {
    std::string name;
    std::size_t limit;
    int32_t dims[3];
    bool nan;
    std::string expect;
  };
  const Case cases[] = {
      {"truncated_table.binary", 12 + full * 8 - 8, {kH, kD, kP}, false, "truncated MERL file"},
      {"truncated_header.binary", 7, {kH, kD, kP}, false, "truncated MERL file"},
      {"wrong_dims.binary", 4096, {kH, kD, 360}, false, "expected 90x90x180"},
      {"nan.binary", SIZE_MAX, {kH, kD, kP}, true, "non-finite MERL value"},
  };
  for (const Case& c : cases) {
    const std::string path = output_path(c.name);
    std::vector<double> t = table;
    if (c.nan) t[12345] = std::nan("");
    write_file(path, c.dims, t, c.limit);
    const prt::Result<MerlBrdf> merl = MerlBrdf::read(path);
    INFO(c.name);
    REQUIRE_FALSE(merl.ok());
    const std::string msg = merl.status().message();
    INFO(msg);
    CHECK(msg.find(path) == 0);
    CHECK(msg.find(c.expect) != std::string::npos);
    CHECK(msg.find('\n') == std::string::npos);
    std::remove(path.c_str());
  }
  const prt::Result<MerlBrdf> missing = MerlBrdf::read(output_path("no_such_file.binary"));
  REQUIRE_FALSE(missing.ok());
  CHECK(missing.status().message().find("cannot open") != std::string::npos);
}

// The white-furnace check on measured data: a MERL table of a constant ρ/π (a Lambert surface)
// passes at ρ = 0.9 and is refused at ρ = 1.3, naming the file; the verdict is kept per path,
// so a second check of the same path does not read the file again (it is deleted in between).
TEST_CASE("MERL: the white-furnace check reads the table once and refuses albedo above 1",
          "[brdf][merl][energy_check]") {
  const std::size_t cells = std::size_t{kH} * kD * kP;
  for (double rho : {0.9, 1.3}) {
    std::vector<double> t(3 * cells);
    for (int c = 0; c < 3; ++c)
      std::fill(t.begin() + c * cells, t.begin() + (c + 1) * cells, rho / kPi / kScale[c]);
    const std::string path = output_path(rho < 1.0 ? "furnace_09.binary" : "furnace_13.binary");
    write_file(path, kDims, t);
    Material m;
    m.model = MaterialModel::kMerl;
    m.merl_path = path;
    const prt::Status first = check_energy_conservation(m);
    std::remove(path.c_str());
    const prt::Status again = check_energy_conservation(m);
    INFO(first.message());
    CHECK(first.ok() == (rho < 1.0));
    CHECK(again.ok() == first.ok());
    CHECK(again.message() == first.message());
    if (rho > 1.0) {
      CHECK(first.message().find("merl(" + path + ") reflects 1.3") != std::string::npos);
    }
  }
}
