// radiosity/form_factor_cache.h — a form-factor matrix saved to disk and loaded back, so that
// a scene whose geometry did not change is re-solved without recomputing its form factors
// (new emission or albedo: neither enters F). Layout: docs/FORMAT.md, "Form-factor cache".
//
// The file is bound to what F depends on by a 64-bit key: FNV-1a-64 over 32-bit words with the
// splitmix64 finaliser (numerics::WordHash of numerics/hash.h, as the geometry fingerprint of
// prt/formats/geometry_check.h; [17] of docs/REFERENCES.md) of the patch count, every patch's
// corners (float bit patterns, −0 as +0) and the method's options (analytic: quadrature points;
// rays: rays per patch and seed; with emitter_rays_per_patch > 0 or reciprocal emitter rows also
// that count and the indices of the emitting patches; the sampling unless Independent; the emitter
// rows and quadrature points unless Rays; hemicube: resolution) with the method's number. Emission
// values do not enter it. A loaded file must carry the key of the caller's patches and options, its
// size must match N, its CRC-32C (prt/formats/crc32c.h) must hold and every factor must be
// finite. Errors throw
// std::runtime_error with one line that names the file; saving is atomic (prt/core/atomic_file.h),
// so a failed save leaves no file behind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"

namespace prt::radiosity {

uint64_t form_factor_key(const std::vector<Patch>& patches, const FormFactorOptions& options);

// Writes F with `key` to PATH (replacing it atomically): with `options`, version 2, which also
// records the method and the settings F was computed with (what `prt info` shows); without,
// version 1 (docs/FORMAT.md).
void save_form_factors(const std::string& path, const FormFactorMatrix& f, uint64_t key,
                       const FormFactorOptions* options = nullptr);

// Reads PATH, checking magic, version, size, checksum and that its key equals `key`:
// "PATH: made for another scene or other form-factor options (key …, expected …)" otherwise.
// Versions 1 and 2 load.
FormFactorMatrix load_form_factors(const std::string& path, uint64_t key);

// What a cache holds, for `prt info`: the checks of load_form_factors except the key.
struct FormFactorCacheInfo {
  uint32_t version = 0;
  uint64_t patches = 0, key = 0, file_size = 0;
  bool settings_recorded = false;  // version 2 written with options: `options` is valid
  FormFactorOptions options;       // method and settings (only what the method uses matters)
};
FormFactorCacheInfo read_form_factor_cache_info(const std::string& path);

// True when PATH starts with the cache's magic.
bool is_form_factor_cache(const std::string& path);

}  // namespace prt::radiosity
