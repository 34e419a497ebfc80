// Tests of prt/core/memory_budget.h: charges over the limit are refused with one line and change
// nothing; sizes parse and print in binary units.
#include <stdexcept>
#include <string>

#include <catch2/catch.hpp>

#include "prt/core/memory_budget.h"

TEST_CASE("memory budget refuses a charge over its limit and keeps its total", "[memory]") {
  prt::MemoryBudget budget(1000, "scene.glb");
  budget.charge(600, "the gather matrix");
  CHECK(budget.used() == 600);
  try {
    budget.charge(500, "the solver's blocks");
    FAIL("a charge over the limit was accepted");
  } catch (const prt::MemoryBudgetExceeded& e) {
    const std::string m = e.what();
    CHECK(m.find("scene.glb: the solver's blocks would take 500 B, 1.1 KB in all") == 0);
    CHECK(m.find("1.1 KB in all") != std::string::npos);
    CHECK(m.find('\n') == std::string::npos);
  }
  CHECK(budget.used() == 600);  // nothing added by the refused charge
  budget.release(600);
  budget.charge(1000, "all of it");
  CHECK(budget.peak() == 1000);
  budget.release(5000);  // clamped
  CHECK(budget.used() == 0);
}

TEST_CASE("an unlimited budget accepts anything and counts its peak", "[memory]") {
  prt::MemoryBudget budget;
  budget.charge(uint64_t(1) << 40, "a terabyte");
  CHECK(budget.peak() == uint64_t(1) << 40);
}

TEST_CASE("memory sizes parse in binary units and refuse nonsense", "[memory]") {
  CHECK(prt::parse_memory_size("8G") == 8ull << 30);
  CHECK(prt::parse_memory_size("512M") == 512ull << 20);
  CHECK(prt::parse_memory_size("1.5GB") == 3ull << 29);
  CHECK(prt::parse_memory_size("2GiB") == 2ull << 30);
  CHECK(prt::parse_memory_size("4096") == 4096);
  for (const char* bad : {"", "G", "-1G", "0", "8X", "nan", "1e30T"})
    CHECK_THROWS_AS(prt::parse_memory_size(bad), std::invalid_argument);
  CHECK(prt::format_memory_size(3435973837ull) == "3.2 GB");
  CHECK(prt::format_memory_size(12) == "12 B");
}

TEST_CASE("the default memory limit is below the machine's memory and not zero", "[memory]") {
  const uint64_t limit = prt::MemoryBudget::default_limit();
  CHECK(limit > (uint64_t(64) << 20));  // any machine that runs the tests has 64 MB free
  CHECK(prt::peak_resident_bytes() > 0);
}
