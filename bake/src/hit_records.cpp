// bake/src/hit_records.cpp — the per-triangle records of the compact hit test (hit_records.h).
#include "hit_records.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "hit_side.h"
#include "huge_pages.h"

namespace prt::bake::detail {

std::vector<HitRecord> make_hit_records(const scene::Scene& scene, const CompactGather& gather) {
  const std::size_t T = scene.triangles.size();
  std::vector<HitRecord> records;
  resize_huge(records, T);
  tbb::parallel_for(
      tbb::blocked_range<std::size_t>(0, T, 1 << 14),
      [&](const tbb::blocked_range<std::size_t>& r) {
        for (std::size_t t = r.begin(); t != r.end(); ++t) {
          const auto tri = static_cast<uint32_t>(t);
          records[t] = HitRecord{front_normal(scene, tri), gather.triangle_index(tri)};
        }
      });
  return records;
}

}  // namespace prt::bake::detail
