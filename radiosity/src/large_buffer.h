// large_buffer.h — zero-filled vectors of N² numbers (form factors, the gather matrix) backed by
// transparent huge pages where the kernel offers them (madvise(MADV_HUGEPAGE); Linux only).
// Filling 400 MB in 4 KiB pages costs ~10⁵ page faults, which dominated the time of a
// 10,000-patch solve on a virtual machine (docs/RADIOSITY.md, "Speed"); 2 MiB pages cut them
// 512-fold. Elsewhere, or when the advice is refused, it is an ordinary zero-filled vector.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <tbb/parallel_for.h>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace prt::radiosity::detail {

template <class T>
void assign_zeroed_large(std::vector<T>* v, std::size_t count) {
  v->clear();
  v->shrink_to_fit();
  v->reserve(count);  // large blocks come from mmap, untouched until filled below
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr uintptr_t kHuge = uintptr_t(2) << 20;
  const uintptr_t begin = reinterpret_cast<uintptr_t>(v->data());
  const uintptr_t end = begin + count * sizeof(T);
  const uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1), last = end & ~(kHuge - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#if defined(MADV_POPULATE_WRITE)
  // The kernel's zeroing of the new pages (page faults, system time) on every core, in 64 MiB
  // pieces, instead of on the one thread that fills the vector below; without
  // MADV_POPULATE_WRITE (Linux < 5.14) madvise fails and the fill faults the pages as before.
  constexpr uintptr_t kPiece = uintptr_t(64) << 20;
  if (last > first)
    tbb::parallel_for(uintptr_t(0), (last - first + kPiece - 1) / kPiece, [&](uintptr_t k) {
      const uintptr_t a = first + k * kPiece, b = std::min(last, a + kPiece);
      madvise(reinterpret_cast<void*>(a), b - a, MADV_POPULATE_WRITE);
    });
#endif
#endif
  v->assign(count, T(0));
}

}  // namespace prt::radiosity::detail
