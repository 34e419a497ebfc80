// bake/src/hit_records.h (private) — one 16-byte record per scene triangle for the compact
// gather's hit test: the oriented geometric normal n_f of hit_side.h's front_normal() and the
// triangle's index in the compact gather (CompactGather::triangle_index). The sampling pass then
// judges a hit's side and renumbers its triangle with one read per hit instead of seven scattered
// ones (the triangle, its three positions, its three normals, the renumbering): at millions of
// vertices those reads leave the caches. The test is hit_side.h's, bit for bit (see there).
//
// Memory: 16 bytes per triangle, held during the sampling pass only. Frame: the Scene's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bake/compact_gather.h"
#include "scene/scene.h"

namespace prt::bake::detail {

struct HitRecord {
  glm::vec3 front;        // n_f: the ray of direction d sees the front iff dot(n_f, d) < 0
  uint32_t gather_index;  // CompactGather::triangle_index of the triangle
};
static_assert(sizeof(HitRecord) == 16, "a hit record is 16 bytes");

// records[t] for every scene triangle t (in parallel).
std::vector<HitRecord> make_hit_records(const scene::Scene& scene, const CompactGather& gather);

// The compact gather's hit test through the records: appends the hit as a CompactHit and returns
// true for a front face, as gather_front_hit_compact() does from the scene.
inline bool gather_front_hit_record(const HitRecord* records, uint32_t triangle, float u, float v,
                                    const glm::vec3& dir, std::vector<CompactHit>& hits) {
  const HitRecord r = records[triangle];
  if (!(glm::dot(r.front, dir) < 0.f)) return false;
  hits.push_back(quantise_hit(r.gather_index, u, v));
  return true;
}

}  // namespace prt::bake::detail
