// report/src/report_settings.cpp — the settings `prt report` sweeps (report.h) and their names.

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "report/report.h"
#include "report_state.h"

namespace prt::report::detail {

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string precision_name(prt::Precision p) {
  return p == prt::Precision::F16 ? "f16" : "f32";
}

std::string bounces_name(int b) {
  return b < 0 ? std::string("converged") : std::to_string(b);
}

bool is_haar(const ReportSetting& s) {
  return s.basis == ReportBasis::Haar;
}

std::string basis_name(const ReportSetting& s) {
  return is_haar(s) ? "haar" : "sh";
}

// Storage of the coefficients: f32/f16 for SH, the quantisation for Haar.
std::string storage_name(const ReportSetting& s) {
  return is_haar(s) ? std::string("i") + std::to_string(static_cast<int>(kHaarQuantization))
                    : precision_name(s.precision);
}

int64_t haar_coefficient_count(int cube) {
  return int64_t{6} * cube * cube;
}

// The number of lighting terms a Haar setting uses (all = 6N²).
int64_t haar_terms_used(const ReportSetting& s) {
  return s.terms > 0 ? std::min(s.terms, haar_coefficient_count(s.cube))
                     : haar_coefficient_count(s.cube);
}

std::string terms_text(const ReportSetting& s) {
  const std::string n = std::to_string(haar_terms_used(s));
  return s.terms > 0 ? n : "all " + n;
}

std::string describe(const ReportSetting& s) {
  if (is_haar(s))
    return "Haar cube " + std::to_string(s.cube) + ", " + terms_text(s) +
           " lighting terms (non-linear), bounces " + bounces_name(s.bounces) + ", " +
           storage_name(s);
  return "SH order " + std::to_string(s.order) + ", " + std::to_string(s.samples) +
         " spp, bounces " + bounces_name(s.bounces) + ", " + precision_name(s.precision);
}

std::string short_label(const ReportSetting& s) {
  // Appended piece by piece: GCC 12 warns falsely (-Wrestrict) on "literal" + std::to_string().
  std::string t(is_haar(s) ? "H" : "n");
  if (is_haar(s)) {
    t += std::to_string(s.cube);
    t += " K";
    t += s.terms > 0 ? std::to_string(s.terms) : std::string("all");
    return t;
  }
  t += std::to_string(s.order);
  t += ' ';
  t += std::to_string(s.samples);
  if (s.bounces >= 0) {
    t += " b";
    t += std::to_string(s.bounces);
  }
  if (s.precision == prt::Precision::F16) t += " f16";
  return t;
}

bool same(const ReportSetting& a, const ReportSetting& b) {
  return a.basis == b.basis && a.order == b.order && a.samples == b.samples &&
         a.bounces == b.bounces && a.precision == b.precision && a.cube == b.cube &&
         a.terms == b.terms;
}

std::string percent(double x) {
  char buf[32];
  if (!std::isfinite(x)) return "inf";
  std::snprintf(buf, sizeof buf, x < 0.01 ? "%.3f%%" : "%.2f%%", 100.0 * x);
  return buf;
}

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, s < 0.01 ? "%.2f ms" : "%.2f s", s < 0.01 ? s * 1e3 : s);
  return buf;
}

}  // namespace prt::report::detail

namespace prt::report {

using namespace detail;

ReportSetting base_setting(bool quick) {
  ReportSetting s;
  s.order = 6;
  s.samples = quick ? 256 : 1024;
  s.bounces = -1;
  s.precision = prt::Precision::F32;
  return s;
}

std::vector<ReportAxis> report_axes(bool quick, const std::optional<std::vector<int>>& haar_cubes) {
  const ReportSetting base = base_setting(quick);
  std::vector<ReportAxis> axes;
  auto vary = [&](const std::string& name, auto values, auto apply) {
    ReportAxis axis{name, {}};
    for (auto v : values) {
      ReportSetting s = base;
      apply(s, v);
      axis.settings.push_back(s);
    }
    axes.push_back(axis);
  };
  const std::vector<int> orders =
      quick ? std::vector<int>{2, 3, 4, 5, 6} : std::vector<int>{2, 3, 4, 5, 6, 8, 10, 12, 16};
  const std::vector<int> samples =
      quick ? std::vector<int>{64, 256, 1024} : std::vector<int>{64, 256, 1024, 4096, 16384};
  const std::vector<int> bounces =
      quick ? std::vector<int>{0, 1, -1} : std::vector<int>{0, 1, 2, 4, 8, -1};
  vary("order", orders, [](ReportSetting& s, int v) { s.order = v; });
  vary("samples", samples, [](ReportSetting& s, int v) { s.samples = v; });
  vary("bounces", bounces, [](ReportSetting& s, int v) { s.bounces = v; });
  vary("precision", std::vector<prt::Precision>{prt::Precision::F32, prt::Precision::F16},
       [](ReportSetting& s, prt::Precision v) { s.precision = v; });
  ReportAxis grid{"grid", {}};
  const std::vector<int> grid_orders =
      quick ? std::vector<int>{2, 4, 6} : std::vector<int>{2, 4, 6, 8, 10};
  const std::vector<int> grid_samples =
      quick ? std::vector<int>{64, 256} : std::vector<int>{64, 256, 1024, 4096};
  for (int n : grid_orders)
    for (int N : grid_samples) {
      ReportSetting s = base;
      s.order = n, s.samples = N;
      grid.settings.push_back(s);
    }
  axes.push_back(grid);
  ReportAxis haar{"haar", {}};
  for (int cube : haar_cubes ? *haar_cubes : default_haar_cubes(quick))
    for (int64_t k : haar_terms(quick)) {
      if (k >= haar_coefficient_count(cube)) continue;  // the same as all terms
      ReportSetting s;
      s.basis = ReportBasis::Haar;
      s.order = 0, s.samples = 0;
      s.bounces = base.bounces;
      s.precision = prt::Precision::F32;
      s.cube = cube;
      s.terms = k;
      haar.settings.push_back(s);
    }
  if (!haar.settings.empty()) axes.push_back(haar);
  return axes;
}

std::vector<double> default_auto_tolerances(bool quick) {
  return quick ? std::vector<double>{0.05} : std::vector<double>{0.01, 0.05, 0.1};
}

std::vector<int> default_haar_cubes(bool quick) {
  return quick ? std::vector<int>{8} : std::vector<int>{8, 16};
}

std::vector<int64_t> haar_terms(bool quick) {
  return quick ? std::vector<int64_t>{10, 30, 100, 0}
               : std::vector<int64_t>{10, 30, 100, 300, 1000, 0};
}

}  // namespace prt::report
