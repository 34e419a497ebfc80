// report/src/stability_report.cpp — runs the stability cases (stability_*.cpp) and writes
// DIR/stability.md and DIR/stability.json (see report/stability_report.h, docs/STABILITY.md).
#include "report/stability_report.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "report/plot_svg.h"
#include "sh/basis.h"
#include "report/stability_cases.h"

namespace prt::report::stability {

double CaseResult::number(const std::string& key) const {
  for (const auto& [k, v] : numbers)
    if (k == key) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

CaseResult run_case(const std::string& group, const std::string& name, const std::string& criterion,
                    const std::function<void(CaseResult&)>& body) {
  CaseResult r;
  r.group = group;
  r.name = name;
  r.criterion = criterion;
  const auto t0 = std::chrono::steady_clock::now();
  try {
    body(r);
  } catch (const std::exception& e) {
    r.passed = false;
    r.detail = std::string("exception: ") + e.what();
  } catch (...) {
    r.passed = false;
    r.detail = "unknown exception";
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  for (const auto& [key, value] : r.numbers) {
    if (!std::isfinite(value)) {
      r.passed = false;
      r.detail += "; non-finite figure " + key;
    }
  }
  return r;
}

std::vector<std::function<CaseResult()>> all_cases(const CaseOptions& o) {
  const int big_w = o.quick ? 2048 : 8192, big_h = big_w / 2;
  return {
      [o] { return check_sh_evaluation_at_poles(o); },
      [o] { return check_rotation_orthogonality(o); },
      [o] { return check_bright_sun(o, 1e5); },
      [o] { return check_bright_sun(o, 1e6); },
      [o] { return check_black_map(o); },
      [o] { return check_single_bright_texel(o); },
      [o] { return check_nan_inf_pixels(o); },
      [o] { return check_map_size(o, 1, 1); },
      [o] { return check_map_size(o, 2, 1); },
      [o, big_w, big_h] { return check_map_size(o, big_w, big_h); },
      [o] { return check_cavity_furnace(o, 0.9); },
      [o] { return check_cavity_furnace(o, 0.99); },
      [o] { return check_cavity_furnace(o, 0.999); },
      [o] { return check_solver_bounded(o); },
      [o] { return check_albedo_refused(o); },
      [o] { return check_degenerate_geometry(o); },
      [o] { return check_scene_scale(o, 1e-3f); },
      [o] { return check_scene_scale(o, 1e4f); },
      [o] { return check_vertex_inside_box(o); },
      [o] { return check_half_overflow(o); },
  };
}

}  // namespace prt::report::stability

namespace prt::report {
namespace {

std::string format_number(double v) {
  char buf[32];
  if (v == std::floor(v) && std::fabs(v) < 1e9)
    std::snprintf(buf, sizeof buf, "%.0f", v);
  else
    std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

}  // namespace

int run_stability_report(const std::string& out_dir, bool quick) {
  namespace st = stability;
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) throw std::runtime_error(out_dir + ": cannot create directory: " + ec.message());
  st::CaseOptions options;
  options.quick = quick;
  std::vector<st::CaseResult> results;
  int failed = 0;
  for (const auto& run : st::all_cases(options)) {
    results.push_back(run());
    const st::CaseResult& r = results.back();
    if (!r.passed) ++failed;
    std::printf("%s %-16s %-32s %7.2f s  %s\n", r.passed ? "PASS" : "FAIL", r.group.c_str(),
                r.name.c_str(), r.seconds, r.detail.c_str());
    std::fflush(stdout);
  }

  nlohmann::json j;
  j["sh_basis"] = sh::kBasisConvention;
  j["quick"] = quick;
  j["cases"] = nlohmann::json::array();
  j["failed"] = failed;
  std::ostringstream md;
  md << "# prt stability report" << (quick ? " (quick)" : "") << "\n\n"
     << "SH basis: real orthonormal, no Condon–Shortley phase, k = l(l+1)+m; frame glTF (+Y "
        "up). What each case means: docs/STABILITY.md.\n\n"
     << "**" << (results.size() - failed) << " of " << results.size() << " cases passed.**\n\n"
     << "| result | group | case | seconds | detail |\n|---|---|---|---|---|\n";
  for (const auto& r : results)
    md << "| " << (r.passed ? "pass" : "**FAIL**") << " | " << r.group << " | " << r.name << " | "
       << format_number(r.seconds) << " | " << r.detail << " |\n";
  for (const auto& r : results) {
    nlohmann::json c;
    c["group"] = r.group;
    c["name"] = r.name;
    c["passed"] = r.passed;
    c["criterion"] = r.criterion;
    c["detail"] = r.detail;
    c["seconds"] = r.seconds;
    nlohmann::json numbers = nlohmann::json::object();
    for (const auto& [k, v] : r.numbers)
      numbers[k] = std::isfinite(v) ? nlohmann::json(v) : nlohmann::json();
    c["numbers"] = numbers;
    if (!r.table_header.empty()) {
      c["table"] = {{"header", r.table_header}, {"rows", r.table_rows}};
    }
    j["cases"].push_back(c);

    md << "\n## " << r.group << ": " << r.name << " — " << (r.passed ? "pass" : "**FAIL**")
       << "\n\nPass means: " << r.criterion << ".\n\n"
       << r.detail << "\n\n";
    if (!r.numbers.empty()) {
      md << "| figure | value |\n|---|---|\n";
      for (const auto& [k, v] : r.numbers) md << "| " << k << " | " << format_number(v) << " |\n";
      md << "\n";
    }
    if (!r.table_header.empty()) {
      md << "|";
      for (const auto& h : r.table_header) md << " " << h << " |";
      md << "\n|";
      for (std::size_t i = 0; i < r.table_header.size(); ++i) md << "---|";
      md << "\n";
      for (const auto& row : r.table_rows) {
        md << "|";
        for (const auto& cell : row) md << " " << cell << " |";
        md << "\n";
      }
      md << "\n";
    }
  }
  const std::filesystem::path dir(out_dir);
  const std::vector<std::string> names = stability_file_names();
  write_text_file((dir / names[0]).string(), j.dump(2) + "\n");
  write_text_file((dir / names[1]).string(), md.str());
  return failed;
}

std::vector<std::string> stability_file_names() {
  return {"stability.json", "stability.md"};
}

}  // namespace prt::report
