// bake/haar_part.h — a Haar bake (bake/haar_baker.h) split across the machines of a farm, as
// the SH bake is (bake/transfer_part.h): the same rows (Morton order, shard i of N takes
// [⌊i·V/N⌋, ⌊(i+1)·V/N⌋)), the same determinism argument (a vertex's texel rays and their
// supersampling jitter depend on the seed and the texel only, so a shard computes the values the
// single bake computes for its vertices), the same scenes (textured scenes, whose albedo is kept
// apart, are refused).
//
// A part holds, per row: unshadowed and shadowed, the vertex's truncated wavelet vector (the
// indices and values compress_vertex_transfer gives, before quantisation); interreflected, its
// direct transfer in the wavelet domain D̂ (6N²·C floats, dense, as the single bake holds it
// before the solve) and its merged gather row of H. merge_haar_parts adds the vectors to the
// builder in vertex order, or assembles D̂ and H and runs the single bake's solve and truncation,
// so the file is the single bake's, byte for byte.
#pragma once

#include <cstdint>
#include <vector>

#include "bake/haar_baker.h"
#include "bake/transfer_part.h"

namespace prt::bake {

struct HaarPart {
  ShardSpec shard;
  uint64_t vertices = 0;
  RowRange rows;
  int channels = 1;  // C
  // Unshadowed, shadowed: per row, its wavelet count, then the indices and C values per index.
  std::vector<uint32_t> sparse_lengths, sparse_index;
  std::vector<float> sparse_values;
  // Interreflected: D̂ (rows × 6N² × C floats) and the merged gather rows of H.
  std::vector<float> wavelets;
  std::vector<uint32_t> gather_lengths, gather_columns;
  std::vector<float> gather_weights;
  uint64_t rays = 0;
  HaarBakeStatistics stats;  // of the shard's run (not part of the file)

  // A part read from a file (bake/transfer_part_file.h): the large arrays stay in the file's
  // mapping (these views; their vectors above empty), which the decoded part holds; the lengths
  // are copied. The merge copies each part's rows and then releases its pages
  // (prt::release_part_pages), so that it does not hold every part besides its own arrays.
  struct Mapped {
    const uint32_t* sparse_index = nullptr;
    const float* sparse_values = nullptr;
    const float* wavelets = nullptr;
    const uint32_t* gather_columns = nullptr;
    const float* gather_weights = nullptr;
    uint64_t entries = 0;   // sparse indices (sparse values: entries · channels)
    uint64_t texels = 0;    // wavelet values: rows · 6N² · channels
    uint64_t gathered = 0;  // gather columns and weights
  };
  bool mapped = false;
  Mapped view;

  // The arrays, wherever they are (the vectors, or the views of a read part).
  const uint32_t* index_data() const { return mapped ? view.sparse_index : sparse_index.data(); }
  uint64_t index_size() const { return mapped ? view.entries : sparse_index.size(); }
  const float* values_data() const { return mapped ? view.sparse_values : sparse_values.data(); }
  uint64_t values_size() const { return mapped ? view.entries * channels : sparse_values.size(); }
  const float* wavelet_data() const { return mapped ? view.wavelets : wavelets.data(); }
  uint64_t wavelet_size() const { return mapped ? view.texels : wavelets.size(); }
  const uint32_t* column_data() const {
    return mapped ? view.gather_columns : gather_columns.data();
  }
  const float* weight_data() const { return mapped ? view.gather_weights : gather_weights.data(); }
  uint64_t column_size() const { return mapped ? view.gathered : gather_columns.size(); }
  uint64_t weight_size() const { return mapped ? view.gathered : gather_weights.size(); }
};

// Releases the pages of a read part's views (prt::release_part_pages); nothing for a part in
// memory. Its values stay readable (read again from the file).
void release_haar_part_pages(const HaarPart& part);

// Throws BakeError when the Haar bake cannot be sharded (a textured scene).
void check_haar_shardable(const scene::Scene& scene, const HaarBakeOptions& options);

HaarPart bake_haar_part(const scene::Scene& scene, const HaarBakeOptions& options, ShardSpec shard,
                        ProgressSink* progress = nullptr);

// The single Haar bake's result from every part of one split, in shard order (checked as
// merge_transfer_parts checks its parts). Throws BakeError when they do not fit. The pages of a
// part read from a file are released once its rows are checked and again once copied.
HaarBakeResult merge_haar_parts(const scene::Scene& scene, const HaarBakeOptions& options,
                                const std::vector<const HaarPart*>& parts,
                                ProgressSink* progress = nullptr);

}  // namespace prt::bake
