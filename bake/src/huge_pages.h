// bake/src/huge_pages.h (private) — large arrays read at random (the compact gather's bounce
// vectors and triangle table) asked to live on 2 MB pages: with 4 KB pages a read scattered over
// gigabytes misses the TLB almost every time. A hint only (Linux transparent huge pages in
// madvise mode); elsewhere, or when refused, the arrays are ordinary.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace prt::bake::detail {

// Asks for 2 MB pages over the 2 MB-aligned interior of a fresh (untouched) allocation: the
// gather reads x and the triangle table at random over hundreds of MB, where 4 KB pages would
// miss the TLB on almost every read. A hint only (Linux transparent huge pages in madvise mode).
inline void advise_huge_pages(const void* data, std::size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t kHuge = std::uintptr_t(1) << 21;
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + kHuge - 1) & ~(kHuge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(kHuge - 1);
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// Sizes a vector for n elements, hinting huge pages before its memory is first touched.
template <class T>
inline void resize_huge(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) {
    std::vector<T>().swap(v);
    v.reserve(n);
    advise_huge_pages(v.data(), n * sizeof(T));
  }
  v.resize(n);
}

// Sizes v for n elements from an `align`-byte boundary (align a power of two, a multiple of
// sizeof(T)), huge pages hinted, every element zero; returns the aligned start. The vector holds
// align / sizeof(T) elements more than n.
template <class T>
inline T* resize_huge_aligned(std::vector<T>& v, std::size_t n, std::size_t align) {
  const std::size_t extra = align / sizeof(T);
  resize_huge(v, n + extra);
  const auto at = reinterpret_cast<std::uintptr_t>(v.data());
  const std::uintptr_t aligned = (at + align - 1) & ~(static_cast<std::uintptr_t>(align) - 1);
  return v.data() + (aligned - at) / sizeof(T);
}

}  // namespace prt::bake::detail
