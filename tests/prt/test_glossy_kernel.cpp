// Tests of prt/glossy/kernel.h: the uncompressed and CPCA kernels against the double
// references (to a float-rounding bound), AVX2 against portable bit for bit, an analytic
// case for the references, the order rules and refused calls.
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/cpca/compressor.h"
#include "prt/diffuse/relighter.h"
#include "prt/glossy/cpca_kernel.h"
#include "prt/glossy/kernel.h"
#include "prt/glossy/reference.h"
#include "support/synthetic_glossy.h"

using prt::CpcaFrame;
using prt::CpcaKernel;
using prt::CpcaTransfer;
using prt::GlossyKernel;
using prt::GlossyTransferData;
using prt::KernelPath;
using prt::ShLighting;

namespace {

ShLighting random_lighting(int order, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  std::vector<double> c(3 * order * order);
  for (double& x : c) x = unit(rng);
  c[0] = c[order * order] = c[2 * order * order] = 3.0;  // mostly positive, like real light
  auto light = ShLighting::from_coefficients(order, c.data());
  REQUIRE(light.ok());
  return *light;
}

std::vector<float> random_b(std::size_t count, int n2, int channels, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-0.5f, 1.0f);
  std::vector<float> b(count * channels * n2);
  for (float& x : b) x = unit(rng);
  return b;
}

// Σ_i |b_i| Σ_j |M_ij L_j| for output channel c of vertex v: the scale of the rounding error.
double magnitude(const GlossyTransferData& d, const ShLighting& light, const float* b_of_v,
                 int b_channels, std::size_t v, int c) {
  const int n2 = static_cast<int>(d.coefficients()), used = std::min<int>(d.order, light.order());
  const float* m = d.matrices.data() + (v * d.channels + (d.channels == 1 ? 0 : c)) * n2 * n2;
  const float* b = b_of_v + (b_channels == 1 ? 0 : c) * n2;
  double sum = 0;
  for (int i = 0; i < n2; ++i) {
    double row = 0;
    for (int j = 0; j < used * used; ++j) {
      row += std::abs(m[i * n2 + j] * light.coefficients_double(c)[j]);
    }
    sum += std::abs(b[i]) * row;
  }
  return sum;
}

CpcaTransfer compress(const GlossyTransferData& d, uint32_t clusters, uint32_t k) {
  prt::CpcaOptions o;
  o.clusters = clusters;
  o.vectors = k;
  auto r = prt::cpca_compress(d, o);
  REQUIRE(r.ok());
  return std::move(r).value();
}

// The matrices a CPCA form stands for (reconstructed, rounded to float).
GlossyTransferData reconstructed(const GlossyTransferData& d, const CpcaTransfer& t) {
  GlossyTransferData r = d;
  std::vector<double> x(t.dimension());
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    prt::cpca_reconstruct(t, v, x.data());
    for (std::size_t e = 0; e < x.size(); ++e) r.matrices[v * x.size() + e] = float(x[e]);
  }
  return r;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

}  // namespace

TEST_CASE("Glossy references: identity transfer passes the lighting through", "[glossy]") {
  // M_v = identity: L' = L (zero beyond the light's order), exit = Σ_i b_i L_c,i.
  GlossyTransferData d;
  d.order = 3;
  d.vertex_count = 2;
  d.matrices.assign(2 * 81, 0.0f);
  for (int v = 0; v < 2; ++v) {
    for (int i = 0; i < 9; ++i) d.matrices[v * 81 + i * 9 + i] = 1.0f;
  }
  const ShLighting light = random_lighting(2, 7);  // order 2 < 3: bands 2 are zero
  double lp[27];
  REQUIRE(prt::glossy_transfer_reference(d, light, 1, lp).ok());
  for (int c = 0; c < 3; ++c) {
    for (int i = 0; i < 9; ++i) {
      CHECK(lp[c * 9 + i] == (i < 4 ? light.coefficients_double(c)[i] : 0.0));
    }
  }
  std::vector<float> b = random_b(1, 9, 3, 3);
  double e[3];
  REQUIRE(prt::glossy_shade_reference(d, light, b.data(), 3, 0, e).ok());
  for (int c = 0; c < 3; ++c) {
    double want = 0;
    for (int i = 0; i < 4; ++i) want += double(b[c * 9 + i]) * light.coefficients_double(c)[i];
    CHECK(e[c] == Approx(want).epsilon(1e-15));
  }
  auto r = GlossyKernel::create(d);
  REQUIRE(r.ok());
  std::vector<float> out(2 * 27);
  REQUIRE(r->transfer(light, 0, 2, out.data()).ok());
  for (int i = 0; i < 9; ++i) CHECK(out[27 + 9 + i] == (i < 4 ? light.coefficients(1)[i] : 0.0f));
}

TEST_CASE("Glossy kernels match the double references to float rounding", "[glossy]") {
  // Bound: the float kernel sums n² products per row of M·L, then n² products b_i·L'_i, each
  // step rounding by at most 2^-24 relative; with K vectors CPCA adds K + 1 terms and the
  // rounding of the per-frame products. |e − e_ref| ≤ (2n² + K + 4)·2^-24·Σ|terms| is the
  // standard bound γ_N·Σ|terms|; the test allows exactly that (no extra factor).
  for (int channels : {1, 3}) {
    const GlossyTransferData d = prt::test::synthetic_glossy(150, 5, channels, 256);
    const CpcaTransfer t = compress(d, 6, 5);
    const GlossyTransferData rec = reconstructed(d, t);
    auto glossy = GlossyKernel::create(d);
    auto cpca = CpcaKernel::create(t);
    REQUIRE(glossy.ok());
    REQUIRE(cpca.ok());
    for (int light_order : {3, 5, 7}) {
      const ShLighting light = random_lighting(light_order, 11 + light_order);
      CpcaFrame frame;
      REQUIRE(cpca->prepare(light, &frame).ok());
      for (int bc : {1, 3}) {
        const std::size_t first = 7, count = 131;
        const std::vector<float> b = random_b(count, 25, bc, 5);
        for (KernelPath path : {KernelPath::Portable, KernelPath::Auto}) {
          std::vector<float> eg(3 * count), ec(3 * count);
          REQUIRE(glossy->shade_using(path, light, b.data(), bc, first, count, eg.data()).ok());
          REQUIRE(cpca->shade_using(path, frame, b.data(), bc, first, count, ec.data()).ok());
          for (std::size_t r = 0; r < count; ++r) {
            const std::size_t v = first + r;
            const float* bv = b.data() + r * bc * 25;
            double ref[3], cref[3];
            REQUIRE(prt::glossy_shade_reference(d, light, bv, bc, v, ref).ok());
            REQUIRE(prt::cpca_shade_reference(t, light, bv, bc, v, cref).ok());
            for (int c = 0; c < 3; ++c) {
              const double tol = (2 * 25 + 4) * 0x1p-24 * magnitude(d, light, bv, bc, v, c);
              CHECK(std::abs(eg[3 * r + c] - ref[c]) <= tol);
              const double ctol = (2 * 25 + 5 + 4) * 0x1p-24 * magnitude(rec, light, bv, bc, v, c);
              CHECK(std::abs(ec[3 * r + c] - cref[c]) <= ctol + 1e-7 * std::abs(cref[c]));
            }
          }
        }
      }
      // L' itself (no b): each entry is one row's sum.
      std::vector<float> lg(3 * 25 * 150), lc(3 * 25 * 150);
      REQUIRE(glossy->transfer(light, 0, 150, lg.data()).ok());
      REQUIRE(cpca->transfer(frame, 0, 150, lc.data()).ok());
      double worst = 0, worst_c = 0, scale = 0;
      for (std::size_t v = 0; v < 150; ++v) {
        double ref[75], cref[75];
        REQUIRE(prt::glossy_transfer_reference(d, light, v, ref).ok());
        REQUIRE(prt::cpca_transfer_reference(t, light, v, cref).ok());
        for (int e = 0; e < 75; ++e) {
          worst = std::max(worst, std::abs(lg[v * 75 + e] - ref[e]));
          worst_c = std::max(worst_c, std::abs(lc[v * 75 + e] - cref[e]));
          scale = std::max(scale, std::abs(ref[e]));
        }
      }
      CHECK(worst <= 1e-5 * scale);
      CHECK(worst_c <= 1e-5 * scale);
    }
  }
}

// The CPCA kernel's AVX-512 path too, where the CPU has AVX-512F (a warning says when it is not
// checked). Orders 1–7 cover an odd and an even count of 8-lane vectors and the generic code.
TEST_CASE("Glossy kernels: AVX2, AVX-512 and portable paths agree bit for bit", "[glossy]") {
  if (!prt::Relighter::avx2_path_available()) {
    WARN("skipping: this CPU lacks AVX2/F16C/FMA");
    return;
  }
  const bool wide = CpcaKernel::avx512_path_available();
  if (!wide) WARN("the CPCA AVX-512 path is not checked: this CPU lacks AVX-512F");
  for (int order : {1, 2, 3, 4, 5, 6, 7}) {  // 7: the AVX2 CPCA code for any order
    for (int channels : {1, 3}) {
      const GlossyTransferData d = prt::test::synthetic_glossy(45, order, channels, 128);
      const int n2 = order * order;
      const CpcaTransfer t = compress(d, 3, std::min(4, n2 * n2 * channels));
      auto glossy = GlossyKernel::create(d);
      auto cpca = CpcaKernel::create(t);
      REQUIRE(glossy.ok());
      REQUIRE(cpca.ok());
      const ShLighting light = random_lighting(std::max(1, order - 1 + channels % 2), 3);
      CpcaFrame frame;
      REQUIRE(cpca->prepare(light, &frame).ok());
      const std::size_t first = 3, count = 40;
      for (int bc : {1, 3}) {
        const std::vector<float> b = random_b(count, n2, bc, 9);
        std::vector<float> p(3 * count), a(3 * count);
        REQUIRE(
            glossy->shade_using(KernelPath::Portable, light, b.data(), bc, first, count, p.data())
                .ok());
        REQUIRE(glossy->shade_using(KernelPath::Avx2, light, b.data(), bc, first, count, a.data())
                    .ok());
        CHECK(same_bits(p, a));
        REQUIRE(cpca->shade_using(KernelPath::Portable, frame, b.data(), bc, first, count, p.data())
                    .ok());
        REQUIRE(
            cpca->shade_using(KernelPath::Avx2, frame, b.data(), bc, first, count, a.data()).ok());
        CHECK(same_bits(p, a));
        if (wide) {
          std::fill(a.begin(), a.end(), -1.0f);
          REQUIRE(cpca->shade_using(KernelPath::Avx512, frame, b.data(), bc, first, count, a.data())
                      .ok());
          CHECK(same_bits(p, a));
        }
      }
      std::vector<float> p(3 * n2 * count), a(3 * n2 * count);
      REQUIRE(glossy->transfer_using(KernelPath::Portable, light, first, count, p.data()).ok());
      REQUIRE(glossy->transfer_using(KernelPath::Avx2, light, first, count, a.data()).ok());
      CHECK(same_bits(p, a));
      REQUIRE(cpca->transfer_using(KernelPath::Portable, frame, first, count, p.data()).ok());
      REQUIRE(cpca->transfer_using(KernelPath::Avx2, frame, first, count, a.data()).ok());
      CHECK(same_bits(p, a));
      if (wide) {
        std::fill(a.begin(), a.end(), -1.0f);
        REQUIRE(cpca->transfer_using(KernelPath::Avx512, frame, first, count, a.data()).ok());
        CHECK(same_bits(p, a));
      }
    }
  }
}

TEST_CASE("Glossy kernels: a chunked range gives the same bits as one call", "[glossy]") {
  const GlossyTransferData d = prt::test::synthetic_glossy(70, 4, 1, 128);
  auto glossy = GlossyKernel::create(d);
  auto cpca = CpcaKernel::create(compress(d, 4, 3));
  REQUIRE(glossy.ok());
  REQUIRE(cpca.ok());
  const ShLighting light = random_lighting(4, 1);
  CpcaFrame frame;
  REQUIRE(cpca->prepare(light, &frame).ok());
  const std::vector<float> b = random_b(70, 16, 1, 2);
  std::vector<float> whole(210), parts(210), cwhole(210), cparts(210);
  REQUIRE(glossy->shade(light, b.data(), 1, 0, 70, whole.data()).ok());
  REQUIRE(cpca->shade(frame, b.data(), 1, 0, 70, cwhole.data()).ok());
  for (std::size_t first : {0u, 5u, 21u, 48u}) {
    const std::size_t end = first == 48 ? 70 : (first == 0 ? 5 : first == 5 ? 21 : 48);
    REQUIRE(
        glossy->shade(light, b.data() + first * 16, 1, first, end - first, parts.data() + 3 * first)
            .ok());
    REQUIRE(
        cpca->shade(frame, b.data() + first * 16, 1, first, end - first, cparts.data() + 3 * first)
            .ok());
  }
  CHECK(same_bits(whole, parts));
  CHECK(same_bits(cwhole, cparts));
}

TEST_CASE("Glossy kernels refuse bad calls", "[glossy]") {
  const GlossyTransferData d = prt::test::synthetic_glossy(20, 2, 1, 64);
  auto glossy = GlossyKernel::create(d);
  auto cpca = CpcaKernel::create(compress(d, 2, 2));
  auto other = CpcaKernel::create(compress(d, 2, 2));
  REQUIRE(glossy.ok());
  REQUIRE(cpca.ok());
  REQUIRE(other.ok());
  const ShLighting light = random_lighting(2, 1);
  std::vector<float> b(20 * 4, 1.0f), out(3 * 20);
  CHECK(glossy->shade(light, b.data(), 2, 0, 20, out.data()).message() ==
        "glossy shade: b has 2 channels, not 1 or 3");
  CHECK(glossy->shade(light, b.data(), 1, 5, 16, out.data()).message() ==
        "glossy shade: vertex range [5, +16) exceeds the 20 vertices");
  CHECK_FALSE(glossy->transfer(light, 0, 1, nullptr).ok());
  // Only the CPCA kernel has an AVX-512 path.
  CHECK(glossy->shade_using(KernelPath::Avx512, light, b.data(), 1, 0, 20, out.data()).message() ==
        "glossy shade: the uncompressed kernel has no AVX-512 path");
  CpcaFrame frame;
  REQUIRE(other->prepare(light, &frame).ok());
  CHECK(cpca->shade(frame, b.data(), 1, 0, 20, out.data()).message() ==
        "cpca shade: the frame was not prepared by this relighter");
  GlossyTransferData bad = d;
  bad.matrices[17] = INFINITY;
  CHECK(GlossyKernel::create(bad).status().message() ==
        "glossy transfer: matrix entry 1 of vertex 1 is not finite");
}
