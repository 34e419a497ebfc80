// fuzz/fuzz_link_cache.cpp — libFuzzer target: the hierarchical radiosity link cache reader
// (radiosity/link_cache.h) on arbitrary bytes, from a scratch file (the reader takes a path), as
// they are and with their checksum resealed (fuzz_checksum.h), so that mutations reach the
// payload checks behind the CRC-32C.
//
// load_link_cache must refuse a malformed file with a one-line std::runtime_error "PATH: …" and
// never crash, over-read, hang, allocate what a header merely claims, or hit undefined behaviour.
// What it accepts must hold what the solver resumed from it indexes blindly
// (link_cache_invariants.h), read_link_cache_info must agree with it, and link_cache_mismatch
// must describe a key that differs in one line naming the file.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "fuzz_checksum.h"
#include "fuzz_input_file.h"
#include "link_cache_invariants.h"
#include "one_line_error.h"
#include "radiosity/link_cache.h"

namespace {

constexpr std::size_t kChecksumOffset = 68;  // docs/FORMAT.md, "Link cache"

void check(const unsigned char* bytes, std::size_t size) {
  const std::string path = prt::fuzz::write_scratch_file(".links", bytes, size);
  prt::radiosity::LinkCache cache;
  try {
    cache = prt::radiosity::load_link_cache(path);
  } catch (const std::runtime_error& e) {
    prt::fuzz::check_one_line_error(e.what(), path);
    return;
  }
  prt::fuzz::check_link_cache_invariants(cache, size);
  if (!prt::radiosity::is_link_cache(path)) std::abort();
  const prt::radiosity::LinkCacheInfo info = prt::radiosity::read_link_cache_info(path);
  if (info.patches != cache.info.patches || info.links != cache.info.links ||
      info.file_size != cache.info.file_size)
    std::abort();
  // The refusals a solve prints for another scene or other settings (the header's doubles and
  // counts formatted, whatever they hold): one line naming the file.
  const prt::radiosity::LinkCacheKeys keys = cache.info.keys;
  const prt::radiosity::HierarchicalOptions options;
  const std::size_t patches = static_cast<std::size_t>(cache.info.patches);
  // With its own keys a file mismatches only by its algorithm revision: none when it is this
  // prt's, else one line naming the file.
  const std::string own = prt::radiosity::link_cache_mismatch(path, info, keys, options, patches);
  if (cache.info.revision == prt::radiosity::kLinkCacheRevision) {
    if (!own.empty()) std::abort();
  } else {
    prt::fuzz::check_one_line_error(own, path);
  }
  prt::fuzz::check_one_line_error(
      prt::radiosity::link_cache_mismatch(path, info, {~keys.geometry, keys.settings, 0}, options,
                                          patches),
      path);
  prt::fuzz::check_one_line_error(
      prt::radiosity::link_cache_mismatch(path, info, {keys.geometry, ~keys.settings, 0}, options,
                                          patches),
      path);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  prt::fuzz::check_as_given_and_resealed(data, size, kChecksumOffset, check);
  return 0;
}
