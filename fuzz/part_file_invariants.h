// fuzz/part_file_invariants.h — what every part read_part_file accepts (prt/formats/part_file.h)
// and every part decode_transfer_part decodes (bake/transfer_part_file.h) must satisfy: the
// header's shard and row range are consistent, every section lies inside the file's mapping,
// aligned, with a unique tag; a decoded part's arrays have the sizes its rows and settings give
// (counted exactly, without wrapping), its hits and gather entries add up to their lengths, its
// views point into the mapping, and the scene or inputs of shard 0 index only their own vertices
// and materials. The merges (merge_transfer_parts, merge_haar_parts, merge_glossy_parts_to_file)
// index by these. A violation aborts (a finding for the fuzzer).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <numeric>
#include <vector>

#include "bake/transfer_part_file.h"
#include "prt/formats/part_file.h"

namespace prt::fuzz {

using Exact = unsigned __int128;  // products of 64-bit counts, which must not wrap

inline bool inside(const void* p, Exact bytes, const unsigned char* begin, std::size_t size) {
  if (bytes == 0) return true;
  const unsigned char* b = static_cast<const unsigned char*>(p);
  return b >= begin && b <= begin + size && bytes <= Exact(begin + size - b);
}

inline void check_part_invariants(const prt::PartFile& f, std::size_t file_size) {
  if (f.count == 0 || f.index >= f.count) std::abort();
  if (f.first_row > f.total_rows || f.row_count > f.total_rows - f.first_row) std::abort();
  const auto* begin = static_cast<const unsigned char*>(f.mapping.get());
  if (begin == nullptr || f.sections.size() > 64) std::abort();
  for (std::size_t s = 0; s < f.sections.size(); ++s) {
    const prt::PartSection& section = f.sections[s];
    if (!inside(section.data(), section.size(), begin, file_size)) std::abort();
    if (section.size() > 0 && (section.data() - begin) % 16 != 0) std::abort();
    for (std::size_t t = 0; t < s; ++t)
      if (f.sections[t].tag == section.tag) std::abort();
  }
}

template <class T>
Exact sum_of(const std::vector<T>& v) {
  Exact s = 0;
  for (T x : v) s += x;
  return s;
}

inline void check_scene(const prt::scene::Scene& scene, uint64_t vertices) {
  if (scene.positions.size() != vertices || scene.normals.size() != vertices ||
      scene.albedo.size() != vertices)
    std::abort();
  for (const glm::uvec3& t : scene.triangles)
    if (t.x >= vertices || t.y >= vertices || t.z >= vertices) std::abort();
  for (const prt::scene::ScenePrimitive& p : scene.primitives)
    if (Exact(p.first_vertex) + p.vertex_count > vertices) std::abort();
}

inline void check_sh_part(const prt::bake::TransferPartFile& d, const unsigned char* begin,
                          std::size_t size) {
  const prt::bake::TransferPart& p = d.part;
  const Exact n = p.rows.size(), k = Exact(d.options.order) * d.options.order;
  const bool sh = d.options.kind != prt::TransferKind::Unshadowed;
  const bool interreflected = d.options.kind == prt::TransferKind::Interreflected;
  if (p.coefficients != d.options.order * d.options.order) std::abort();
  if (p.direct_size() != (sh ? n * k : 0) || p.ao.size() != (d.options.ao ? n : 0) ||
      p.bent.size() != (d.options.bent_normals ? 3 * n : 0) ||
      p.gather_rows.size() != (interreflected ? n : 0) || sum_of(p.gather_rows) != p.hit_size())
    std::abort();
  if (!inside(p.direct_view, Exact(p.direct_count) * sizeof(double), begin, size) ||
      !inside(p.hits_view, Exact(p.hit_count) * sizeof(prt::bake::CompactHit), begin, size))
    std::abort();
  if (d.subsurface && p.shard.index == 0) {
    if (d.subsurface->vertex_material.size() != p.vertices) std::abort();
    for (int32_t m : d.subsurface->vertex_material)
      if (m < -1 || (m >= 0 && std::size_t(m) >= d.subsurface->materials.size())) std::abort();
  }
}

inline void check_haar_part(const prt::bake::TransferPartFile& d, const unsigned char* begin,
                            std::size_t size) {
  const prt::bake::HaarPart& p = d.haar_part;
  const Exact n = p.rows.size(), w = Exact(6) * d.haar_options.cube_size * d.haar_options.cube_size;
  const bool interreflected = d.haar_options.transport == prt::TransferKind::Interreflected;
  if (p.channels != 1 && p.channels != 3) std::abort();
  const Exact entries = sum_of(p.sparse_lengths);
  if (p.sparse_lengths.size() != (interreflected ? 0 : n) || p.index_size() != entries ||
      p.values_size() != entries * p.channels ||
      p.wavelet_size() != (interreflected ? n * w * p.channels : 0) ||
      p.gather_lengths.size() != (interreflected ? n : 0))
    std::abort();
  const Exact gathered = sum_of(p.gather_lengths);
  if (p.column_size() != gathered || p.weight_size() != gathered) std::abort();
  if (!p.mapped || !inside(p.index_data(), Exact(p.index_size()) * 4, begin, size) ||
      !inside(p.values_data(), Exact(p.values_size()) * 4, begin, size) ||
      !inside(p.wavelet_data(), Exact(p.wavelet_size()) * 4, begin, size) ||
      !inside(p.column_data(), Exact(p.column_size()) * 4, begin, size) ||
      !inside(p.weight_data(), Exact(p.weight_size()) * 4, begin, size))
    std::abort();
}

inline void check_glossy_part(const prt::bake::TransferPartFile& d, const unsigned char* begin,
                              std::size_t size) {
  const prt::bake::GlossyPart& p = d.glossy_part;
  const Exact n = p.rows.size(), order = d.glossy_options.order;
  if (p.order != d.glossy_options.order) std::abort();
  if (p.direct_size() != n * order * order * order * order ||
      p.hit_counts.size() != (d.glossy_options.bounces != 0 ? n : 0) ||
      p.hit_size() != sum_of(p.hit_counts))
    std::abort();
  if (!inside(p.direct_view, Exact(p.direct_count) * sizeof(float), begin, size) ||
      !inside(p.hits_view, Exact(p.hit_count) * sizeof(prt::bake::GlossyHitRecord), begin, size))
    std::abort();
  if (p.shard.index == 0) {
    if (!d.glossy_inputs) std::abort();
    const prt::bake::GlossyInputs& in = *d.glossy_inputs;
    if (in.tangents.size() != p.vertices || in.material_of_vertex.size() != p.vertices)
      std::abort();
    for (uint32_t m : in.material_of_vertex)
      if (m >= in.materials.size()) std::abort();
  }
}

inline void check_decoded_part(const prt::bake::TransferPartFile& d, const prt::PartFile& f,
                               std::size_t size) {
  const auto* begin = static_cast<const unsigned char*>(f.mapping.get());
  const prt::bake::TransferPart& p = d.part;
  if (p.shard.index != f.index || p.shard.count != f.count || p.vertices != f.total_rows ||
      p.rows.first != f.first_row || p.rows.size() != f.row_count)
    std::abort();
  if (d.form_factors) {
    if (d.form_factor_rows.size() != Exact(f.row_count) * f.total_rows) std::abort();
    return;
  }
  if (f.index == 0 && !d.scene) std::abort();
  if (d.scene) check_scene(*d.scene, f.total_rows);
  if (d.haar)
    check_haar_part(d, begin, size);
  else if (d.glossy)
    check_glossy_part(d, begin, size);
  else
    check_sh_part(d, begin, size);
}

}  // namespace prt::fuzz
