// report/stability_cases.h — the stability cases behind run_stability_report()
// (report/stability_report.h), one function each, so that a single case can be run on its own
// (the tests run them one by one, with the same code as the report).
//
// Conventions: SH basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase,
// k = l(l+1)+m, polar axis +z), glTF frame (+Y up), lat-long maps as in sh/env_map.h.
// Every case catches its own exceptions: one that throws is returned as failed with the message.
// What each case checks and its pass criterion: docs/STABILITY.md.
#pragma once

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace prt::report::stability {

struct CaseResult {
  std::string group;      // "numerics", "environment", "interreflection", "geometry", "storage"
  std::string name;       // short identifier, e.g. "sh_poles_l200"
  std::string criterion;  // what "pass" means, one sentence
  bool passed = false;
  std::string detail;  // one line: what happened (the error message where an error is right)
  std::vector<std::pair<std::string, double>> numbers;  // measured figures, in order
  std::vector<std::string> table_header;                // optional table (markdown in the report)
  std::vector<std::vector<std::string>> table_rows;
  double seconds = 0;

  void add(const std::string& key, double value) { numbers.emplace_back(key, value); }
  double number(const std::string& key) const;  // NaN when absent
};

struct CaseOptions {
  bool quick = false;  // smaller maps and meshes (the tests use quick)
};

// Numerics.
CaseResult check_sh_evaluation_at_poles(const CaseOptions& options);
CaseResult check_rotation_orthogonality(const CaseOptions& options);
// Environments.
CaseResult check_bright_sun(const CaseOptions& options, double sun_to_sky);
CaseResult check_black_map(const CaseOptions& options);
CaseResult check_single_bright_texel(const CaseOptions& options);
CaseResult check_nan_inf_pixels(const CaseOptions& options);
CaseResult check_map_size(const CaseOptions& options, int width, int height);
// Interreflection.
CaseResult check_cavity_furnace(const CaseOptions& options, double albedo);
CaseResult check_solver_bounded(const CaseOptions& options);
CaseResult check_albedo_refused(const CaseOptions& options);
// Geometry.
CaseResult check_degenerate_geometry(const CaseOptions& options);
CaseResult check_scene_scale(const CaseOptions& options, float scale);
CaseResult check_vertex_inside_box(const CaseOptions& options);
// Storage.
CaseResult check_half_overflow(const CaseOptions& options);

// Every case of the report, in report order (the large map is 8192×4096, or 2048×1024 when
// quick).
std::vector<std::function<CaseResult()>> all_cases(const CaseOptions& options);

// Runs `body` with timing and exception capture (an exception fails the case, its message
// becomes the detail). Also fails the case if any recorded number is NaN or ±Inf.
CaseResult run_case(const std::string& group, const std::string& name, const std::string& criterion,
                    const std::function<void(CaseResult&)>& body);

}  // namespace prt::report::stability
