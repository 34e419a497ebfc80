// tests/golden/golden_update.h — replacing a golden reference by a new render, as
// scripts/update-golden.sh does through `prt_golden update`.
//
// References are stored as the test reads them: PNG as rendered; EXR as 16-bit half floats (a
// quarter of the float file; rounding ≤ 2^-11 relative, a tenth of the EXR tolerance). A
// reference is rewritten only when its stored pixels would change, so an update that changes
// nothing leaves the files (and git) untouched.
#pragma once

#include <filesystem>
#include <string>

#include "image_compare.h"

namespace prt::golden {

struct UpdateResult {
  bool existed = false;    // there was a reference before
  bool rewritten = false;  // the stored pixels changed (or it is new) and the file was written
  Comparison comparison;   // new render against the old reference (when it existed)
  std::string describe() const;  // e.g. "unchanged", "changed within tolerance: ...", "new"
};

// Compares `render` with `reference` and, when the stored pixels differ, writes the render to
// `reference` in its stored form. Throws std::runtime_error "PATH: problem" on I/O errors.
UpdateResult update_reference(const std::filesystem::path& reference,
                              const std::filesystem::path& render);

}  // namespace prt::golden
