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
// rows and quadrature points unless Rays; hemicube: resolution) with the method's number, and the
// revision of the algorithms (kFormFactorRevision). Emission values do not enter it. A loaded file
// must carry the algorithms' revision and the key of the caller's patches and options, its size
// must match N, its CRC-32C (prt/formats/crc32c.h) must hold and every factor must be finite.
// Errors throw
// std::runtime_error with one line that names the file; saving is atomic (prt/core/atomic_file.h),
// so a failed save leaves no file behind.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "radiosity/form_factors.h"
#include "radiosity/patches.h"

namespace prt::radiosity {

// The revision of the form-factor algorithms, raised whenever a method computes another F for the
// same patches and options: 1, every cache written before revisions were recorded (versions 1
// and 2); 2, reciprocal emitter rows replaced by the emitter's own ray row when their sums
// disagree (form_factors.h, EmitterRows). A cache of an earlier revision is stale: `prt radiosity`
// recomputes it and saves over it (radiosity/scene_solve.h).
constexpr uint32_t kFormFactorRevision = 2;

uint64_t form_factor_key(const std::vector<Patch>& patches, const FormFactorOptions& options);

// Writes F with `key` to PATH (replacing it atomically) as version 3, which records `revision`
// (the algorithms' that computed F: a merge of parts made by an earlier prt passes theirs) and,
// with `options`, the method and the settings F was computed with (what `prt info` shows;
// docs/FORMAT.md).
void save_form_factors(const std::string& path, const FormFactorMatrix& f, uint64_t key,
                       const FormFactorOptions* options = nullptr,
                       uint32_t revision = kFormFactorRevision);

// The revision PATH records (1 for versions 1 and 2), after the header checks of
// load_form_factors; the matrix is not read.
uint32_t form_factor_cache_revision(const std::string& path);

// Reads PATH, checking magic, version, size, checksum, that its revision is kFormFactorRevision
// ("PATH: form factors of algorithm revision R, this prt computes revision 2; …") and that its key
// equals `key`: "PATH: made for another scene or other form-factor options (key …, expected …)"
// otherwise. Versions 1, 2 and 3 are read.
FormFactorMatrix load_form_factors(const std::string& path, uint64_t key);

// What a cache holds, for `prt info`: the checks of load_form_factors except the revision and
// the key.
struct FormFactorCacheInfo {
  uint32_t version = 0, revision = 0;
  uint64_t patches = 0, key = 0, file_size = 0;
  bool settings_recorded = false;  // version 2 written with options: `options` is valid
  FormFactorOptions options;       // method and settings (only what the method uses matters)
};
FormFactorCacheInfo read_form_factor_cache_info(const std::string& path);

// True when PATH starts with the cache's magic.
bool is_form_factor_cache(const std::string& path);

}  // namespace prt::radiosity
