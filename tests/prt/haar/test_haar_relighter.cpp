// Tests of sparse Haar relighting (prt/haar/relighter.h) against brute-force texel sums.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/haar/relighter.h"
#include "sh/constants.h"

namespace {

struct DenseScene {
  int size = 0;
  int channels = 1;
  int64_t vertex_count = 0;
  std::vector<float> transfer;  // vertex-major, 6N²·channels per vertex
};

DenseScene random_dense_scene(int n, int channels, int64_t vertices, uint32_t seed) {
  DenseScene s{n, channels, vertices, {}};
  const size_t texels = 6 * static_cast<size_t>(n) * n;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(0.0f, 1.0f);
  s.transfer.resize(static_cast<size_t>(vertices) * texels * channels);
  for (int64_t v = 0; v < vertices; ++v)
    for (size_t t = 0; t < texels; ++t) {
      const int row = static_cast<int>(t % (n * n)) / n, col = static_cast<int>(t % n);
      const float omega = static_cast<float>(prt::cube_texel_solid_angle(n, col, row));
      for (int c = 0; c < channels; ++c)
        s.transfer[(v * texels + t) * channels + c] = omega * dist(rng) / prt::sh::kPiFloat;
    }
  return s;
}

prt::HaarTransfer build_transfer(const DenseScene& s, const prt::HaarTransferOptions& options) {
  prt::HaarTransferBuilder builder(s.size, s.channels, options.quantization);
  const size_t per_vertex = 6 * static_cast<size_t>(s.size) * s.size * s.channels;
  for (int64_t v = 0; v < s.vertex_count; ++v) {
    const prt::Result<prt::SparseVertexTransfer> sv = prt::compress_vertex_transfer(
        s.transfer.data() + v * per_vertex, s.size, s.channels, options);
    REQUIRE(sv.ok());
    REQUIRE(builder.add_vertex(*sv).ok());
  }
  prt::Result<prt::HaarTransfer> t = builder.finish();
  REQUIRE(t.ok());
  return std::move(*t);
}

prt::CubeMap random_lighting(int n, uint32_t seed) {
  prt::CubeMap cube = prt::make_black_cube_map(n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> dist(0.0f, 10.0f);
  for (float& v : cube.rgb) v = dist(rng);
  return cube;
}

}  // namespace

TEST_CASE("With all terms kept and no quantisation, relighting equals the texel sum",
          "[haar][relighter]") {
  for (int channels : {1, 3}) {
    const int n = 8;
    const DenseScene scene = random_dense_scene(n, channels, 40, 31 + channels);
    prt::HaarTransferOptions options;
    options.quantization = prt::HaarQuantization::Float32;
    const prt::HaarRelighter relighter(build_transfer(scene, options));
    const prt::CubeMap light = random_lighting(n, 77);
    const prt::SparseLighting all = prt::keep_all_terms(*prt::transform_cube(light));
    std::vector<float> fast(3 * scene.vertex_count);
    REQUIRE(relighter.shade(all, fast.data()).ok());
    std::vector<double> reference(3 * scene.vertex_count);
    REQUIRE(prt::shade_dense_reference(scene.transfer.data(), scene.vertex_count, n, channels,
                                       light, reference.data())
                .ok());
    for (size_t i = 0; i < fast.size(); ++i) {
      // Positive transfer and lighting, so B is the magnitude scale. Float coefficients
      // (2⁻²⁴ relative each) and a 384-term float sum: ≲ 384·2⁻²⁴ ≈ 2.3e-5 worst case,
      // ~√384·2⁻²⁴ ≈ 1.2e-6 in practice; 1e-5 (the brief's figure) sits between.
      INFO("channels " << channels << ", value " << i);
      REQUIRE(fast[i] == Approx(reference[i]).epsilon(1e-5));
    }
  }
}

TEST_CASE("Quantised relighting error stays within the propagated bound", "[haar][relighter]") {
  const int n = 8;
  const DenseScene scene = random_dense_scene(n, 3, 30, 5);
  const prt::CubeMap light = random_lighting(n, 6);
  const prt::SparseLighting all = prt::keep_all_terms(*prt::transform_cube(light));
  std::vector<double> reference(3 * scene.vertex_count);
  REQUIRE(prt::shade_dense_reference(scene.transfer.data(), scene.vertex_count, n, 3, light,
                                     reference.data())
              .ok());
  double sum_abs_light = 0.0;  // Σ_i max_c |L̂_i,c|
  for (size_t i = 0; i < all.index.size(); ++i)
    sum_abs_light += std::max(
        {std::fabs(all.rgb[3 * i]), std::fabs(all.rgb[3 * i + 1]), std::fabs(all.rgb[3 * i + 2])});
  for (prt::HaarQuantization q : {prt::HaarQuantization::Bits16, prt::HaarQuantization::Bits8}) {
    prt::HaarTransferOptions options;
    options.quantization = q;
    const prt::HaarRelighter relighter(build_transfer(scene, options));
    std::vector<float> fast(3 * scene.vertex_count);
    REQUIRE(relighter.shade(all, fast.data()).ok());
    double worst = 0.0;
    for (int64_t v = 0; v < scene.vertex_count; ++v) {
      // Each coefficient is off by at most bound(m_v); Σ_i |L̂_i|·bound bounds the sum, plus
      // 1e-5·B for the float evaluation (as in the unquantised test).
      const double m = static_cast<double>(relighter.transfer().vertex_step[v]) *
                       prt::haar_quantization_levels(q);
      const double bound = prt::haar_quantization_error_bound(q, m) * sum_abs_light;
      for (int c = 0; c < 3; ++c) {
        const double err = std::fabs(fast[3 * v + c] - reference[3 * v + c]);
        INFO("bits " << static_cast<int>(q) << ", vertex " << v);
        REQUIRE(err <= bound * (1 + 1e-6) + 1e-5 * reference[3 * v + c]);
        worst = std::max(worst, err / reference[3 * v + c]);
      }
    }
    // 8 bits must visibly differ from exact (the quantiser is really in the path).
    if (q == prt::HaarQuantization::Bits8) CHECK(worst > 1e-4);
  }
}

TEST_CASE("A point light in one texel shades exactly the vertices that see it",
          "[haar][relighter]") {
  // Vertices with normals on a Fibonacci sphere; vertex v sees texel t iff n_v·ω_t > 0 and
  // (t + v) mod 3 ≠ 0 (a synthetic occluder pattern). Where it sees, T = ω_t·(0.5 + 0.5 n·ω)/π,
  // so every visible texel carries a clearly non-zero value.
  const int n = 8;
  const int vertices = 48;
  const size_t texels = 6 * n * n;
  DenseScene scene{n, 1, vertices, std::vector<float>(vertices * texels, 0.0f)};
  std::vector<std::vector<bool>> sees(vertices, std::vector<bool>(texels, false));
  for (int v = 0; v < vertices; ++v) {
    const double y = 1.0 - 2.0 * (v + 0.5) / vertices, r = std::sqrt(1.0 - y * y);
    const double phi = v * 2.399963229728653;
    const double normal[3] = {r * std::cos(phi), y, r * std::sin(phi)};
    for (size_t t = 0; t < texels; ++t) {
      const int face = static_cast<int>(t / (n * n));
      const int row = static_cast<int>(t % (n * n)) / n, col = static_cast<int>(t % n);
      double d[3];
      prt::cube_texel_direction(n, face, col, row, d);
      const double cosine = normal[0] * d[0] + normal[1] * d[1] + normal[2] * d[2];
      if (cosine > 0 && (t + v) % 3 != 0) {
        sees[v][t] = true;
        scene.transfer[v * texels + t] = static_cast<float>(
            prt::cube_texel_solid_angle(n, col, row) * (0.5 + 0.5 * cosine) / prt::sh::kPi);
      }
    }
  }
  prt::HaarTransferOptions options;
  options.quantization = prt::HaarQuantization::Float32;
  const prt::HaarRelighter relighter(build_transfer(scene, options));
  for (size_t lit : {size_t{0}, size_t{77}, size_t{200}, size_t{383}}) {
    prt::CubeMap light = prt::make_black_cube_map(n);
    light.rgb[3 * lit] = light.rgb[3 * lit + 1] = light.rgb[3 * lit + 2] = 1000.0f;
    const prt::WaveletCube w = *prt::transform_cube(light);
    const prt::SparseLighting all = prt::select_nonlinear(w, 6 * n * n);
    std::vector<float> out(3 * vertices);
    REQUIRE(relighter.shade(all, out.data()).ok());
    int lit_count = 0;
    for (int v = 0; v < vertices; ++v) {
      // Float noise scale of this vertex: Σ_i |T̂_v,i|·|L̂_i| (double, from the stored terms).
      // Cancellation leaves at most ~K·2⁻²⁴ ≈ 2.3e-5 of it (K = 384 terms) in the worst case;
      // the threshold 1e-4 of it is safely above that and far below any visible vertex's B.
      double scale = 0.0;
      const prt::HaarTransfer& t = relighter.transfer();
      for (size_t k = 0; k < all.index.size(); ++k) {
        const uint32_t i = all.index[k];
        for (uint64_t e = t.offsets[i]; e < t.offsets[i + 1]; ++e)
          if (t.vertices[e] == static_cast<uint32_t>(v))
            scale += std::fabs(t.values_f32[e] * static_cast<double>(all.rgb[3 * k]));
      }
      const double threshold = 1e-4 * scale;
      const double expected = 1000.0 * scene.transfer[v * texels + lit];
      INFO("lit texel " << lit << ", vertex " << v << ", B = " << out[3 * v] << ", expected "
                        << expected << ", threshold " << threshold);
      if (sees[v][lit]) {
        ++lit_count;
        REQUIRE(expected > 100 * threshold);  // the test can tell lit from unlit
        REQUIRE(out[3 * v] == Approx(expected).epsilon(1e-4));
      } else {
        REQUIRE(std::fabs(out[3 * v]) <= threshold);
      }
      REQUIRE(out[3 * v] == out[3 * v + 1]);  // grey transfer, white light
    }
    CHECK(lit_count > 0);
    CHECK(lit_count < vertices);
  }
}

TEST_CASE("Shading rejects mismatched lighting", "[haar][relighter]") {
  const DenseScene scene = random_dense_scene(8, 1, 3, 1);
  const prt::HaarRelighter relighter(build_transfer(scene, prt::HaarTransferOptions{}));
  std::vector<float> out(9, 5.0f);
  prt::SparseLighting wrong;
  wrong.size = 16;
  CHECK_FALSE(relighter.shade(wrong, out.data()).ok());
  CHECK(out == std::vector<float>(9, 0.0f));
  prt::SparseLighting bad_index;
  bad_index.size = 8;
  bad_index.index = {384};
  bad_index.rgb = {1, 1, 1};
  CHECK_FALSE(relighter.shade(bad_index, out.data()).ok());
}

namespace {

// Random sparse wavelet-domain transfer with every kind of slice the blocked layout meets:
// indices every vertex keeps (i mod 48 < 3: dense columns), indices 95% / 60% of vertices keep
// (dense or sparse depending on dense_fraction and the block), 5% elsewhere, and every 101st
// vertex empty (step 0). Per-vertex scales span 10^±2 so the quantisation steps differ.
// Returns the transfer and, in `dense_wavelet`, the dequantised coefficients the transfer
// really holds (vertex-major, 6N²·channels), for an independent reference.
prt::HaarTransfer random_sparse_transfer(int n, int channels, int64_t vertices,
                                         prt::HaarQuantization q, uint32_t seed,
                                         std::vector<float>* dense_wavelet) {
  const uint32_t count = 6u * n * n;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), sym(-1.0f, 1.0f), expo(-2.0f, 2.0f);
  prt::HaarTransferBuilder builder(n, channels, q);
  for (int64_t v = 0; v < vertices; ++v) {
    prt::SparseVertexTransfer sv;
    const float scale = std::pow(10.0f, expo(rng));
    for (uint32_t i = 0; i < count && v % 101 != 0; ++i) {
      const uint32_t kind = i % 48;
      const float keep = kind < 3 ? 1.0f : kind == 5 ? 0.95f : kind == 7 ? 0.6f : 0.05f;
      if (unit(rng) >= keep) continue;
      sv.index.push_back(i);
      for (int c = 0; c < channels; ++c) sv.values.push_back(scale * sym(rng));
    }
    REQUIRE(builder.add_vertex(sv).ok());
  }
  prt::Result<prt::HaarTransfer> t = builder.finish();
  REQUIRE(t.ok());
  dense_wavelet->assign(static_cast<size_t>(vertices) * count * channels, 0.0f);
  for (uint32_t i = 0; i < count; ++i)
    for (uint64_t e = t->offsets[i]; e < t->offsets[i + 1]; ++e)
      for (int c = 0; c < channels; ++c)
        (*dense_wavelet)[(static_cast<size_t>(t->vertices[e]) * count + i) * channels + c] =
            t->dequantized_value(e, c);
  return std::move(*t);
}

}  // namespace

TEST_CASE("The blocked relighter equals the list walk and the dense reference",
          "[haar][relighter]") {
  // 2053 vertices: not a multiple of any block size below (2053 = 293·7 + 2 = 32·64 + 5 =
  // 2·1024 + 5), so every layout has a short last block.
  const int n = 8;
  const int64_t vertices = 2053;
  const size_t count = 6 * n * n;
  // Lighting: random sky plus a one-texel sun, K = 60 non-linear terms, and one term forced to
  // zero (the relighter skips those).
  prt::CubeMap sky = random_lighting(n, 11);
  sky.rgb[3 * 100] = sky.rgb[3 * 100 + 1] = sky.rgb[3 * 100 + 2] = 3000.0f;
  prt::SparseLighting lighting = prt::select_nonlinear(*prt::transform_cube(sky), 60);
  REQUIRE(lighting.term_count() == 60);
  lighting.rgb[3 * 7] = lighting.rgb[3 * 7 + 1] = lighting.rgb[3 * 7 + 2] = 0.0f;
  // The texel-domain lighting these K terms stand for (for shade_dense_reference).
  prt::WaveletCube kept{n, std::vector<float>(3 * count, 0.0f)};
  for (size_t k = 0; k < lighting.term_count(); ++k)
    for (int c = 0; c < 3; ++c) kept.rgb[3 * lighting.index[k] + c] = lighting.rgb[3 * k + c];
  const prt::CubeMap kept_texels = *prt::inverse_transform_cube(kept);

  for (int channels : {1, 3}) {
    for (prt::HaarQuantization q : {prt::HaarQuantization::Float32, prt::HaarQuantization::Bits16,
                                    prt::HaarQuantization::Bits8}) {
      std::vector<float> wavelet;
      const prt::HaarTransfer transfer =
          random_sparse_transfer(n, channels, vertices, q, 40 + channels, &wavelet);
      // Independent reference: the dequantised transfer back in the texel domain, summed in
      // double against the texel-domain lighting.
      std::vector<float> texels = wavelet;
      for (int64_t v = 0; v < vertices; ++v)
        for (int face = 0; face < 6; ++face)
          for (int c = 0; c < channels; ++c)
            prt::inverse_haar_2d(texels.data() + (v * count + face * n * n) * channels + c, n,
                                 channels);
      std::vector<double> reference(3 * vertices);
      REQUIRE(prt::shade_dense_reference(texels.data(), vertices, n, channels, kept_texels,
                                         reference.data())
                  .ok());
      // Per-vertex magnitude scale Σ_k |T̂_v,k|·|L̂_k| (double) for the tolerances.
      std::vector<double> scale(3 * vertices, 0.0);
      for (int64_t v = 0; v < vertices; ++v)
        for (size_t k = 0; k < lighting.term_count(); ++k)
          for (int c = 0; c < 3; ++c)
            scale[3 * v + c] += std::fabs(
                double(
                    wavelet[(v * count + lighting.index[k]) * channels + (channels == 1 ? 0 : c)]) *
                double(lighting.rgb[3 * k + c]));
      std::vector<float> lists(3 * vertices);
      REQUIRE(prt::shade_index_lists(transfer, lighting, lists.data()).ok());

      for (int block : {1, 7, 64, 1024, 65536}) {
        for (double dense : {0.0, 0.5, 0.9, 2.0}) {
          const prt::HaarRelighter relighter(transfer, prt::HaarRelighterLayout{block, dense});
          // The data really exercises both paths: fraction 2 never stores a dense column,
          // fraction ≤ 0.9 always does (the i mod 48 < 3 columns are full), and fraction 0
          // stores every non-empty slice densely.
          if (dense > 1.0) {
            REQUIRE(relighter.dense_slice_count() == 0);
          } else {
            REQUIRE(relighter.dense_slice_count() > 0);
          }
          std::vector<float> fast(3 * vertices, -1.0f);
          REQUIRE(relighter.shade(lighting, fast.data()).ok());
          for (int64_t j = 0; j < 3 * vertices; ++j) {
            INFO("channels " << channels << ", bits " << static_cast<int>(q) << ", block " << block
                             << ", dense fraction " << dense << ", value " << j);
            // Same products, same per-vertex order as the list walk: equal up to float
            // rounding (in practice bit for bit); 1e-6 of the magnitude scale allows a few
            // ulps of reassociation should a compiler fuse multiply-adds differently.
            REQUIRE(std::fabs(fast[j] - lists[j]) <= 1e-6 * scale[j]);
            // Against the double texel sum: the float sum of ≤ 60 terms (≤ 60·2⁻²⁴ ≈ 3.6e-6
            // of the scale) plus the float inverse transforms of transfer and lighting (three
            // levels at N = 8, a few 2⁻²⁴ each, relative to the same magnitudes): 2e-5 of the
            // scale leaves a margin of ~3.
            REQUIRE(std::fabs(fast[j] - reference[j]) <= 2e-5 * scale[j] + 1e-30);
          }
        }
      }
    }
  }
}

TEST_CASE("Shading refuses a transfer whose lists are inconsistent", "[haar][relighter]") {
  std::vector<float> wavelet;
  prt::HaarTransfer transfer =
      random_sparse_transfer(8, 3, 50, prt::HaarQuantization::Bits16, 3, &wavelet);
  REQUIRE(transfer.entry_count() > 0);
  transfer.vertices[0] = 50;  // out of range
  const prt::HaarRelighter relighter(transfer);
  prt::SparseLighting one;
  one.size = 8;
  one.index = {0};
  one.rgb = {1, 1, 1};
  std::vector<float> out(150, 5.0f);
  CHECK_FALSE(relighter.shade(one, out.data()).ok());
  CHECK(out == std::vector<float>(150, 0.0f));
}
