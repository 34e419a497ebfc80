// radiosity/link_cache.h — the hierarchy and final links of a hierarchical radiosity solve
// (radiosity/hierarchical_solver.h) saved to disk and loaded back: `--form-factor-cache` with
// the hierarchical solver. Layout: docs/FORMAT.md, "Link cache".
//
// Stored: the hierarchy as its leaf order (the tree's shape follows from the patch count, every
// node's data from its patches: radiosity/hierarchy.h), every final link (receiver node, sender
// node with the exact flag, g: for an exact link A_s·F_sr with its visibility, for a point link
// V / (π r² + max A), the visible fraction V times the unoccluded kernel; radiosity/links.h) and
// the patches' radiance the last solve started from. Three 64-bit keys (FNV-1a-64 over 32-bit
// words with the splitmix64 finaliser, numerics::WordHash, as form_factor_cache.h) bind it:
//   geometry: the patch count, every patch's corners and visible fraction (float bit patterns);
//   settings: what shapes the links besides the light: ε, the visibility rays a point link (as
//     resolved), the seed, fine or coarse transfer, the passes, the solve's tolerance and
//     iteration limit;
//   lighting: every patch's emission and albedo (double bit patterns): the "BF" oracle refined
//     against the radiosity they give.
// The header also records the revision of the link algorithms (kLinkCacheRevision), which the
// settings key covers from revision 2 on. A loaded file must be of the current revision and have
// the caller's geometry and settings keys (else one line naming what differs); its lighting key
// tells whether the links are used as they are (the same light: the last solve repeated, bit for
// bit) or re-checked for the new light (hierarchical_solver.h, resume_hierarchical). Its CRC-32C
// (prt/formats/crc32c.h) must hold, the order must be a permutation, the links in range and sorted,
// every number finite. Errors throw std::runtime_error with one line that names the file; saving is
// atomic (prt/core/atomic_file.h), so a failed save leaves no file behind. The bytes depend only on
// the solve's result, which does not depend on the thread count.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "prt/core/memory_budget.h"
#include "radiosity/hierarchical_solver.h"
#include "radiosity/links.h"
#include "radiosity/patches.h"

namespace prt::radiosity {

// The revision of the link algorithms (refinement, link values and visibility,
// radiosity/links.h), raised whenever the same patches and settings give other links: 1, the
// first (the caches written before revisions were recorded hold 0 there and are revision 1). A
// cache of an earlier revision is stale: `prt radiosity` solves afresh and saves over it
// (radiosity/scene_solve.h); one of a later revision is refused (link_cache_mismatch).
constexpr uint32_t kLinkCacheRevision = 1;

struct LinkCacheKeys {
  uint64_t geometry = 0, settings = 0, lighting = 0;
};

// The keys of `patches` (with their hidden parts marked) solved with `options`.
LinkCacheKeys link_cache_keys(const std::vector<Patch>& patches,
                              const HierarchicalOptions& options);

// What the header records (also for `prt info`).
struct LinkCacheInfo {
  uint32_t version = 0, revision = 0;
  LinkCacheKeys keys;
  uint64_t patches = 0, links = 0, file_size = 0;
  bool fine = false;
  double epsilon = 0, tolerance = 0;
  uint64_t seed = 0, max_iterations = 0;
  uint32_t visibility_rays = 0, max_passes = 0;
};

struct LinkCache {
  LinkCacheInfo info;
  std::vector<uint32_t> order;    // the hierarchy's leaf order
  std::vector<glm::dvec3> start;  // HierarchicalSolution::last_start
  std::vector<Link> links;
};

// Writes the solve of `patches` with `options` (keys from link_cache_keys) to PATH, atomically.
void save_link_cache(const std::string& path, const LinkCacheKeys& keys,
                     const HierarchicalOptions& options, const HierarchicalSolution& solved);

// Reads and checks the header (magic, version, sizes, reserved bytes 116-127 zero, the bytes
// present); not the checksum.
LinkCacheInfo read_link_cache_info(const std::string& path);

// Reads PATH whole with every check above except the keys, which the caller compares; the links
// and the rest are charged to `budget` (may be null) before they are read.
LinkCache load_link_cache(const std::string& path, MemoryBudget* budget = nullptr);

// "PATH: link cache of algorithm revision R, this prt computes revision …" when its revision is
// not kLinkCacheRevision, "PATH: link cache made for another scene (geometry key …)" or "… with
// other hierarchical settings (cache: …; asked: …)" when a key other than lighting differs; empty
// when they match.
std::string link_cache_mismatch(const std::string& path, const LinkCacheInfo& cached,
                                const LinkCacheKeys& keys, const HierarchicalOptions& options,
                                std::size_t patches);

// True when PATH starts with the link cache's magic.
bool is_link_cache(const std::string& path);

}  // namespace prt::radiosity
