// Tests of sparse, quantised Haar transfer (prt/haar/transfer.h).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/haar/transfer.h"
#include "prt/haar/transform.h"

namespace {

// A random sparse vertex with magnitudes spanning several decades (as real transfer does).
prt::SparseVertexTransfer random_sparse_vertex(int n, int channels, std::mt19937& rng) {
  prt::SparseVertexTransfer v;
  const uint32_t total = 6u * n * n;
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (uint32_t i = 0; i < total; ++i) {
    if (unit(rng) > 0.1) continue;
    v.index.push_back(i);
    for (int c = 0; c < channels; ++c) {
      const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
      v.values.push_back(static_cast<float>(sign * std::pow(10.0, -4.0 * unit(rng))));
    }
  }
  return v;
}

}  // namespace

TEST_CASE("Quantisation error stays within the stated bound (8 and 16 bits)", "[haar][transfer]") {
  for (prt::HaarQuantization q : {prt::HaarQuantization::Bits8, prt::HaarQuantization::Bits16,
                                  prt::HaarQuantization::Float32}) {
    for (int channels : {1, 3}) {
      const int n = 8;
      std::mt19937 rng(17 + channels);
      std::vector<prt::SparseVertexTransfer> input;
      prt::HaarTransferBuilder builder(n, channels, q);
      for (int v = 0; v < 40; ++v) {
        input.push_back(random_sparse_vertex(n, channels, rng));
        REQUIRE(builder.add_vertex(input.back()).ok());
      }
      const prt::Result<prt::HaarTransfer> t = builder.finish();
      REQUIRE(t.ok());
      // Walk the structure back to (vertex, index) → value and compare with the input.
      std::vector<double> worst_ratio(input.size(), 0.0);
      uint64_t seen = 0;
      for (uint32_t i = 0; i + 1 < t->offsets.size(); ++i) {
        for (uint64_t e = t->offsets[i]; e < t->offsets[i + 1]; ++e) {
          const uint32_t v = t->vertices[e];
          if (e > t->offsets[i]) REQUIRE(t->vertices[e - 1] < v);  // ascending per list
          const auto& in = input[v];
          const auto it = std::lower_bound(in.index.begin(), in.index.end(), i);
          REQUIRE((it != in.index.end() && *it == i));
          const size_t k = static_cast<size_t>(it - in.index.begin());
          double m = 0.0;
          for (float x : in.values) m = std::max(m, static_cast<double>(std::fabs(x)));
          const double bound = prt::haar_quantization_error_bound(q, m);
          for (int c = 0; c < channels; ++c) {
            const double err = std::fabs(t->dequantized_value(e, c) - in.values[k * channels + c]);
            INFO("bits " << static_cast<int>(q) << ", vertex " << v << ", index " << i);
            if (q == prt::HaarQuantization::Float32) {
              REQUIRE(err == 0.0);
            } else {
              REQUIRE(err <= bound);
              worst_ratio[v] = std::max(worst_ratio[v], err / bound);
            }
          }
          ++seen;
        }
      }
      size_t expected_entries = 0;
      for (const auto& in : input) expected_entries += in.index.size();
      CHECK(seen == expected_entries);
      if (q != prt::HaarQuantization::Float32) {
        // The bound is tight: with hundreds of uniformly spread values per vertex the worst
        // error reaches most of step/2 (shows the values really were quantised).
        for (double r : worst_ratio) CHECK(r > 0.5);
      }
      CHECK(t->stored_bytes() < t->dense_bytes());
    }
  }
}

TEST_CASE("Truncation keeps terms above the relative threshold, then the top M",
          "[haar][transfer]") {
  const int n = 8, channels = 3;
  const size_t total = 6 * n * n;
  std::mt19937 rng(2);
  std::normal_distribution<float> dist(0.0f, 1.0f);
  std::vector<float> coeffs(total * channels);
  for (float& v : coeffs) v = dist(rng);
  for (size_t i = 0; i < total; i += 7)
    coeffs[i * channels] = coeffs[i * channels + 1] = coeffs[i * channels + 2] =
        0.0f;  // exact zeros
  std::vector<float> magnitude(total);
  float largest = 0.0f;
  for (size_t i = 0; i < total; ++i) {
    magnitude[i] = std::max(
        {std::fabs(coeffs[3 * i]), std::fabs(coeffs[3 * i + 1]), std::fabs(coeffs[3 * i + 2])});
    largest = std::max(largest, magnitude[i]);
  }
  prt::HaarTransferOptions options;
  options.relative_threshold = 0.3;
  const prt::SparseVertexTransfer a =
      prt::truncate_vertex_coefficients(coeffs.data(), n, 3, options);
  std::vector<uint32_t> expected;
  for (size_t i = 0; i < total; ++i)
    if (magnitude[i] > 0 && magnitude[i] >= 0.3 * largest)
      expected.push_back(static_cast<uint32_t>(i));
  CHECK(a.index == expected);
  for (size_t k = 0; k < a.index.size(); ++k)
    for (int c = 0; c < 3; ++c) CHECK(a.values[3 * k + c] == coeffs[3 * a.index[k] + c]);

  options.relative_threshold = 0.0;
  options.max_terms_per_vertex = 25;
  const prt::SparseVertexTransfer b =
      prt::truncate_vertex_coefficients(coeffs.data(), n, 3, options);
  std::vector<uint32_t> order(total);
  std::iota(order.begin(), order.end(), 0u);
  std::sort(order.begin(), order.end(), [&](uint32_t x, uint32_t y) {
    return magnitude[x] != magnitude[y] ? magnitude[x] > magnitude[y] : x < y;
  });
  order.resize(25);
  std::sort(order.begin(), order.end());
  CHECK(b.index == order);

  // No threshold, no limit: every non-zero term (the exact zeros are not stored).
  options.max_terms_per_vertex = 0;
  const prt::SparseVertexTransfer c =
      prt::truncate_vertex_coefficients(coeffs.data(), n, 3, options);
  CHECK(c.index.size() == total - (total + 6) / 7);
}

TEST_CASE("Compressing a dense vertex without truncation keeps it exactly", "[haar][transfer]") {
  const int n = 8;
  const size_t texels = 6 * n * n;
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> dist(0.0f, 1e-2f);
  std::vector<float> dense(texels);
  for (float& v : dense) v = dist(rng);
  dense[5] = std::numeric_limits<float>::quiet_NaN();
  prt::HaarTransferOptions options;
  options.quantization = prt::HaarQuantization::Float32;
  const prt::Result<prt::SparseVertexTransfer> s =
      prt::compress_vertex_transfer(dense.data(), n, 1, options);
  REQUIRE(s.ok());
  CHECK(s->nonfinite_count == 1);
  dense[5] = 0.0f;  // what the NaN became
  // Scatter back into a full coefficient vector and invert face by face.
  std::vector<float> coeffs(texels, 0.0f);
  for (size_t k = 0; k < s->index.size(); ++k) coeffs[s->index[k]] = s->values[k];
  for (int f = 0; f < 6; ++f) prt::inverse_haar_2d(coeffs.data() + f * n * n, n);
  for (size_t t = 0; t < texels; ++t) {
    // Round trip of a float Haar transform: N ulps of the largest value (see test_haar_transform).
    REQUIRE(std::fabs(coeffs[t] - dense[t]) <= n * std::ldexp(1e-2, -23));
  }
  CHECK_FALSE(prt::compress_vertex_transfer(dense.data(), 12, 1, options).ok());
  CHECK_FALSE(prt::compress_vertex_transfer(dense.data(), n, 2, options).ok());
}

TEST_CASE("The builder rejects malformed vertices", "[haar][transfer]") {
  prt::HaarTransferBuilder builder(8, 1, prt::HaarQuantization::Bits16);
  prt::SparseVertexTransfer v;
  v.index = {3, 2};
  v.values = {1.0f, 2.0f};
  CHECK_FALSE(builder.add_vertex(v).ok());  // not ascending
  v.index = {2, 384};
  CHECK_FALSE(builder.add_vertex(v).ok());  // out of range (6·8² = 384)
  v.index = {2};
  CHECK_FALSE(builder.add_vertex(v).ok());  // value count mismatch
  v.values = {1.0f};
  CHECK(builder.add_vertex(v).ok());
  const prt::Result<prt::HaarTransfer> t = builder.finish();
  REQUIRE(t.ok());
  CHECK(t->vertex_count == 1);
  CHECK(t->entry_count() == 1);
  CHECK(t->dequantized_value(0, 0) == Approx(1.0f).epsilon(1e-6));
  prt::HaarTransferBuilder bad(12, 1, prt::HaarQuantization::Bits16);
  CHECK_FALSE(bad.add_vertex(v).ok());
  CHECK_FALSE(bad.finish().ok());
}
