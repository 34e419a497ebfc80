// transfer_fixtures.h — random but valid TransferData for the prt tests.
#pragma once

#include <cstdint>
#include <random>
#include <string>

#include "prt/formats/geometry_check.h"
#include "prt/formats/transfer_data.h"

namespace prt::test {

// A TransferData with every section filled with reproducible random values.
inline TransferData make_transfer_data(uint64_t vertex_count, uint32_t order, uint32_t channels,
                                       Precision storage, uint32_t seed = 1,
                                       bool with_optional_sections = true) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  TransferData d;
  d.kind = TransferKind::Interreflected;
  d.order = order;
  d.channels = channels;
  d.storage = storage;
  d.albedo_folded = (seed % 2) == 1;
  d.vertex_count = vertex_count;
  const std::size_t v = static_cast<std::size_t>(vertex_count);
  d.positions.resize(3 * v);
  d.normals.resize(3 * v);
  for (float& x : d.positions) x = 10.0f * unit(rng);
  for (std::size_t i = 0; i < v; ++i) {
    d.normals[3 * i] = 0.0f;
    d.normals[3 * i + 1] = 1.0f;
    d.normals[3 * i + 2] = 0.0f;
  }
  d.coefficients.resize(v * channels * order * order);
  for (float& x : d.coefficients) x = unit(rng);
  if (with_optional_sections) {
    d.ao.resize(v);
    for (float& x : d.ao) x = 0.5f + 0.5f * unit(rng);
    d.bent_normals = d.normals;
    d.primitives.push_back({0, v / 2, "floor"});
    d.primitives.push_back({v / 2, v - v / 2, "статуя \xf0\x9f\x97\xbf"});  // UTF-8
    d.primitives.push_back({0, 0, ""});
    d.metadata_json = R"({"rays": 256, "bounces": 2, "sh": "real, no Condon-Shortley"})";
  }
  d.fingerprint = geometry_fingerprint(d.positions.data(), v);
  return d;
}

}  // namespace prt::test
