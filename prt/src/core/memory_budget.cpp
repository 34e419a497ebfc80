// prt/src/core/memory_budget.cpp — see memory_budget.h.
#include "prt/core/memory_budget.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#if defined(__unix__) || defined(__APPLE__)
#include <sys/resource.h>
#include <unistd.h>
#endif

namespace prt {

MemoryBudget::MemoryBudget(uint64_t limit_bytes, std::string owner)
    : limit_(limit_bytes), owner_(std::move(owner)) {}

void MemoryBudget::charge(uint64_t bytes, const std::string& what) {
  uint64_t current = used_.load();
  for (;;) {
    const uint64_t total = current + bytes;
    if (limit_ > 0 && (total > limit_ || total < current)) {
      const std::string prefix = owner_.empty() ? std::string() : owner_ + ": ";
      throw MemoryBudgetExceeded(prefix + what + " would take " + format_memory_size(bytes) + ", " +
                                 format_memory_size(total) + " in all; the memory limit is " +
                                 format_memory_size(limit_));
    }
    if (used_.compare_exchange_weak(current, total)) break;
  }
  uint64_t peak = peak_.load();
  const uint64_t now = used_.load();
  while (now > peak && !peak_.compare_exchange_weak(peak, now)) {
  }
}

void MemoryBudget::release(uint64_t bytes) {
  uint64_t current = used_.load();
  while (!used_.compare_exchange_weak(current, current > bytes ? current - bytes : 0)) {
  }
}

namespace {

// A "Key:   123 kB" line of /proc/meminfo, in bytes; 0 when absent.
uint64_t meminfo_bytes(const char* key) {
  std::ifstream in("/proc/meminfo");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line)) {
    if (line.compare(0, prefix.size(), prefix) != 0) continue;
    std::istringstream fields(line.substr(prefix.size()));
    uint64_t kib = 0;
    fields >> kib;
    return kib * 1024;
  }
  return 0;
}

}  // namespace

uint64_t MemoryBudget::default_limit() {
  uint64_t available = meminfo_bytes("MemAvailable");
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGE_SIZE)
  if (available == 0) {
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
    if (pages > 0 && page > 0)
      available = static_cast<uint64_t>(pages) * static_cast<uint64_t>(page);
  }
#endif
  return available / 20 * 17;
}

uint64_t parse_memory_size(const std::string& text) {
  const auto bad = [&] {
    return std::invalid_argument("'" + text +
                                 "' is not a memory size (a positive number with K, M, G or T)");
  };
  std::size_t used = 0;
  double value = 0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    throw bad();
  }
  std::string unit = text.substr(used);
  for (char& c : unit) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (!unit.empty() && unit.back() == 'B') unit.pop_back();
  if (!unit.empty() && unit.back() == 'I') unit.pop_back();  // "GiB"
  double scale = 1;
  if (unit == "K")
    scale = 1024.0;
  else if (unit == "M")
    scale = 1024.0 * 1024;
  else if (unit == "G")
    scale = 1024.0 * 1024 * 1024;
  else if (unit == "T")
    scale = 1024.0 * 1024 * 1024 * 1024;
  else if (!unit.empty())
    throw bad();
  const double bytes = value * scale;
  if (!std::isfinite(bytes) || bytes < 1 || bytes > 1.8e19) throw bad();
  return static_cast<uint64_t>(bytes);
}

std::string format_memory_size(uint64_t bytes) {
  const char* units[] = {"B", "KB", "MB", "GB", "TB"};
  double v = static_cast<double>(bytes);
  int u = 0;
  while (v >= 1024 && u < 4) v /= 1024, ++u;
  char buf[32];
  if (u == 0)
    std::snprintf(buf, sizeof buf, "%llu B", static_cast<unsigned long long>(bytes));
  else
    std::snprintf(buf, sizeof buf, "%.1f %s", v, units[u]);
  return buf;
}

uint64_t peak_resident_bytes() {
#if defined(__unix__)
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) == 0) return static_cast<uint64_t>(usage.ru_maxrss) * 1024;
#endif
  return 0;
}

}  // namespace prt
