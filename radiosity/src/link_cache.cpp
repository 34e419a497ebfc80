// radiosity/src/link_cache.cpp — see radiosity/link_cache.h.
#include "radiosity/link_cache.h"

#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <stdexcept>

#include "numerics/hash.h"
#include "prt/core/atomic_file.h"
#include "prt/formats/crc32c.h"

namespace prt::radiosity {
namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'H', 'R', 'L', '1', '\n'};
constexpr uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 128;
constexpr std::size_t kReservedOffset = 116;  // bytes 116-127: zero
constexpr std::size_t kChecksumOffset = 68;
constexpr uint32_t kFlagFine = 1;
static_assert(sizeof(Link) == 12, "a link is three 32-bit words on disk");

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

void put(unsigned char* out, std::size_t at, const void* v, std::size_t n) {
  std::memcpy(out + at, v, n);
}
template <class T>
T get(const unsigned char* in, std::size_t at) {
  T v;
  std::memcpy(&v, in + at, sizeof v);
  return v;
}

// Little-endian (the machines prt runs on; docs/FORMAT.md), checksum as given.
void encode(const LinkCacheInfo& h, uint32_t checksum, unsigned char* out) {
  std::memset(out, 0, kHeaderSize);
  std::memcpy(out, kMagic, 8);
  const uint32_t header_size = kHeaderSize, flags = h.fine ? kFlagFine : 0;
  put(out, 8, &h.version, 4);
  put(out, 12, &header_size, 4);
  put(out, 16, &h.keys.geometry, 8);
  put(out, 24, &h.keys.settings, 8);
  put(out, 32, &h.keys.lighting, 8);
  put(out, 40, &h.patches, 8);
  put(out, 48, &h.links, 8);
  put(out, 56, &h.file_size, 8);
  put(out, 64, &flags, 4);
  put(out, kChecksumOffset, &checksum, 4);
  put(out, 72, &h.epsilon, 8);
  put(out, 80, &h.seed, 8);
  put(out, 88, &h.visibility_rays, 4);
  put(out, 92, &h.max_passes, 4);
  put(out, 96, &h.tolerance, 8);
  put(out, 104, &h.max_iterations, 8);
  put(out, 112, &h.revision, 4);
}

uint64_t payload_bytes(uint64_t patches, uint64_t links) {
  return patches * (sizeof(uint32_t) + sizeof(glm::dvec3)) + links * sizeof(Link);
}

std::string hex(uint64_t v) {
  char text[19];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, v);
  return text;
}

void hash_double(numerics::WordHash& h, double v) {
  uint64_t bits;
  std::memcpy(&bits, &v, 8);
  h.add_u64(v == 0.0 ? 0 : bits);
}

// Opens PATH and checks the header; the file is left at the payload; *checksum is the stored one.
File open_cache(const std::string& path, LinkCacheInfo* info, unsigned char* header,
                uint32_t* checksum) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file) throw std::runtime_error(path + ": cannot open link cache: " + std::strerror(errno));
  const std::size_t got = std::fread(header, 1, kHeaderSize, file.get());
  if (got >= 8 && std::memcmp(header, kMagic, 8) != 0)
    throw std::runtime_error(path +
                             ": not a prt link cache (bad magic; a dense form-factor "
                             "cache does not serve the hierarchical solver)");
  if (got < kHeaderSize) throw std::runtime_error(path + ": truncated link cache (header)");
  LinkCacheInfo& h = *info;
  h.version = get<uint32_t>(header, 8);
  if (h.version != kVersion || get<uint32_t>(header, 12) != kHeaderSize)
    throw std::runtime_error(path + ": link cache version " + std::to_string(h.version) +
                             " (this prt reads version " + std::to_string(kVersion) + ")");
  h.keys = {get<uint64_t>(header, 16), get<uint64_t>(header, 24), get<uint64_t>(header, 32)};
  h.patches = get<uint64_t>(header, 40);
  h.links = get<uint64_t>(header, 48);
  h.file_size = get<uint64_t>(header, 56);
  const uint32_t flags = get<uint32_t>(header, 64);
  h.fine = (flags & kFlagFine) != 0;
  *checksum = get<uint32_t>(header, kChecksumOffset);
  h.epsilon = get<double>(header, 72);
  h.seed = get<uint64_t>(header, 80);
  h.visibility_rays = get<uint32_t>(header, 88);
  h.max_passes = get<uint32_t>(header, 92);
  h.tolerance = get<double>(header, 96);
  h.max_iterations = get<uint64_t>(header, 104);
  h.revision = get<uint32_t>(header, 112);
  if (h.revision == 0) h.revision = 1;  // written before the revision was recorded
  for (std::size_t at = kReservedOffset; at < kHeaderSize; ++at)
    if (header[at] != 0)
      throw std::runtime_error(path + ": corrupt link cache (reserved header byte " +
                               std::to_string(at) + " is not zero)");
  // The counts are bounded before any size arithmetic, so hostile ones cannot overflow it.
  if (h.patches == 0 || h.patches > (uint64_t(1) << 31) || h.links > (uint64_t(1) << 40) ||
      (flags & ~kFlagFine) != 0 || h.file_size != kHeaderSize + payload_bytes(h.patches, h.links))
    throw std::runtime_error(path + ": corrupt link cache (size fields disagree)");
  if (std::fseek(file.get(), 0, SEEK_END) != 0)
    throw std::runtime_error(path + ": cannot seek: " + std::strerror(errno));
  const long present = std::ftell(file.get());
  if (present < 0 || uint64_t(present) < h.file_size)
    throw std::runtime_error(path + ": truncated link cache (" + std::to_string(present) + " of " +
                             std::to_string(h.file_size) + " bytes)");
  if (uint64_t(present) > h.file_size)
    throw std::runtime_error(path + ": corrupt link cache (unexpected bytes after the end)");
  std::fseek(file.get(), static_cast<long>(kHeaderSize), SEEK_SET);
  std::memset(header + kChecksumOffset, 0, 4);  // as the checksum takes it
  return file;
}

template <class T>
void read_array(std::FILE* file, const std::string& path, std::vector<T>* v, uint32_t* crc) {
  if (std::fread(v->data(), sizeof(T), v->size(), file) != v->size())
    throw std::runtime_error(path + ": cannot read link cache: " + std::strerror(errno));
  *crc = crc32c(v->data(), v->size() * sizeof(T), *crc);
}

// The checks of load_link_cache on the payload.
void check_payload(const std::string& path, const LinkCache& c) {
  const uint64_t n = c.order.size(), nodes = 2 * n - 1;
  std::vector<bool> seen(n, false);
  for (uint32_t p : c.order) {
    if (p >= n || seen[p])
      throw std::runtime_error(path + ": corrupt link cache (the leaf order is no permutation)");
    seen[p] = true;
  }
  for (const glm::dvec3& l : c.start)
    if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z))
      throw std::runtime_error(path + ": corrupt link cache (non-finite radiance)");
  for (std::size_t k = 0; k < c.links.size(); ++k) {
    const Link& l = c.links[k];
    const bool sorted = k == 0 || c.links[k - 1].receiver < l.receiver ||
                        (c.links[k - 1].receiver == l.receiver && c.links[k - 1].source < l.source);
    if (l.receiver >= nodes || l.source_node() >= nodes || !std::isfinite(l.g) || l.g < 0.f ||
        !sorted)
      throw std::runtime_error(path + ": corrupt link cache (link " + std::to_string(k) +
                               " out of range or order)");
  }
}

}  // namespace

LinkCacheKeys link_cache_keys(const std::vector<Patch>& patches,
                              const HierarchicalOptions& options) {
  LinkCacheKeys keys;
  numerics::WordHash geometry, settings, lighting;
  geometry.add_u64(patches.size());
  for (const Patch& p : patches) {
    for (const glm::dvec3& c : p.corners)
      for (int k = 0; k < 3; ++k) geometry.add_float(static_cast<float>(c[k]));
    geometry.add_float(static_cast<float>(p.visible));
    for (int k = 0; k < 3; ++k) hash_double(lighting, p.emission[k]);
    for (int k = 0; k < 3; ++k) hash_double(lighting, p.albedo[k]);
  }
  const LinkOptions links = resolved_link_options(patches.size(), options);
  hash_double(settings, links.epsilon);
  settings.add_word(static_cast<uint32_t>(links.visibility_rays));
  settings.add_u64(links.seed);
  settings.add_word(links.fine ? 1u : 0u);
  settings.add_word(static_cast<uint32_t>(options.max_passes));
  hash_double(settings, options.solve.tolerance);
  settings.add_u64(options.solve.max_iterations);
  // Revision 1 adds nothing (the keys of the caches written before revisions were recorded);
  // every later revision is a word of its own, so no earlier cache has a current key.
  if (kLinkCacheRevision != 1) settings.add_word(0x52000000u + kLinkCacheRevision);
  keys.geometry = geometry.finish();
  keys.settings = settings.finish();
  keys.lighting = lighting.finish();
  return keys;
}

void save_link_cache(const std::string& path, const LinkCacheKeys& keys,
                     const HierarchicalOptions& options, const HierarchicalSolution& solved) {
  const std::size_t n = solved.hierarchy.order.size();
  if (solved.last_start.size() != n)
    throw std::invalid_argument(path + ": the solve kept no starting radiance");
  const LinkOptions links = resolved_link_options(n, options);
  LinkCacheInfo h;
  h.version = kVersion;
  h.revision = kLinkCacheRevision;
  h.keys = keys;
  h.patches = n;
  h.links = solved.links.size();
  h.file_size = kHeaderSize + payload_bytes(n, h.links);
  h.fine = solved.stats.fine;
  h.epsilon = links.epsilon;
  h.seed = links.seed;
  h.visibility_rays = static_cast<uint32_t>(links.visibility_rays);
  h.max_passes = static_cast<uint32_t>(options.max_passes);
  h.tolerance = options.solve.tolerance;
  h.max_iterations = options.solve.max_iterations;
  unsigned char header[kHeaderSize];
  encode(h, 0, header);
  uint32_t crc = crc32c(header, kHeaderSize);
  crc = crc32c(solved.hierarchy.order.data(), n * sizeof(uint32_t), crc);
  crc = crc32c(solved.last_start.data(), n * sizeof(glm::dvec3), crc);
  crc = crc32c(solved.links.data(), solved.links.size() * sizeof(Link), crc);
  encode(h, crc, header);
  const Status status = replace_file_atomically(path, [&](const std::string& temporary) {
    File file(std::fopen(temporary.c_str(), "wb"));
    if (!file)
      return Status::Error(path + ": cannot create " + temporary + ": " + std::strerror(errno));
    const bool written =
        std::fwrite(header, 1, kHeaderSize, file.get()) == kHeaderSize &&
        std::fwrite(solved.hierarchy.order.data(), sizeof(uint32_t), n, file.get()) == n &&
        std::fwrite(solved.last_start.data(), sizeof(glm::dvec3), n, file.get()) == n &&
        std::fwrite(solved.links.data(), sizeof(Link), solved.links.size(), file.get()) ==
            solved.links.size();
    if (!written || std::fclose(file.release()) != 0)
      return Status::Error(path + ": cannot write " + temporary + ": " + std::strerror(errno));
    return Status::Ok();
  });
  if (!status.ok()) throw std::runtime_error(status.message());
}

LinkCacheInfo read_link_cache_info(const std::string& path) {
  LinkCacheInfo info;
  unsigned char header[kHeaderSize];
  uint32_t checksum = 0;
  open_cache(path, &info, header, &checksum);
  return info;
}

LinkCache load_link_cache(const std::string& path, MemoryBudget* budget) {
  LinkCache c;
  unsigned char header[kHeaderSize];
  uint32_t checksum = 0;
  File file = open_cache(path, &c.info, header, &checksum);
  if (budget) budget->charge(payload_bytes(c.info.patches, c.info.links), "the link cache");
  c.order.resize(c.info.patches);
  c.start.resize(c.info.patches);
  c.links.resize(c.info.links);
  uint32_t crc = crc32c(header, kHeaderSize);
  read_array(file.get(), path, &c.order, &crc);
  read_array(file.get(), path, &c.start, &crc);
  read_array(file.get(), path, &c.links, &crc);
  if (budget) budget->release(payload_bytes(c.info.patches, c.info.links));
  if (crc != checksum) throw std::runtime_error(path + ": corrupt link cache (checksum mismatch)");
  check_payload(path, c);
  return c;
}

std::string link_cache_mismatch(const std::string& path, const LinkCacheInfo& cached,
                                const LinkCacheKeys& keys, const HierarchicalOptions& options,
                                std::size_t patches) {
  const std::string advice = "; give another --form-factor-cache or delete this one";
  if (cached.revision != kLinkCacheRevision)
    return path + ": link cache of algorithm revision " + std::to_string(cached.revision) +
           ", this prt computes revision " + std::to_string(kLinkCacheRevision) + advice;
  if (cached.keys.geometry != keys.geometry)
    return path + ": link cache made for another scene or subdivision (geometry key " +
           hex(cached.keys.geometry) + " of " + std::to_string(cached.patches) +
           " patches, expected " + hex(keys.geometry) + " of " + std::to_string(patches) + ")" +
           advice;
  if (cached.keys.settings == keys.settings) return "";
  const LinkOptions links = resolved_link_options(patches, options);
  char text[320];
  std::snprintf(text, sizeof text,
                "(settings key: cache --link-epsilon %g, --link-rays %u, seed %" PRIu64
                ", --link-passes %u, --tolerance %g, %" PRIu64 " iterations; asked %g, %d, %" PRIu64
                ", %d, %g, %zu)",
                cached.epsilon, cached.visibility_rays, cached.seed, cached.max_passes,
                cached.tolerance, cached.max_iterations, links.epsilon, links.visibility_rays,
                links.seed, options.max_passes, options.solve.tolerance,
                options.solve.max_iterations);
  return path + ": link cache made with other hierarchical settings " + text + advice;
}

bool is_link_cache(const std::string& path) {
  File file(std::fopen(path.c_str(), "rb"));
  char magic[8];
  return file && std::fread(magic, 1, 8, file.get()) == 8 && std::memcmp(magic, kMagic, 8) == 0;
}

}  // namespace prt::radiosity
