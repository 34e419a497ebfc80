// prt/core/memory_budget.h — the memory a job may use, checked before it is allocated.
//
// A bake or solve of a large scene knows, before it allocates a large buffer, how many bytes the
// buffer needs. It charges them to a MemoryBudget first; a charge that would take the total over
// the limit throws MemoryBudgetExceeded with one line naming what needed the memory, how much the
// job would hold, and the limit, so a job too large for its machine stops at once instead of
// swapping. Buffers freed again are released. The budget counts only what is charged (large
// buffers: gather matrices, coefficient blocks, form factors, links); small bookkeeping is left
// out, which is why the default limit keeps a margin below the machine's memory.
//
// Sizes: bytes, as uint64_t. parse_memory_size accepts "8G", "512M", "1.5GB", "100000K" or a
// plain number of bytes (binary units: K = 1024). Thread-safe charges (an atomic total); no
// threads of its own, no dependencies beyond the C++17 library.
#pragma once

#include <atomic>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace prt {

struct MemoryBudgetExceeded : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class MemoryBudget {
 public:
  // A budget of `limit_bytes` (0: unlimited). `owner` prefixes every message, for example the
  // scene's path.
  explicit MemoryBudget(uint64_t limit_bytes = 0, std::string owner = {});

  // Adds `bytes` for `what` ("the gather matrix"); throws MemoryBudgetExceeded when the total
  // would exceed the limit: "OWNER: WHAT would take 3.2 GB, 17.9 GB in all; the
  // memory limit is 16.0 GB". Nothing is added when it throws.
  void charge(uint64_t bytes, const std::string& what);
  // Takes back bytes charged earlier (clamped at zero).
  void release(uint64_t bytes);

  uint64_t limit() const { return limit_; }
  uint64_t used() const { return used_.load(); }
  uint64_t peak() const { return peak_.load(); }  // the largest total charged so far

  // The default limit: 85% of the memory the system reports as available now (Linux
  // MemAvailable), or of the physical memory where that is not known; 0 if neither is.
  static uint64_t default_limit();

 private:
  uint64_t limit_;
  std::string owner_;
  std::atomic<uint64_t> used_{0};
  std::atomic<uint64_t> peak_{0};
};

// "8G" → 8 GiB and so on (above); throws std::invalid_argument naming the text when it is not a
// positive size.
uint64_t parse_memory_size(const std::string& text);
// 3435973837 → "3.2 GB" (binary units, one decimal).
std::string format_memory_size(uint64_t bytes);
// The peak resident set size of this process so far (getrusage), in bytes; 0 where unknown.
uint64_t peak_resident_bytes();

}  // namespace prt
