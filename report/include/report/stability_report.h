// report/stability_report.h — the stability cases of `prt report --stability`:
// numerics at high SH order and near the poles, extreme environments (bright suns, black maps,
// NaN/Inf texels, 1×1 and 8192×4096 maps), stiff interreflection (the spherical-cavity furnace
// at albedo 0.9 .. 0.999, B = ρf/(1 − ρ(1 − f))), degenerate geometry, scale invariance, and
// float16 overflow. The same case code runs in the tests (tests/report/test_stability*.cpp).
//
// Conventions: SH basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase,
// k = l(l+1)+m), glTF scene frame (+Y up), lat-long maps as in sh/env_map.h. Radiance in the
// map's units. What each case checks and what "pass" means: docs/STABILITY.md.
#pragma once

#include <string>
#include <vector>

namespace prt::report {

// Runs every stability case, writes out_dir/stability.md and out_dir/stability.json (creating
// out_dir; files are written atomically) and prints one line per case to stdout. `quick` uses
// smaller maps and meshes (the 8192×4096 map becomes 2048×1024). Returns the number of failed
// cases (0 = all passed). Throws std::runtime_error "PATH: problem" only when the report
// cannot be written; a case that throws is recorded as failed with its message.
int run_stability_report(const std::string& out_dir, bool quick);

// The names of the files run_stability_report writes into out_dir.
std::vector<std::string> stability_file_names();

}  // namespace prt::report
