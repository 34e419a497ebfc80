// scene/src/small_pages_scope.h (private) — a scope in which the process takes no transparent
// huge pages (Linux prctl PR_SET_THP_DISABLE; the previous setting is restored on exit).
//
// Why: Embree asks for 2 MB pages (madvise MADV_HUGEPAGE) over the memory of its BVH builder.
// Where the kernel compacts memory to find 2 MB pages at fault time (transparent_hugepage/defrag
// = madvise, the Debian default), building the BVH of 4M triangles took 3.0–3.8 s of CPU of
// which 1.5–2.4 s in the kernel, against 1.7 s (0.3 s kernel) with 4 KB pages; the BVH is the
// same either way (same builder, same flags: only the pages under it differ), so every hit is
// bit-identical. Measured in docs/BENCHMARKS.md ("Farm shards at 2M vertices: the fixed cost").
// Elsewhere, or when the call is refused, a no-op.
#pragma once

#if defined(__linux__)
#include <sys/prctl.h>
#endif

namespace prt::scene::detail {

class SmallPagesScope {
 public:
  SmallPagesScope() {
#if defined(__linux__) && defined(PR_SET_THP_DISABLE)
    const int was = prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0);
    if (was == 0 && prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0) == 0) restore_ = true;
#endif
  }
  ~SmallPagesScope() {
#if defined(__linux__) && defined(PR_SET_THP_DISABLE)
    if (restore_) prctl(PR_SET_THP_DISABLE, 0, 0, 0, 0);
#endif
  }
  SmallPagesScope(const SmallPagesScope&) = delete;
  SmallPagesScope& operator=(const SmallPagesScope&) = delete;

 private:
  bool restore_ = false;
};

}  // namespace prt::scene::detail
