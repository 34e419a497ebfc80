// bake/src/glossy_part.cpp — a glossy bake split into shards and merged (bake/glossy_part.h).
#include "bake/glossy_part.h"

#include <algorithm>
#include <cmath>

#include "bake/sampling.h"
#include "glossy_bake_stages.h"
#include "prt/formats/part_file.h"
#include "scene/scene_label.h"
#include "scene/tangent_frames.h"

namespace prt::bake {

GlossyInputs glossy_inputs(const scene::Scene& scene) {
  GlossyInputs in;
  in.tangents = scene::tangent_frames(scene);
  glossy_scene_materials(scene, in.materials, in.material_of_vertex);
  return in;
}

void check_glossy_shardable(const scene::Scene& scene, const GlossyBakeOptions& options) {
  if (options.bounces != 0 && scene.textured())
    throw BakeError(scene::scene_label(scene) +
                    ": a sharded interreflected glossy bake needs an untextured albedo (the "
                    "bounces read the texture at the hit points; a part carries vertex albedo)");
}

GlossyPart bake_glossy_part(const scene::Scene& scene, const GlossyBakeOptions& options,
                            ShardSpec shard, ProgressSink* progress) {
  check_glossy_shardable(scene, options);
  if (shard.count == 0 || shard.index >= shard.count)
    throw BakeError(scene::scene_label(scene) + ": shard " + std::to_string(shard.index) + "/" +
                    std::to_string(shard.count) + " is not a shard");
  GlossyPart part;
  part.shard = shard;
  part.vertices = scene.vertex_count();
  part.rows = shard_rows(part.vertices, shard);
  part.order = options.order;
  const std::vector<uint32_t> order = make_morton_order(scene.positions);
  const std::vector<uint32_t> rows(order.begin() + part.rows.first, order.begin() + part.rows.end);
  detail::GlossySampled s = detail::sample_glossy_vertices(scene, options, glossy_inputs(scene),
                                                           rows, progress, part.stats);
  part.direct = std::move(s.direct);
  if (options.bounces != 0) {
    part.hit_counts.resize(rows.size());
    for (std::size_t r = 0; r < rows.size(); ++r)
      part.hit_counts[r] = static_cast<uint32_t>(s.hit_offset[r + 1] - s.hit_offset[r]);
    part.hits = std::move(s.hits);
  }
  part.rays = s.rays;
  part.back_face_hits = s.back_face_hits;
  return part;
}

namespace {

// A part read from a file: its pages go once its rows are copied, not with the file (the merge's
// peak is its own arrays plus one part, not plus every part). In-memory parts: nothing.
void release_pages(const GlossyPart& p) {
  if (p.direct_view) prt::release_part_pages(p.direct_view, p.direct_count * sizeof(float));
  if (p.hits_view) prt::release_part_pages(p.hits_view, p.hit_count * sizeof(GlossyHitRecord));
}

// The parts' rows in vertex order; BakeError when a part does not fit the scene or options.
detail::GlossySampled gather_parts(const scene::Scene& scene, const GlossyBakeOptions& o,
                                   const std::vector<const GlossyPart*>& parts) {
  const std::string name = scene::scene_label(scene);
  const uint64_t V = scene.vertex_count(), KK = uint64_t(o.order) * o.order * o.order * o.order;
  const uint64_t N = static_cast<uint64_t>(round_up_to_packet(o.samples));
  const bool interreflect = o.bounces != 0;
  const std::vector<uint32_t> order = make_morton_order(scene.positions);
  detail::GlossySampled all;
  all.direct.resize(V * KK);
  std::vector<uint32_t> count(V, 0);
  for (const GlossyPart* p : parts) {
    const uint64_t R = p->rows.size();
    if (p->vertices != V || p->rows.end > V || p->order != o.order || p->direct_size() != R * KK ||
        p->hit_counts.size() != (interreflect ? R : 0))
      throw BakeError(name + ": glossy part " + std::to_string(p->shard.index) +
                      " does not fit the scene or the settings");
    const float* direct = p->direct_values();
    uint64_t hits = 0;
    for (uint64_t r = 0; r < R; ++r) {
      const uint32_t v = order[p->rows.first + r];
      std::copy_n(direct + r * KK, KK, &all.direct[v * KK]);
      if (interreflect) count[v] = p->hit_counts[r], hits += count[v];
    }
    if (hits != p->hit_size())
      throw BakeError(name + ": glossy part " + std::to_string(p->shard.index) +
                      ": its hit counts do not add up to its hits");
    // A row's hits name distinct samples in increasing order: the merge keeps only which samples
    // hit (a bit each) and implies each hit's sample by its rank, as the single bake does.
    const GlossyHitRecord* part_hits = p->hit_values();
    uint64_t next = 0;
    for (uint64_t r = 0; r < p->hit_counts.size(); ++r)
      for (uint32_t k = 0; k < p->hit_counts[r]; ++k, ++next) {
        const GlossyHitRecord& h = part_hits[next];
        if (h.triangle >= scene.triangles.size() || h.sample >= N ||
            (k > 0 && h.sample <= part_hits[next - 1].sample) || std::isnan(h.u) || std::isnan(h.v))
          throw BakeError(name + ": glossy part " + std::to_string(p->shard.index) +
                          ": a hit names no triangle or sample, repeats one, or has NaN "
                          "barycentrics");
      }
    all.rays += p->rays;
    all.back_face_hits += p->back_face_hits;
    release_pages(*p);  // copied and checked: read again below, one part at a time
  }
  all.hit_offset.assign(V + 1, 0);
  for (uint64_t v = 0; v < V; ++v) all.hit_offset[v + 1] = all.hit_offset[v] + count[v];
  all.hits.resize(all.hit_offset[V]);
  for (const GlossyPart* p : parts) {
    const GlossyHitRecord* part_hits = p->hit_values();
    uint64_t next = 0;
    for (uint64_t r = 0; r < p->hit_counts.size(); ++r) {
      const uint32_t v = order[p->rows.first + r];
      std::copy_n(part_hits + next, p->hit_counts[r], all.hits.begin() + all.hit_offset[v]);
      next += p->hit_counts[r];
    }
    release_pages(*p);
  }
  return all;
}

}  // namespace

GlossyBakeResult merge_glossy_parts_to_file(const scene::Scene& scene, const GlossyInputs& inputs,
                                            const GlossyBakeOptions& options,
                                            const std::vector<const GlossyPart*>& parts,
                                            const std::string& path, ProgressSink* progress) {
  const std::string name = scene::scene_label(scene);
  const std::size_t V = scene.vertex_count();
  if (inputs.tangents.size() != V || inputs.material_of_vertex.size() != V)
    throw BakeError(name + ": the glossy inputs do not fit the scene");
  for (uint32_t m : inputs.material_of_vertex)
    if (m >= inputs.materials.size()) throw BakeError(name + ": a vertex names no material");
  // The parts tile the rows in shard order, as the SH and Haar merges check: each part's row
  // count in gather_parts is then its own (not a wrapped end - first) and every vertex is filled
  // once.
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const RowRange want =
        shard_rows(V, {static_cast<uint32_t>(i), static_cast<uint32_t>(parts.size())});
    if (parts[i]->rows.first != want.first || parts[i]->rows.end != want.end)
      throw BakeError(name + ": glossy part " + std::to_string(i) + " of " +
                      std::to_string(parts.size()) + " does not fit the split");
  }
  if (parts.empty()) throw BakeError(name + ": no glossy parts to merge");
  // Before gather_parts allocates V order⁴ floats (the bake checks its options only after).
  if (options.order < 1 || options.order > kMaxGlossyBakeOrder)
    throw BakeError(name + ": glossy SH order " + std::to_string(options.order) +
                    " is outside [1, " + std::to_string(kMaxGlossyBakeOrder) + "]");
  detail::GlossySampled all = gather_parts(scene, options, parts);
  return detail::finish_glossy_bake_to_file(scene, options, inputs, all, path, progress);
}

}  // namespace prt::bake
