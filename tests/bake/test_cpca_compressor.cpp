// Tests of prt/glossy/cpca_transfer.h: exact reconstruction at full rank, error monotone in vectors
// and clusters, target-error selection, determinism across thread counts, refused input. The
// matrices are fixtures/synthetic_glossy.h's (shadowed transfer of a small analytic scene, rotated
// into each vertex's tangent frame).
#include <cmath>
#include <vector>

#include <catch2/catch.hpp>

#include "bake/cpca/compressor.h"
#include "bake/cpca/matrix_source.h"
#include "bake/cpca/relit_metric.h"
#include "fixtures/synthetic_glossy.h"
#include "prt/formats/cpca_file.h"
#include "prt/formats/geometry_check.h"
#include "prt/formats/glossy_transfer_file.h"
#include "support/test_data.h"

using prt::CpcaOptions;
using prt::CpcaTransfer;
using prt::GlossyTransferData;

namespace {

const GlossyTransferData& data_order5() {
  static const GlossyTransferData d = prt::fixtures::synthetic_glossy(600, 5, 1, 512);
  return d;
}

CpcaTransfer compress(const GlossyTransferData& d, const CpcaOptions& o) {
  auto r = prt::cpca_compress(d, o);
  INFO((r.ok() ? std::string() : r.status().message()));
  REQUIRE(r.ok());
  return std::move(r).value();
}

// Largest |x − x̃| over all entries, relative to the largest |x|.
double max_relative_entry_error(const CpcaTransfer& t, const GlossyTransferData& d) {
  const std::size_t dim = t.dimension();
  std::vector<double> r(dim);
  double worst = 0, scale = 0;
  for (std::size_t v = 0; v < d.vertex_count; ++v) {
    prt::cpca_reconstruct(t, v, r.data());
    for (std::size_t e = 0; e < dim; ++e) {
      worst = std::max(worst, std::abs(r[e] - d.matrices[v * dim + e]));
      scale = std::max(scale, std::abs(double(d.matrices[v * dim + e])));
    }
  }
  return worst / scale;
}

}  // namespace

TEST_CASE("CPCA with as many vectors as dimensions reconstructs to float rounding", "[cpca]") {
  // Order 2: D = 16 (grey) or 48 (RGB); K = D spans everything. Float rounding of the basis,
  // mean and weights leaves ~sqrt(D)·2^-24 relative per entry; 1e-5 allows 10x that and
  // more, and is far below the truncation error of fewer vectors (K = 3 below: > 1e-3).
  for (int channels : {1, 3}) {
    const GlossyTransferData d = prt::fixtures::synthetic_glossy(300, 2, channels, 256);
    CpcaOptions o;
    o.clusters = 5;
    o.vectors = 16 * channels;
    const CpcaTransfer t = compress(d, o);
    CHECK(max_relative_entry_error(t, d) < 1e-5);
    CHECK(prt::cpca_relative_rms_error(t, d.matrices.data()) < 1e-6);
    CHECK(prt::cpca_relative_rms_error_truncated(t, d.matrices.data(), 3) > 1e-3);
  }
}

TEST_CASE("CPCA with K at least the cluster size reconstructs exactly at order 5", "[cpca]") {
  // 40 vertices in 4 clusters, K = 40 ≥ every cluster's size: each cluster's members lie in
  // mean + span of its vectors (D = 625 > K: the Gram side of the subspace iteration).
  const GlossyTransferData d = prt::fixtures::synthetic_glossy(40, 5, 1, 256);
  CpcaOptions o;
  o.clusters = 4;
  o.vectors = 40;
  const CpcaTransfer t = compress(d, o);
  CHECK(max_relative_entry_error(t, d) < 1e-5);
}

TEST_CASE("CPCA error falls with more vectors and more clusters", "[cpca]") {
  const GlossyTransferData& d = data_order5();
  CpcaOptions o;
  o.clusters = 8;
  double previous = INFINITY, means_only = 0;
  for (uint32_t k : {0u, 1u, 2u, 4u, 8u, 16u}) {
    o.vectors = k;
    const double e = prt::cpca_relative_rms_error(compress(d, o), d.matrices.data());
    INFO("K = " << k << ": " << e);
    CHECK(e < previous);
    previous = e;
    if (k == 0) means_only = e;
  }
  // 16 vectors remove most of what the 8 cluster means leave (measured: 0.57 -> 0.085).
  CHECK(previous < 0.2 * means_only);
  o.vectors = 4;
  previous = INFINITY;
  for (uint32_t q : {1u, 2u, 4u, 8u, 16u, 32u}) {
    o.clusters = q;
    const double e = prt::cpca_relative_rms_error(compress(d, o), d.matrices.data());
    INFO("clusters = " << q << ": " << e);
    CHECK(e < previous);
    previous = e;
  }
  // Truncations of one result are nested subspaces: never worse with one more vector.
  o.clusters = 8;
  o.vectors = 12;
  const CpcaTransfer t = compress(d, o);
  for (uint32_t k = 1; k <= 12; ++k) {
    CHECK(prt::cpca_relative_rms_error_truncated(t, d.matrices.data(), k) <=
          prt::cpca_relative_rms_error_truncated(t, d.matrices.data(), k - 1));
  }
}

TEST_CASE("CPCA target-error selection meets its target with few vectors", "[cpca]") {
  const GlossyTransferData& d = data_order5();
  for (double target : {0.3, 0.15, 0.1}) {
    CpcaOptions o;
    o.clusters = 8;
    o.target_relative_rms = target;
    o.max_vectors = 24;
    const CpcaTransfer t = compress(d, o);
    const double e = prt::cpca_relative_rms_error(t, d.matrices.data());
    INFO("target " << target << ": K = " << t.vector_count << ", error " << e);
    CHECK(e <= target);
    CHECK(t.vector_count <= 24);
    // K is the smallest count whose truncation of the max_vectors clustering meets the target:
    // that clustering (the same run, deterministic for a seed) truncated to K − 1 misses it.
    if (t.vector_count > 0) {
      o.target_relative_rms = 0;
      o.vectors = o.max_vectors;
      const CpcaTransfer full = compress(d, o);
      CHECK(prt::cpca_relative_rms_error_truncated(full, d.matrices.data(), t.vector_count - 1) >
            target);
      // A run clustered for K − 1 vectors can do better than that truncation, but not by much:
      // measured 14% and 13% below the targets 0.3 and 0.1 (seed 1); the margin varies by seed.
      o.vectors = t.vector_count - 1;
      CHECK(prt::cpca_relative_rms_error(compress(d, o), d.matrices.data()) > target * 0.8);
    }
  }
  CpcaOptions o;
  o.clusters = 2;
  o.target_relative_rms = 1e-9;
  o.max_vectors = 2;
  auto r = prt::cpca_compress(d, o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status().message().find("not reached") != std::string::npos);
}

TEST_CASE("CPCA is identical for any thread count", "[cpca]") {
  const GlossyTransferData& d = data_order5();
  CpcaOptions o;
  o.clusters = 12;
  o.vectors = 6;
  o.threads = 1;
  const CpcaTransfer one = compress(d, o);
  for (unsigned threads : {2u, 3u, 8u}) {
    o.threads = threads;
    const CpcaTransfer many = compress(d, o);
    CHECK(many.cluster_of_vertex == one.cluster_of_vertex);
    CHECK(many.means == one.means);
    CHECK(many.basis == one.basis);
    CHECK(many.weights == one.weights);
  }
  o.seed = 2;  // a different seed is allowed to (and here does) cluster differently
  o.threads = 1;
  CHECK(compress(d, o).cluster_of_vertex != one.cluster_of_vertex);
}

TEST_CASE("CPCA refuses bad input with a one-line message", "[cpca]") {
  GlossyTransferData d = prt::fixtures::synthetic_glossy(20, 2, 1, 64);
  CpcaOptions o;
  o.clusters = 3;
  o.vectors = 2;
  d.matrices[37] = NAN;
  auto r = prt::cpca_compress(d, o);
  REQUIRE_FALSE(r.ok());
  CHECK(r.status().message() == "cpca: matrix entry 5 of vertex 2 is not finite");
  d.matrices[37] = 0;
  d.channels = 2;
  CHECK_FALSE(prt::cpca_compress(d, o).ok());
  d.channels = 1;
  o.clusters = 0;
  CHECK_FALSE(prt::cpca_compress(d, o).ok());
  o.clusters = 50;  // more clusters than vertices: clamped to 20
  auto clamped = prt::cpca_compress(d, o);
  REQUIRE(clamped.ok());
  CHECK(clamped->cluster_count == 20);
  CHECK(prt::cpca_relative_rms_error(*clamped, d.matrices.data()) < 1e-6);
  CpcaTransfer bad = *clamped;
  bad.cluster_of_vertex[3] = 20;
  CHECK(prt::cpca_validate(bad).message() ==
        "cpca: vertex 3 has cluster id 20 beyond the 20 clusters");
}

TEST_CASE("CPCA file: round trip, size, and refused damage", "[cpca]") {
  GlossyTransferData d = prt::fixtures::synthetic_glossy(50, 3, 3, 64);
  d.fingerprint = 0x1234567890abcdefull;
  CpcaOptions o;
  o.clusters = 4;
  o.vectors = 3;
  const CpcaTransfer t = compress(d, o);
  CHECK(t.fingerprint == d.fingerprint);
  auto bytes = prt::encode_cpca_file(t);
  REQUIRE(bytes.ok());
  // 64 header + 4·4·(3+1)·243 + ids 2·50 = 100 + weights 4·50·3.
  CHECK(bytes->size() == 64 + 4 * 4 * 4 * 243 + 100 + 600);
  CHECK(bytes->size() == t.payload_bytes());
  const std::string path = prt::test::output_path("cpca_round_trip.prtq").string();
  REQUIRE(prt::write_cpca_file(path, t).ok());
  auto back = prt::read_cpca_file(path);
  REQUIRE(back.ok());
  CHECK(back->means == t.means);
  CHECK(back->basis == t.basis);
  CHECK(back->weights == t.weights);
  CHECK(back->cluster_of_vertex == t.cluster_of_vertex);
  CHECK(back->fingerprint == t.fingerprint);
  CHECK((back->order == 3 && back->channels == 3 && back->vector_count == 3));
  std::vector<unsigned char> bad = *bytes;
  bad[700] ^= 1;
  CHECK(prt::decode_cpca_file(bad.data(), bad.size(), "x.prtq").status().message() ==
        "x.prtq: checksum mismatch (the file is corrupt)");
  CHECK(prt::decode_cpca_file(bytes->data(), bytes->size() - 4, "x.prtq").status().message() ==
        "x.prtq: file size " + std::to_string(bytes->size() - 4) + " differs from the " +
            std::to_string(bytes->size()) + " bytes the header records (truncated?)");
  CHECK(prt::decode_cpca_file("PRTC", 4, "y").status().message() ==
        "y: not a CPCA transfer file (no PRCP header)");
  CHECK_FALSE(prt::read_cpca_file(prt::test::output_path("missing.prtq").string()).ok());
}

TEST_CASE("CPCA file with a source section: geometry and materials round trip", "[cpca]") {
  // The source section carries what the glossy file had besides its matrices, so that the
  // .prtq relights on its own; everything must come back as written, and the section must
  // agree with the CPCA header.
  GlossyTransferData d = prt::fixtures::synthetic_glossy(90, 3, 1, 128);
  d.materials.resize(2);
  d.materials[1].model = prt::brdf::MaterialModel::kWard;
  d.materials[1].specular = prt::brdf::grey(0.4);
  d.materials[1].alpha_x = 0.2;
  d.materials[1].alpha_y = 0.1;
  for (std::size_t v = 0; v < d.vertex_count; v += 2) d.material_of_vertex[v] = 1;
  d.primitives = {{0, 40, "a"}, {40, 50, "b"}};
  d.fingerprint = prt::geometry_fingerprint(d.positions.data(), d.vertex_count);
  d.metadata_json = "{\"bake\":\"test\"}";
  CpcaOptions o;
  o.clusters = 3;
  o.vectors = 4;
  const CpcaTransfer t = compress(d, o);
  auto plain = prt::encode_cpca_file(t);
  auto with = prt::encode_cpca_file(t, d);
  REQUIRE(plain.ok());
  REQUIRE(with.ok());
  CHECK(with->size() > plain->size() + 8);
  auto file = prt::decode_cpca_file_with_source(with->data(), with->size(), "s.prtq");
  INFO((file.ok() ? std::string() : file.status().message()));
  REQUIRE(file.ok());
  REQUIRE(file->has_source);
  const GlossyTransferData& s = file->source;
  CHECK(s.order == 3);
  CHECK(s.channels == 1);
  CHECK(s.matrices.empty());
  CHECK(s.positions == d.positions);
  CHECK(s.normals == d.normals);
  CHECK(s.tangents == d.tangents);
  CHECK(s.material_of_vertex == d.material_of_vertex);
  REQUIRE(s.materials.size() == 2);
  CHECK(s.materials[1].model == prt::brdf::MaterialModel::kWard);
  CHECK(s.materials[1].alpha_y == 0.1);
  REQUIRE(s.primitives.size() == 2);
  CHECK(s.primitives[1].name == "b");
  CHECK(s.metadata_json.find("test") != std::string::npos);
  CHECK(file->cpca.weights == t.weights);
  // The plain reader reads the CPCA of both; without a section there is no source.
  auto cpca_only = prt::decode_cpca_file(with->data(), with->size(), "s.prtq");
  REQUIRE(cpca_only.ok());
  CHECK(cpca_only->basis == t.basis);
  auto unsourced = prt::decode_cpca_file_with_source(plain->data(), plain->size(), "p.prtq");
  REQUIRE(unsourced.ok());
  CHECK_FALSE(unsourced->has_source);
  // A source of other geometry or another vertex count is refused when writing.
  GlossyTransferData moved = d;
  moved.positions[0] += 0.5f;
  moved.fingerprint = 0;
  CHECK_FALSE(prt::encode_cpca_file(t, moved).ok());
  GlossyTransferData fewer = prt::fixtures::synthetic_glossy(80, 3, 1, 128);
  CHECK_FALSE(prt::encode_cpca_file(t, fewer).ok());
  // A damaged section fails the file's checksum; a truncated one its size.
  std::vector<unsigned char> bad = *with;
  bad[bad.size() - 100] ^= 0x20;
  CHECK_FALSE(prt::decode_cpca_file_with_source(bad.data(), bad.size(), "s.prtq").ok());
  CHECK_FALSE(prt::decode_cpca_file_with_source(with->data(), with->size() - 8, "s.prtq").ok());
  // Through a file on disk.
  const std::string path = prt::test::output_path("cpca_source.prtq").string();
  REQUIRE(prt::write_cpca_file(path, t, d).ok());
  auto read = prt::read_cpca_file_with_source(path);
  REQUIRE(read.ok());
  CHECK(read->has_source);
  CHECK(read->source.positions == d.positions);
}

namespace {

void require_identical(const CpcaTransfer& a, const CpcaTransfer& b) {
  CHECK(a.cluster_count == b.cluster_count);
  CHECK(a.vector_count == b.vector_count);
  CHECK(a.cluster_of_vertex == b.cluster_of_vertex);
  CHECK(a.means == b.means);
  CHECK(a.basis == b.basis);
  CHECK(a.weights == b.weights);
}

}  // namespace

// Out of core: the file's matrices mapped (binary32) or expanded into a mapped scratch file
// (binary16: the expansion does not fit the limit), and a metric's scaled copy in a scratch
// file too, under a memory limit below the matrices' size: the clustering reads the same floats
// in the same order, so the result is bit-identical to the in-memory compression.
TEST_CASE("CPCA of a file under a memory limit below its matrices equals the in-memory one",
          "[cpca]") {
  GlossyTransferData d = prt::fixtures::synthetic_glossy(3000, 4, 3, 256);
  const uint64_t matrix_bytes = 4 * d.matrices.size();  // 9.2 MB
  const uint64_t limit = 6u << 20;
  REQUIRE(limit < matrix_bytes);
  for (const prt::Precision storage : {prt::Precision::F32, prt::Precision::F16}) {
    d.storage = storage;
    const std::string path = prt::test::output_path("cpca_out_of_core.prtg").string();
    REQUIRE(prt::write_glossy_transfer_file(path, d).ok());
    const auto whole = prt::read_glossy_transfer_file(path);
    REQUIRE(whole.ok());
    for (const bool metric : {false, true}) {
      CpcaOptions o;
      o.clusters = 12;
      o.vectors = 6;
      o.threads = 1;
      if (metric) {
        auto g = prt::cpca_relit_metric(whole.value());
        REQUIRE(g.ok());
        o.row_metric = std::move(g).value();
      }
      const CpcaTransfer in_memory = compress(whole.value(), o);
      o.memory_limit = limit;
      prt::MemoryBudget budget(limit, path);
      auto source = prt::GlossyMatrixSource::open(path, budget);
      INFO((source.ok() ? std::string() : source.status().message()));
      REQUIRE(source.ok());
      CHECK((*source)->data().matrices.empty());
      CHECK((*source)->mapped() == (storage == prt::Precision::F32));
      CHECK(budget.used() == 0);  // nothing of the matrices is held in memory
      auto out = prt::cpca_compress(d.order, d.channels, d.vertex_count, (*source)->matrices(), o);
      INFO((out.ok() ? std::string() : out.status().message()));
      REQUIRE(out.ok());
      INFO("storage " << int(storage) << ", metric " << metric);
      require_identical(out.value(), in_memory);
    }
  }
}

TEST_CASE("CPCA refuses a memory limit below its own buffers in one line", "[cpca]") {
  const GlossyTransferData& d = data_order5();
  CpcaOptions o;
  o.clusters = 8;
  o.vectors = 4;
  o.memory_limit = 16 * 1024;
  const auto r = prt::cpca_compress(d, o);
  REQUIRE_FALSE(r.ok());
  INFO(r.status().message());
  CHECK(r.status().message().find("the memory limit is 16.0 KB") != std::string::npos);
  CHECK(r.status().message().find('\n') == std::string::npos);
}
