#include "radiosity/form_factor_cache.h"

#include <algorithm>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>

#include "form_factor_rows.h"
#include "large_buffer.h"
#include "numerics/hash.h"
#include "prt/core/atomic_file.h"
#include "prt/formats/crc32c.h"

namespace prt::radiosity {
namespace {

constexpr char kMagic[8] = {'P', 'R', 'T', 'F', 'F', 'M', '1', '\n'};
// Version 3 (what save_form_factors writes) adds the algorithms' revision at 96 to version 2,
// which added the form-factor settings (offsets 64..95, recorded when the options are given) and
// the method at 40 to version 1 (64-byte header, method 0). Versions 1 and 2 are revision 1.
constexpr uint32_t kVersion = 3;
constexpr std::size_t kHeaderSizeV1 = 64, kHeaderSizeV2 = 96, kHeaderSize = 104;
constexpr std::size_t kChecksumOffset = 48;
constexpr uint32_t kFlagSettings = 1;  // offset 44: the settings at 64..95 are recorded

struct Header {
  uint32_t version = kVersion, header_size = kHeaderSize;
  uint64_t key = 0, n = 0, file_size = 0;
  uint32_t method = 0, flags = 0, checksum = 0;
  // Versions 2 and 3 (valid with kFlagSettings).
  uint32_t quadrature_points = 0, rays_per_patch = 0, emitter_rays_per_patch = 0, sampling = 0,
           emitter_rows = 0, hemicube_resolution = 0;
  uint64_t seed = 0;
  // Version 3; 1 for the earlier versions.
  uint32_t revision = 1, reserved = 0;
};

// The header bytes (h.header_size of them), little-endian (the machines prt runs on;
// docs/FORMAT.md).
void encode(const Header& h, unsigned char* out) {
  std::memset(out, 0, h.header_size);
  std::memcpy(out, kMagic, 8);
  std::memcpy(out + 8, &h.version, 4);
  std::memcpy(out + 12, &h.header_size, 4);
  std::memcpy(out + 16, &h.key, 8);
  std::memcpy(out + 24, &h.n, 8);
  std::memcpy(out + 32, &h.file_size, 8);
  std::memcpy(out + 40, &h.method, 4);
  std::memcpy(out + 44, &h.flags, 4);
  std::memcpy(out + kChecksumOffset, &h.checksum, 4);
  if (h.header_size < kHeaderSizeV2) return;
  const uint32_t words[6] = {h.quadrature_points, h.rays_per_patch, h.emitter_rays_per_patch,
                             h.sampling,          h.emitter_rows,   h.hemicube_resolution};
  std::memcpy(out + 64, words, sizeof words);
  std::memcpy(out + 88, &h.seed, 8);
  if (h.header_size < kHeaderSize) return;
  std::memcpy(out + 96, &h.revision, 4);
  std::memcpy(out + 100, &h.reserved, 4);
}

void decode(const unsigned char* in, Header* h) {
  std::memcpy(&h->version, in + 8, 4);
  std::memcpy(&h->header_size, in + 12, 4);
  std::memcpy(&h->key, in + 16, 8);
  std::memcpy(&h->n, in + 24, 8);
  std::memcpy(&h->file_size, in + 32, 8);
  std::memcpy(&h->method, in + 40, 4);
  std::memcpy(&h->flags, in + 44, 4);
  std::memcpy(&h->checksum, in + kChecksumOffset, 4);
  if (h->header_size < kHeaderSizeV2) return;
  uint32_t words[6];
  std::memcpy(words, in + 64, sizeof words);
  h->quadrature_points = words[0];
  h->rays_per_patch = words[1];
  h->emitter_rays_per_patch = words[2];
  h->sampling = words[3];
  h->emitter_rows = words[4];
  h->hemicube_resolution = words[5];
  std::memcpy(&h->seed, in + 88, 8);
  if (h->header_size < kHeaderSize) return;
  std::memcpy(&h->revision, in + 96, 4);
  std::memcpy(&h->reserved, in + 100, 4);
}

std::string hex(uint64_t v) {
  char text[19];
  std::snprintf(text, sizeof text, "0x%016" PRIx64, v);
  return text;
}

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};

}  // namespace

uint64_t form_factor_key(const std::vector<Patch>& patches, const FormFactorOptions& options) {
  numerics::WordHash h;
  h.add_u64(patches.size());
  for (const Patch& p : patches)
    for (const glm::dvec3& c : p.corners)
      for (int k = 0; k < 3; ++k) h.add_float(static_cast<float>(c[k]));
  h.add_word(static_cast<uint32_t>(options.method));
  switch (options.method) {
    case FormFactorMethod::Analytic:
      h.add_word(static_cast<uint32_t>(options.quadrature_points));
      break;
    case FormFactorMethod::Rays:
      h.add_word(static_cast<uint32_t>(options.rays_per_patch));
      h.add_u64(options.seed);
      // Which patches shoot more rays is part of how F was estimated (not their emission).
      if (options.emitter_rays_per_patch > 0 || options.emitter_rows == EmitterRows::Reciprocal) {
        h.add_word(static_cast<uint32_t>(options.emitter_rays_per_patch));
        for (std::size_t i = 0; i < patches.size(); ++i)
          if (patches[i].emission != glm::dvec3(0.0)) h.add_u64(i);
      }
      // Independent samples and ray-cast emitter rows add nothing, so that a cache made before
      // these choices existed (the same F, bit for bit) keeps its key; any other choice changes
      // the key, so a cache of another estimator is refused.
      if (options.sampling != RaySampling::Independent)
        h.add_word(0x50000000u + static_cast<uint32_t>(options.sampling));
      if (options.emitter_rows != EmitterRows::Rays) {
        h.add_word(0x45000000u + static_cast<uint32_t>(options.emitter_rows));
        h.add_word(static_cast<uint32_t>(options.quadrature_points));
      }
      break;
    case FormFactorMethod::Hemicube:
      h.add_word(static_cast<uint32_t>(options.hemicube_resolution));
      break;
  }
  // Revision 1 added nothing (the keys of the caches written before revisions were recorded);
  // every later revision is a word of its own, so no earlier cache has a current key.
  if (kFormFactorRevision != 1) h.add_word(0x52000000u + kFormFactorRevision);
  return h.finish();
}

void save_form_factors(const std::string& path, const FormFactorMatrix& f, uint64_t key,
                       const FormFactorOptions* options, uint32_t revision) {
  if (f.f.size() != f.size * f.size)
    throw std::invalid_argument(path + ": form-factor matrix is not N×N");
  Header h;
  h.key = key;
  h.n = f.size;
  h.revision = revision;
  if (options) {
    h.method = static_cast<uint32_t>(options->method);
    h.flags = kFlagSettings;
    h.quadrature_points = static_cast<uint32_t>(options->quadrature_points);
    h.rays_per_patch = static_cast<uint32_t>(options->rays_per_patch);
    h.emitter_rays_per_patch = static_cast<uint32_t>(options->emitter_rays_per_patch);
    h.sampling = static_cast<uint32_t>(options->sampling);
    h.emitter_rows = static_cast<uint32_t>(options->emitter_rows);
    h.hemicube_resolution = static_cast<uint32_t>(options->hemicube_resolution);
    h.seed = options->seed;
  }
  const std::size_t header_size = h.header_size;
  h.file_size = header_size + f.f.size() * sizeof(float);
  unsigned char header[kHeaderSize];
  encode(h, header);
  h.checksum = crc32c(f.f.data(), f.f.size() * sizeof(float), crc32c(header, header_size));
  encode(h, header);
  const Status status = replace_file_atomically(path, [&](const std::string& temporary) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(temporary.c_str(), "wb"));
    if (!file)
      return Status::Error(path + ": cannot create " + temporary + ": " + std::strerror(errno));
    const bool written =
        std::fwrite(header, 1, header_size, file.get()) == header_size &&
        std::fwrite(f.f.data(), sizeof(float), f.f.size(), file.get()) == f.f.size();
    if (!written || std::fclose(file.release()) != 0)
      return Status::Error(path + ": cannot write " + temporary + ": " + std::strerror(errno));
    return Status::Ok();
  });
  if (!status.ok()) throw std::runtime_error(status.message());
}

namespace {

using File = std::unique_ptr<std::FILE, FileCloser>;

// Opens PATH and checks magic, version, header size, the size fields and the bytes present;
// fills *h and header[0 .. h->header_size). The file is left at the matrix.
File open_cache(const std::string& path, Header* h, unsigned char* header) {
  File file(std::fopen(path.c_str(), "rb"));
  if (!file)
    throw std::runtime_error(path + ": cannot open form-factor cache: " + std::strerror(errno));
  std::memset(header, 0, kHeaderSize);
  const std::size_t got = std::fread(header, 1, kHeaderSizeV1, file.get());
  if (got >= 8 && std::memcmp(header, kMagic, 8) != 0)
    throw std::runtime_error(path + ": not a prt form-factor cache (bad magic)");
  if (got < kHeaderSizeV1)
    throw std::runtime_error(path + ": truncated form-factor cache (header)");
  h->header_size = static_cast<uint32_t>(kHeaderSizeV1);
  decode(header, h);
  const bool v1 = h->version == 1 && h->header_size == kHeaderSizeV1;
  const bool v2 = h->version == 2 && h->header_size == kHeaderSizeV2;
  const bool v3 = h->version == 3 && h->header_size == kHeaderSize;
  if (!v1 && !v2 && !v3)
    throw std::runtime_error(path + ": form-factor cache version " + std::to_string(h->version) +
                             " (this prt reads versions 1 to " + std::to_string(kVersion) + ")");
  if (!v1) {
    const std::size_t rest = h->header_size - kHeaderSizeV1;
    if (std::fread(header + kHeaderSizeV1, 1, rest, file.get()) != rest)
      throw std::runtime_error(path + ": truncated form-factor cache (header)");
    decode(header, h);
  }
  // N is bounded before any size arithmetic, so a hostile count cannot overflow it.
  if (h->n > (uint64_t(1) << 20) || h->file_size != h->header_size + h->n * h->n * sizeof(float) ||
      (v1 && h->flags != 0) || (h->flags & ~kFlagSettings) != 0 || h->method > 2)
    throw std::runtime_error(path + ": corrupt form-factor cache (size fields disagree)");
  if (h->revision == 0 || h->reserved != 0)
    throw std::runtime_error(path +
                             ": corrupt form-factor cache (revision 0 or reserved bytes set)");
  if (std::fseek(file.get(), 0, SEEK_END) != 0)
    throw std::runtime_error(path + ": cannot seek: " + std::strerror(errno));
  const long present = std::ftell(file.get());
  if (present < 0 || uint64_t(present) < h->file_size)
    throw std::runtime_error(path + ": truncated form-factor cache (" + std::to_string(present) +
                             " of " + std::to_string(h->file_size) + " bytes)");
  if (uint64_t(present) > h->file_size)
    throw std::runtime_error(path + ": corrupt form-factor cache (unexpected bytes after the end)");
  std::fseek(file.get(), static_cast<long>(h->header_size), SEEK_SET);
  std::memset(header + kChecksumOffset, 0, 4);  // as the checksum takes it
  return file;
}

}  // namespace

uint32_t form_factor_cache_revision(const std::string& path) {
  Header h;
  unsigned char header[kHeaderSize];
  open_cache(path, &h, header);
  return h.revision;
}

FormFactorMatrix load_form_factors(const std::string& path, uint64_t key) {
  Header h;
  unsigned char header[kHeaderSize];
  File file = open_cache(path, &h, header);
  if (h.revision != kFormFactorRevision)
    throw std::runtime_error(path + ": form factors of algorithm revision " +
                             std::to_string(h.revision) + ", this prt computes revision " +
                             std::to_string(kFormFactorRevision) +
                             "; give another --form-factor-cache or delete this one");
  if (h.key != key)
    throw std::runtime_error(path + ": made for another scene or other form-factor options (key " +
                             hex(h.key) + ", expected " + hex(key) +
                             "); give another --form-factor-cache or delete this one");
  FormFactorMatrix m;
  m.size = h.n;
  detail::assign_zeroed_large(&m.f, m.size * m.size);
  if (std::fread(m.f.data(), sizeof(float), m.f.size(), file.get()) != m.f.size())
    throw std::runtime_error(path + ": cannot read form-factor cache: " + std::strerror(errno));
  if (crc32c(m.f.data(), m.f.size() * sizeof(float), crc32c(header, h.header_size)) != h.checksum)
    throw std::runtime_error(path + ": corrupt form-factor cache (checksum mismatch)");
  // A NaN or infinite factor would spread through every patch's radiosity in the solve.
  for (std::size_t k = 0; k < m.f.size(); ++k)
    if (!std::isfinite(m.f[k]))
      throw std::runtime_error(
          path + ": corrupt form-factor cache (non-finite form factor at row " +
          std::to_string(k / m.size) + ", column " + std::to_string(k % m.size) + ")");
  return m;
}

FormFactorCacheInfo read_form_factor_cache_info(const std::string& path) {
  Header h;
  unsigned char header[kHeaderSize];
  File file = open_cache(path, &h, header);
  // The checksum, read in pieces (the matrix is not kept).
  uint32_t crc = crc32c(header, h.header_size);
  std::vector<unsigned char> chunk(std::size_t(1) << 20);
  for (uint64_t left = h.file_size - h.header_size; left > 0;) {
    const std::size_t want = static_cast<std::size_t>(std::min<uint64_t>(left, chunk.size()));
    if (std::fread(chunk.data(), 1, want, file.get()) != want)
      throw std::runtime_error(path + ": cannot read form-factor cache: " + std::strerror(errno));
    crc = crc32c(chunk.data(), want, crc);
    left -= want;
  }
  if (crc != h.checksum)
    throw std::runtime_error(path + ": corrupt form-factor cache (checksum mismatch)");
  FormFactorCacheInfo info;
  info.version = h.version;
  info.revision = h.revision;
  info.patches = h.n;
  info.key = h.key;
  info.file_size = h.file_size;
  info.settings_recorded = (h.flags & kFlagSettings) != 0;
  if (info.settings_recorded) {
    FormFactorOptions& o = info.options;
    o.method = static_cast<FormFactorMethod>(h.method);
    o.quadrature_points = static_cast<int>(h.quadrature_points);
    o.rays_per_patch = static_cast<int>(h.rays_per_patch);
    o.emitter_rays_per_patch = static_cast<int>(h.emitter_rays_per_patch);
    o.sampling = h.sampling == 0 ? RaySampling::Independent : RaySampling::Sobol;
    o.emitter_rows = h.emitter_rows == 0 ? EmitterRows::Rays : EmitterRows::Reciprocal;
    o.hemicube_resolution = static_cast<int>(h.hemicube_resolution);
    o.seed = h.seed;
  }
  return info;
}

bool is_form_factor_cache(const std::string& path) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  char magic[8];
  return file && std::fread(magic, 1, 8, file.get()) == 8 && std::memcmp(magic, kMagic, 8) == 0;
}

}  // namespace prt::radiosity
