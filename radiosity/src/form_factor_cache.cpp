#include "radiosity/form_factor_cache.h"

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
constexpr uint32_t kVersion = 1;
constexpr std::size_t kHeaderSize = 64;
constexpr std::size_t kChecksumOffset = 48;

struct Header {
  uint32_t version = kVersion, header_size = kHeaderSize;
  uint64_t key = 0, n = 0, file_size = 0;
  uint32_t method = 0, checksum = 0;
};

// The 64 header bytes, little-endian (the machines prt runs on; docs/FORMAT.md).
void encode(const Header& h, unsigned char* out) {
  std::memset(out, 0, kHeaderSize);
  std::memcpy(out, kMagic, 8);
  std::memcpy(out + 8, &h.version, 4);
  std::memcpy(out + 12, &h.header_size, 4);
  std::memcpy(out + 16, &h.key, 8);
  std::memcpy(out + 24, &h.n, 8);
  std::memcpy(out + 32, &h.file_size, 8);
  std::memcpy(out + 40, &h.method, 4);
  std::memcpy(out + kChecksumOffset, &h.checksum, 4);
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
  return h.finish();
}

void save_form_factors(const std::string& path, const FormFactorMatrix& f, uint64_t key) {
  if (f.f.size() != f.size * f.size)
    throw std::invalid_argument(path + ": form-factor matrix is not N×N");
  Header h;
  h.key = key;
  h.n = f.size;
  h.file_size = kHeaderSize + f.f.size() * sizeof(float);
  unsigned char header[kHeaderSize];
  encode(h, header);
  h.checksum = crc32c(f.f.data(), f.f.size() * sizeof(float), crc32c(header, kHeaderSize));
  encode(h, header);
  const Status status = replace_file_atomically(path, [&](const std::string& temporary) {
    std::unique_ptr<std::FILE, FileCloser> file(std::fopen(temporary.c_str(), "wb"));
    if (!file)
      return Status::Error(path + ": cannot create " + temporary + ": " + std::strerror(errno));
    const bool written =
        std::fwrite(header, 1, kHeaderSize, file.get()) == kHeaderSize &&
        std::fwrite(f.f.data(), sizeof(float), f.f.size(), file.get()) == f.f.size();
    if (!written || std::fclose(file.release()) != 0)
      return Status::Error(path + ": cannot write " + temporary + ": " + std::strerror(errno));
    return Status::Ok();
  });
  if (!status.ok()) throw std::runtime_error(status.message());
}

FormFactorMatrix load_form_factors(const std::string& path, uint64_t key) {
  std::unique_ptr<std::FILE, FileCloser> file(std::fopen(path.c_str(), "rb"));
  if (!file)
    throw std::runtime_error(path + ": cannot open form-factor cache: " + std::strerror(errno));
  unsigned char header[kHeaderSize];
  const std::size_t got = std::fread(header, 1, kHeaderSize, file.get());
  if (got >= 8 && std::memcmp(header, kMagic, 8) != 0)
    throw std::runtime_error(path + ": not a prt form-factor cache (bad magic)");
  if (got < kHeaderSize) throw std::runtime_error(path + ": truncated form-factor cache (header)");
  Header h;
  std::memcpy(&h.version, header + 8, 4);
  std::memcpy(&h.header_size, header + 12, 4);
  std::memcpy(&h.key, header + 16, 8);
  std::memcpy(&h.n, header + 24, 8);
  std::memcpy(&h.file_size, header + 32, 8);
  std::memcpy(&h.method, header + 40, 4);
  std::memcpy(&h.checksum, header + kChecksumOffset, 4);
  if (h.version != kVersion || h.header_size != kHeaderSize)
    throw std::runtime_error(path + ": form-factor cache version " + std::to_string(h.version) +
                             " (this prt reads version " + std::to_string(kVersion) + ")");
  // N is bounded before any size arithmetic, so a hostile count cannot overflow it.
  if (h.n > (uint64_t(1) << 20) || h.file_size != kHeaderSize + h.n * h.n * sizeof(float))
    throw std::runtime_error(path + ": corrupt form-factor cache (size fields disagree)");
  if (std::fseek(file.get(), 0, SEEK_END) != 0)
    throw std::runtime_error(path + ": cannot seek: " + std::strerror(errno));
  const long present = std::ftell(file.get());
  if (present < 0 || uint64_t(present) < h.file_size)
    throw std::runtime_error(path + ": truncated form-factor cache (" + std::to_string(present) +
                             " of " + std::to_string(h.file_size) + " bytes)");
  if (uint64_t(present) > h.file_size)
    throw std::runtime_error(path + ": corrupt form-factor cache (unexpected bytes after the end)");
  if (h.key != key)
    throw std::runtime_error(path + ": made for another scene or other form-factor options (key " +
                             hex(h.key) + ", expected " + hex(key) +
                             "); give another --form-factor-cache or delete this one");
  FormFactorMatrix m;
  m.size = h.n;
  detail::assign_zeroed_large(&m.f, m.size * m.size);
  std::fseek(file.get(), static_cast<long>(kHeaderSize), SEEK_SET);
  if (std::fread(m.f.data(), sizeof(float), m.f.size(), file.get()) != m.f.size())
    throw std::runtime_error(path + ": cannot read form-factor cache: " + std::strerror(errno));
  std::memset(header + kChecksumOffset, 0, 4);
  if (crc32c(m.f.data(), m.f.size() * sizeof(float), crc32c(header, kHeaderSize)) != h.checksum)
    throw std::runtime_error(path + ": corrupt form-factor cache (checksum mismatch)");
  // A NaN or infinite factor would spread through every patch's radiosity in the solve.
  for (std::size_t k = 0; k < m.f.size(); ++k)
    if (!std::isfinite(m.f[k]))
      throw std::runtime_error(
          path + ": corrupt form-factor cache (non-finite form factor at row " +
          std::to_string(k / m.size) + ", column " + std::to_string(k % m.size) + ")");
  return m;
}

}  // namespace prt::radiosity
