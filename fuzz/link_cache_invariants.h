// fuzz/link_cache_invariants.h — what every link cache load_link_cache accepts must satisfy
// (radiosity/link_cache.h): the header's counts and size match the arrays and the file, the leaf
// order is a permutation of the patches, every radiance is finite, and every link names nodes of
// the 2N − 1 node tree, carries a finite g ≥ 0 and follows the previous one in (receiver, sender)
// order. resume_hierarchical indexes nodes and patches by these without checking them again. A
// violation aborts (a finding for the fuzzer).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <vector>

#include "radiosity/link_cache.h"

namespace prt::fuzz {

inline void check_link_cache_invariants(const prt::radiosity::LinkCache& c, std::size_t file_size) {
  const uint64_t n = c.info.patches;
  if (n == 0 || c.order.size() != n || c.start.size() != n || c.links.size() != c.info.links)
    std::abort();
  if (c.info.file_size != file_size ||
      file_size != 128 + n * (sizeof(uint32_t) + 3 * sizeof(double)) + c.links.size() * 12)
    std::abort();
  std::vector<bool> seen(n, false);
  for (uint32_t p : c.order) {
    if (p >= n || seen[p]) std::abort();
    seen[p] = true;
  }
  for (const glm::dvec3& l : c.start)
    if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z)) std::abort();
  const uint64_t nodes = 2 * n - 1;
  for (std::size_t k = 0; k < c.links.size(); ++k) {
    const prt::radiosity::Link& l = c.links[k];
    if (l.receiver >= nodes || l.source_node() >= nodes || !std::isfinite(l.g) || l.g < 0.f)
      std::abort();
    if (k > 0) {
      const prt::radiosity::Link& p = c.links[k - 1];
      if (p.receiver > l.receiver || (p.receiver == l.receiver && p.source >= l.source))
        std::abort();
    }
  }
}

}  // namespace prt::fuzz
