// report/src/ssao_report_outputs.cpp — the tables, summary and pictures of `prt report --ssao`
// (ssao_report_outputs.h).
#include "report/ssao_report_outputs.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "prt/core/atomic_file.h"
#include "relight/image_io.h"

namespace prt::report {
namespace {

void write_text(const std::string& path, const std::string& text) {
  const prt::Status s = prt::write_file_atomically(path, text.data(), text.size());
  if (!s.ok()) throw std::runtime_error(s.message());
}

// The regions of RegionErrors by name, distance bins as "distance_K".
std::vector<std::pair<std::string, const ErrorAccumulator*>> regions(const RegionErrors& e) {
  std::vector<std::pair<std::string, const ErrorAccumulator*>> r = {{"all", &e.all},
                                                                    {"contact", &e.contact},
                                                                    {"thin", &e.thin},
                                                                    {"edge", &e.edge},
                                                                    {"interior", &e.interior}};
  for (std::size_t i = 0; i < e.distance.size(); ++i)
    r.emplace_back("distance_" + std::to_string(i), &e.distance[i]);
  return r;
}

// The bin's eye-distance range [lo, hi).
std::pair<double, double> bin_range(const SsaoReportSettings& s, std::size_t bin, std::size_t n) {
  const double w = (s.distance_hi - s.distance_lo) / static_cast<double>(n);
  return {s.distance_lo + w * static_cast<double>(bin),
          s.distance_lo + w * static_cast<double>(bin + 1)};
}

std::string csv_table(const std::vector<SsaoResult>& results, const SsaoReportSettings& s) {
  std::ostringstream out;
  out << "camera,estimate,truth,region,distance_lo,distance_hi,pixels,relative_rms,rms,bias,"
         "truth_mean\n";
  char line[320];
  for (const SsaoResult& r : results)
    for (const auto& [name, acc] : regions(r.errors)) {
      const ErrorStats st = acc->stats();
      double lo = 0, hi = 0;
      if (name.rfind("distance_", 0) == 0)
        std::tie(lo, hi) = bin_range(s, std::stoul(name.substr(9)), r.errors.distance.size());
      std::snprintf(line, sizeof line, "%s,%s,%s,%s,%.6g,%.6g,%llu,%.6f,%.6f,%.6f,%.6f\n",
                    r.camera.c_str(), r.estimate.c_str(), r.truth.c_str(), name.c_str(), lo, hi,
                    static_cast<unsigned long long>(st.pixels), st.relative_rms, st.rms, st.bias,
                    st.truth_mean);
      out << line;
    }
  return out.str();
}

nlohmann::json json_table(const std::vector<SsaoResult>& results, const SsaoReportSettings& s) {
  nlohmann::json j;
  j["scene"] = s.scene;
  j["radius"] = s.radius;
  j["classic_samples"] = s.samples;
  j["gtao_slices"] = s.slices;
  j["gtao_steps"] = s.steps;
  j["truth_rays_per_pixel"] = s.truth_rays;
  j["baked_samples_per_vertex"] = s.bake_samples;
  if (s.obscurance.enabled())
    j["obscurance"] = {{"distance", s.obscurance.distance},
                       {"falloff", bake::obscurance_falloff_name(s.obscurance.falloff)}};
  j["regions"] = {
      {"contact", "nearest hit < " + std::to_string(s.rule.contact_fraction) + " R"},
      {"thin", "surface thinner than " + std::to_string(s.rule.thin_fraction) + " R"},
      {"edge", "within " + std::to_string(s.rule.edge_fraction) + " x height of the image border"}};
  j["error"] = "relative RMS = sqrt(sum (e - t)^2 / sum t^2) over the region's covered pixels";
  nlohmann::json rows = nlohmann::json::array();
  for (const SsaoResult& r : results) {
    nlohmann::json row = {{"camera", r.camera}, {"estimate", r.estimate}, {"truth", r.truth}};
    for (const auto& [name, acc] : regions(r.errors)) {
      const ErrorStats st = acc->stats();
      nlohmann::json e = {{"pixels", st.pixels},
                          {"relative_rms", st.relative_rms},
                          {"rms", st.rms},
                          {"bias", st.bias},
                          {"truth_mean", st.truth_mean}};
      if (name.rfind("distance_", 0) == 0) {
        const auto [lo, hi] = bin_range(s, std::stoul(name.substr(9)), r.errors.distance.size());
        e["distance"] = {lo, hi};
      }
      row[name] = e;
    }
    rows.push_back(row);
  }
  j["results"] = rows;
  return j;
}

std::string summary_text(const std::vector<SsaoResult>& results, const SsaoReportSettings& s) {
  std::ostringstream out;
  char line[400];
  out << "# Screen-space AO against ray-traced AO: " << s.scene << "\n\n";
  std::snprintf(line, sizeof line,
                "Radius R = %.4g scene units; classic SSAO %d samples, GTAO %d slices x %d steps "
                "per side; truth %d rays per pixel; baked AO %d samples per vertex.\n\n",
                s.radius, s.samples, s.slices, s.steps, s.truth_rays, s.bake_samples);
  out << line;
  std::snprintf(line, sizeof line,
                "Truths, traced per pixel at the G-buffer's points: `ao` = AO (every hit "
                "occludes); `obscurance` = obscurance with D = %.4g, falloff %s (AO within D "
                "when the falloff is constant). Pixels: the front side of surfaces.\n\n",
                s.obscurance.distance, bake::obscurance_falloff_name(s.obscurance.falloff));
  out << line;
  out << "Relative RMS error over all cameras (pixels in parentheses):\n\n"
         "| estimate | truth | all | contact | thin | edge band | interior |\n"
         "|---|---|---|---|---|---|---|\n";
  for (const SsaoResult& r : results) {
    if (r.camera != "all") continue;
    out << "| " << r.estimate << " | " << r.truth;
    for (const ErrorAccumulator* acc :
         {&r.errors.all, &r.errors.contact, &r.errors.thin, &r.errors.edge, &r.errors.interior}) {
      const ErrorStats st = acc->stats();
      std::snprintf(line, sizeof line, " | %.3f (%llu)", st.relative_rms,
                    static_cast<unsigned long long>(st.pixels));
      out << line;
    }
    out << " |\n";
  }
  out << "\nRelative RMS error by distance from the eye (all cameras):\n\n| estimate | truth |";
  const std::size_t bins = results.empty() ? 0 : results.front().errors.distance.size();
  for (std::size_t b = 0; b < bins; ++b) {
    const auto [lo, hi] = bin_range(s, b, bins);
    std::snprintf(line, sizeof line, " %.3g-%.3g |", lo, hi);
    out << line;
  }
  out << "\n|---|---|";
  for (std::size_t b = 0; b < bins; ++b) out << "---|";
  out << "\n";
  for (const SsaoResult& r : results) {
    if (r.camera != "all") continue;
    out << "| " << r.estimate << " | " << r.truth << " |";
    for (const ErrorAccumulator& acc : r.errors.distance) {
      const ErrorStats st = acc.stats();
      std::snprintf(line, sizeof line, " %.3f |", st.relative_rms);
      out << (st.pixels ? line : " - |");
    }
    out << "\n";
  }
  return out.str();
}

}  // namespace

std::vector<std::string> ssao_table_names() {
  return {"ssao_errors.csv", "ssao_errors.json", "summary.md"};
}

std::vector<std::string> write_ssao_tables(const std::string& dir,
                                           const std::vector<SsaoResult>& results,
                                           const SsaoReportSettings& settings) {
  namespace fs = std::filesystem;
  const std::vector<std::string> names = ssao_table_names();
  std::vector<std::string> paths;
  for (const std::string& n : names) paths.push_back((fs::path(dir) / n).string());
  write_text(paths[0], csv_table(results, settings));
  write_text(paths[1], json_table(results, settings).dump(1) + "\n");
  write_text(paths[2], summary_text(results, settings));
  return paths;
}

void write_ssao_picture(const std::string& path, const AoCapture& c, const PixelTruth& truth) {
  const int W = c.width, H = c.height, rows = truth.obscurance.empty() ? 2 : 3;
  std::vector<float> rgb(static_cast<std::size_t>(3 * W) * rows * H * 3, 0.f);
  const auto put = [&](int tile, int x, int y, float r, float g, float b) {
    const int col = tile % 3, row = tile / 3;
    // capture rows run bottom to top; the picture's top to bottom
    const std::size_t i =
        (static_cast<std::size_t>(row * H + (H - 1 - y)) * (3 * W) + col * W + x) * 3;
    rgb[i] = r;
    rgb[i + 1] = g;
    rgb[i + 2] = b;
  };
  const auto estimate = [&](const std::string& name, std::size_t px) {
    for (std::size_t k = 0; k < c.estimate_names.size(); ++k)
      if (c.estimate_names[k] == name) return c.estimates[k][4 * px];
    return 1.f;
  };
  // red: the estimate is brighter than the truth, blue: darker; full colour at ±0.5
  const auto difference = [&](int tile, int x, int y, float e, float t) {
    const float d = std::clamp((e - t) * 2.f, -1.f, 1.f);
    put(tile, x, y, 1.f - std::max(0.f, -d), 1.f - std::fabs(d), 1.f - std::max(0.f, d));
  };
  for (int y = 0; y < H; ++y)
    for (int x = 0; x < W; ++x) {
      const std::size_t px = static_cast<std::size_t>(y) * W + x;
      if (!c.front(px) || truth.ao[px] < 0.f) {
        for (int t = 0; t < 3 * rows; ++t) put(t, x, y, 0.1f, 0.1f, 0.12f);
        continue;
      }
      const float t = truth.ao[px], s = estimate("ssao", px), g = estimate("gtao", px);
      const float b = estimate("baked", px);
      put(0, x, y, t, t, t);
      put(1, x, y, s, s, s);
      put(2, x, y, g, g, g);
      put(3, x, y, b, b, b);
      difference(4, x, y, s, t);
      difference(5, x, y, g, t);
      if (rows < 3) continue;
      const float o = truth.obscurance[px];
      put(6, x, y, o, o, o);
      difference(7, x, y, s, o);
      difference(8, x, y, g, o);
    }
  relight::write_image(path, 3 * W, rows * H, 3, rgb.data());
}

}  // namespace prt::report
