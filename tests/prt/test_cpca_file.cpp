// tests/prt/test_cpca_file.cpp — the .prtq format's versions (prt/formats/cpca_file.h): version 2
// carries the compression record, version-1 files (no record) still read, and a record flag in a
// version-1 header or a record that does not fit the file is refused.
#include <cstring>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/formats/cpca_file.h"
#include "prt/formats/crc32c.h"
#include "prt/formats/geometry_check.h"

namespace {

// A CPCA of 3 vertices at order 1 (D = 1), one cluster, one vector, and its source.
void tiny(prt::CpcaTransfer* t, prt::GlossyTransferData* source) {
  t->order = 1;
  t->channels = 1;
  t->cluster_count = 1;
  t->vector_count = 1;
  t->vertex_count = 3;
  t->means = {0.5f};
  t->basis = {1.f};
  t->cluster_of_vertex = {0, 0, 0};
  t->weights = {0.1f, -0.2f, 0.3f};
  source->order = 1;
  source->channels = 1;
  source->vertex_count = 3;
  source->positions = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  source->normals = {0, 0, 1, 0, 0, 1, 0, 0, 1};
  source->tangents = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
  source->materials = {prt::brdf::Material{}};
  source->material_of_vertex = {0, 0, 0};
  source->metadata_json = "{\"generator\":\"test\"}";
  source->primitives = {{0, 3, "all"}};
  source->matrices.assign(3, 0.f);
  source->fingerprint = prt::geometry_fingerprint(source->positions.data(), 3);
  t->fingerprint = source->fingerprint;
}

uint32_t u32(const std::vector<unsigned char>& b, std::size_t at) {
  uint32_t v;
  std::memcpy(&v, &b[at], 4);
  return v;
}

// Sets a u32 field and recomputes the checksum (offset 56, taken as zero).
void patch(std::vector<unsigned char>* b, std::size_t at, uint32_t value) {
  std::memcpy(&(*b)[at], &value, 4);
  std::memset(&(*b)[56], 0, 4);
  const uint32_t crc = prt::crc32c(b->data(), b->size());
  std::memcpy(&(*b)[56], &crc, 4);
}

}  // namespace

TEST_CASE("cpca file: version 2 keeps the compression record, version 1 still reads") {
  prt::CpcaTransfer t;
  prt::GlossyTransferData source;
  tiny(&t, &source);
  const std::string record = "{\"metric\":\"relit\",\"metric_relative_rms_error\":0.0125}";
  auto with = prt::encode_cpca_file(t, source, record);
  REQUIRE(with.ok());
  CHECK(u32(*with, 4) == 2);
  CHECK(u32(*with, 28) == (prt::kCpcaFlagSource | prt::kCpcaFlagRecord));
  auto read = prt::decode_cpca_file_with_source(with->data(), with->size(), "with.prtq");
  INFO(read.status().message());
  REQUIRE(read.ok());
  CHECK(read->record_json == record);
  CHECK(read->has_source);
  CHECK(read->source.metadata_json == source.metadata_json);
  CHECK(read->cpca.weights == t.weights);

  // A file as version 1 wrote it: no record, version 1 in the header.
  auto old = prt::encode_cpca_file(t, source);
  REQUIRE(old.ok());
  CHECK(u32(*old, 28) == prt::kCpcaFlagSource);
  patch(&*old, 4, 1);
  auto old_read = prt::decode_cpca_file_with_source(old->data(), old->size(), "old.prtq");
  INFO(old_read.status().message());
  REQUIRE(old_read.ok());
  CHECK(old_read->record_json.empty());
  CHECK(old_read->has_source);

  // The record flag is not a version-1 flag; a version this reader does not know is refused.
  std::vector<unsigned char> v1_record = *with;
  patch(&v1_record, 4, 1);
  auto refused = prt::decode_cpca_file_with_source(v1_record.data(), v1_record.size(), "x.prtq");
  REQUIRE_FALSE(refused.ok());
  CHECK(refused.status().message().find("x.prtq: inconsistent CPCA header") == 0);
  std::vector<unsigned char> v3 = *with;
  patch(&v3, 4, 3);
  auto future = prt::decode_cpca_file_with_source(v3.data(), v3.size(), "x.prtq");
  REQUIRE_FALSE(future.ok());
  CHECK(future.status().message().find("unsupported CPCA file version 3") != std::string::npos);
  // A record size that runs past the end.
  std::vector<unsigned char> long_record = *with;
  const std::size_t at = long_record.size() - record.size() - 8;
  patch(&long_record, at, uint32_t(record.size() + 1));
  auto overrun = prt::decode_cpca_file_with_source(long_record.data(), long_record.size(), "x");
  CHECK_FALSE(overrun.ok());
}
