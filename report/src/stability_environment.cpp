// report/src/stability_environment.cpp — stability cases on extreme environment maps: a sun
// 1e5–1e6 times the sky (ringing and negative lobes, per window), an all-black map, a single
// bright texel, NaN/Inf/negative texels, and 1×1 .. 8192×4096 maps.
//
// Conventions: lat-long maps of sh/env_map.h (row 0 = +Y, centre column +X), SH basis of
// sh/basis.h, projection sh::project (exact texel solid angles), lighting prt::ShLighting,
// windows sh/window.h (Sloan, "Stupid SH tricks", 2008). Irradiance E = π × radiance convolved
// with the clamped cosine (Ramamoorthi & Hanrahan 2001): band l scaled by A_l.
#include <sys/resource.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "prt/lighting/sh_lighting.h"
#include "report/stability_cases.h"
#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/env_map.h"
#include "sh/projection.h"
#include "sh/window.h"
#include "sh/zonal.h"

namespace prt::report::stability {
namespace {

using sh::kPi;

std::string format(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

sh::EnvMap make_constant_latlong(int width, int height, float r, float g, float b) {
  sh::EnvMap env;
  env.layout = sh::EnvLayout::LatLong;
  env.width = width;
  env.height = height;
  env.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  for (std::size_t i = 0; i < env.rgb.size(); i += 3) {
    env.rgb[i] = r;
    env.rgb[i + 1] = g;
    env.rgb[i + 2] = b;
  }
  return env;
}

// Spherical Fibonacci lattice of n unit directions.
std::vector<std::array<double, 3>> fibonacci_directions(int n) {
  std::vector<std::array<double, 3>> dirs(n);
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, s = std::sqrt(std::max(0.0, 1.0 - z * z));
    dirs[i] = {s * std::cos(golden * i), s * std::sin(golden * i), z};
  }
  return dirs;
}

struct LobeStats {
  double min_value = 0, max_value = 0, negative_fraction = 0;
  bool finite = true;
};

// Min, max and fraction of directions with a value < −1e-12·max|value| of one channel's
// expansion (order² coefficients).
LobeStats measure_lobes(const std::vector<double>& coefficients, int order,
                        const std::vector<std::array<double, 3>>& dirs) {
  LobeStats s;
  s.min_value = INFINITY;
  s.max_value = -INFINITY;
  std::vector<double> values(dirs.size());
  double max_abs = 0;
  for (std::size_t i = 0; i < dirs.size(); ++i) {
    sh::reconstruct(coefficients.data(), 1, order, dirs[i].data(), &values[i]);
    s.finite &= std::isfinite(values[i]);
    s.min_value = std::min(s.min_value, values[i]);
    s.max_value = std::max(s.max_value, values[i]);
    max_abs = std::max(max_abs, std::fabs(values[i]));
  }
  std::size_t negative = 0;
  for (double v : values) negative += v < -1e-12 * max_abs ? 1 : 0;
  s.negative_fraction = static_cast<double>(negative) / static_cast<double>(dirs.size());
  return s;
}

std::vector<double> channel(const prt::ShLighting& lighting, int c) {
  const double* p = lighting.coefficients_double(c);
  return std::vector<double>(p, p + lighting.coefficient_count());
}

std::vector<double> irradiance_coefficients(std::vector<double> radiance, int order) {
  std::vector<double> a(order);
  for (int l = 0; l < order; ++l) a[l] = sh::clamped_cosine_band_factor(l);
  sh::convolve_zonal(order, a.data(), radiance.data());
  return radiance;
}

prt::ShLighting require_lighting(const sh::EnvMap& env, int order) {
  auto lighting = prt::ShLighting::from_env_map(env, order);
  if (!lighting.ok()) throw std::runtime_error(lighting.status().message());
  return std::move(lighting.value());
}

long peak_rss_mb() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024;  // KiB on Linux
}

}  // namespace

CaseResult check_bright_sun(const CaseOptions& options, double sun_to_sky) {
  char name[64];
  std::snprintf(name, sizeof name, "sun_%.0e_times_sky", sun_to_sky);
  return run_case(
      "environment", name,
      "L00 matches the exact quadrature to 1e-9; every window gives finite radiance and "
      "irradiance; 'auto' keeps irradiance >= −1e-3·max (negative lobes of the others reported)",
      [&options, sun_to_sky](CaseResult& r) {
        const int width = options.quick ? 256 : 512, height = width / 2;
        sh::EnvMap env = make_constant_latlong(width, height, 1.f, 1.f, 1.f);
        // Sun: texels within 0.75° of a direction 40° above the horizon toward −Z (a disc of
        // a few texels; the real sun's 0.27° radius is below one texel at these sizes).
        const double elevation = 40.0 * kPi / 180.0;
        const double sun[3] = {0.0, std::sin(elevation), -std::cos(elevation)};
        const double cos_radius = std::cos(0.75 * kPi / 180.0 + kPi / height);
        double sun_solid_angle = 0;
        for (int row = 0; row < height; ++row)
          for (int col = 0; col < width; ++col) {
            double d[3];
            sh::texel_direction(env.layout, width, height, col, row, d);
            if (d[0] * sun[0] + d[1] * sun[1] + d[2] * sun[2] < cos_radius) continue;
            float* px = &env.rgb[(static_cast<std::size_t>(row) * width + col) * 3];
            px[0] = px[1] = px[2] = static_cast<float>(sun_to_sky);
            sun_solid_angle += sh::texel_solid_angle(env.layout, width, height, col, row);
          }
        if (sun_solid_angle <= 0) throw std::runtime_error("sun: no texel selected");
        const double expected_l00 =
            (4.0 * kPi + sun_solid_angle * (static_cast<float>(sun_to_sky) - 1.0)) * 0.5 /
            std::sqrt(kPi);
        const auto dirs = fibonacci_directions(options.quick ? 2048 : 8192);
        bool finite = true, auto_ok = true;
        double l00_error = 0;
        r.table_header = {"order",         "window",
                          "min L / max L", "negative L fraction",
                          "min E / max E", "negative E fraction"};
        for (int order : {3, 9}) {
          const prt::ShLighting base = require_lighting(env, order);
          l00_error =
              std::max(l00_error, std::fabs(base.coefficients_double(0)[0] / expected_l00 - 1.0));
          for (sh::Window w : {sh::Window::None, sh::Window::Hanning, sh::Window::Lanczos,
                               sh::Window::Laplacian, sh::Window::Auto}) {
            prt::ShLighting lighting = base;
            const prt::Status st = lighting.apply_window(w, -1.0);
            if (!st.ok()) throw std::runtime_error(st.message());
            const LobeStats rad = measure_lobes(channel(lighting, 0), order, dirs);
            const LobeStats irr =
                measure_lobes(irradiance_coefficients(channel(lighting, 0), order), order, dirs);
            finite &= rad.finite && irr.finite;
            if (w == sh::Window::Auto && irr.min_value < -1e-3 * irr.max_value) auto_ok = false;
            r.table_rows.push_back(
                {std::to_string(order), sh::window_name(w), format(rad.min_value / rad.max_value),
                 format(rad.negative_fraction), format(irr.min_value / irr.max_value),
                 format(irr.negative_fraction)});
            if (order == 9 && (w == sh::Window::None || w == sh::Window::Auto)) {
              const std::string p = std::string("order9_") + sh::window_name(w) + "_";
              r.add(p + "min_radiance_over_max", rad.min_value / rad.max_value);
              r.add(p + "negative_radiance_fraction", rad.negative_fraction);
              r.add(p + "min_irradiance_over_max", irr.min_value / irr.max_value);
              r.add(p + "negative_irradiance_fraction", irr.negative_fraction);
            }
          }
        }
        r.add("sun_solid_angle_sr", sun_solid_angle);
        r.add("l00_relative_error", l00_error);
        // 1e-9: the projection sums ~1e5 float texels in double; the exact sum differs only by
        // rounding (the reference uses the same exact texel solid angles).
        r.passed = finite && auto_ok && l00_error <= 1e-9;
        r.detail = std::string(finite ? "finite" : "NON-FINITE output") +
                   (auto_ok ? "; auto keeps irradiance non-negative"
                            : "; auto left negative "
                              "irradiance");
      });
}

CaseResult check_black_map(const CaseOptions&) {
  return run_case(
      "environment", "all_black_map",
      "every coefficient and every window's reconstruction is exactly 0 (auto picks 'none')",
      [](CaseResult& r) {
        const sh::EnvMap env = make_constant_latlong(64, 32, 0.f, 0.f, 0.f);
        bool all_zero = true;
        std::string auto_choice;
        for (sh::Window w : {sh::Window::None, sh::Window::Hanning, sh::Window::Lanczos,
                             sh::Window::Laplacian, sh::Window::Auto}) {
          prt::ShLighting lighting = require_lighting(env, 9);
          const prt::Status st = lighting.apply_window(w, -1.0);
          if (!st.ok()) throw std::runtime_error(st.message());
          for (int c = 0; c < 3; ++c)
            for (int k = 0; k < lighting.coefficient_count(); ++k)
              all_zero &=
                  lighting.coefficients_double(c)[k] == 0.0 && lighting.coefficients(c)[k] == 0.0f;
        }
        std::vector<double> zeros(3 * 81, 0.0);
        const sh::WindowChoice choice = sh::choose_window_auto(zeros.data(), 3, 9);
        r.add("auto_min_irradiance_after", choice.min_irradiance_after);
        r.passed = all_zero && choice.window == sh::Window::None &&
                   std::isfinite(choice.min_irradiance_after);
        r.detail = std::string(all_zero ? "all zero" : "non-zero output") + "; auto chose " +
                   sh::window_name(choice.window);
      });
}

CaseResult check_single_bright_texel(const CaseOptions&) {
  return run_case(
      "environment", "single_bright_texel",
      "coefficients equal ω·L·Y_k(texel centre) to 1e-12 of max|L_k| per channel, and the "
      "reconstruction peaks in the texel's direction",
      [](CaseResult& r) {
        const int width = 64, height = 32, col = 40, row = 9, order = 9;
        sh::EnvMap env = make_constant_latlong(width, height, 0.f, 0.f, 0.f);
        const float value[3] = {1e4f, 2e4f, 5e3f};
        for (int c = 0; c < 3; ++c)
          env.rgb[(static_cast<std::size_t>(row) * width + col) * 3 + c] = value[c];
        double dir[3];
        sh::texel_direction(env.layout, width, height, col, row, dir);
        const double omega = sh::texel_solid_angle(env.layout, width, height, col, row);
        std::vector<double> y(order * order);
        sh::evaluate(order, dir[0], dir[1], dir[2], y.data());
        const prt::ShLighting lighting = require_lighting(env, order);
        double worst = 0;
        for (int c = 0; c < 3; ++c) {
          double max_abs = 0, max_err = 0;
          for (int k = 0; k < order * order; ++k) {
            const double expected = omega * value[c] * y[k];
            max_abs = std::max(max_abs, std::fabs(expected));
            max_err = std::max(max_err, std::fabs(lighting.coefficients_double(c)[k] - expected));
          }
          worst = std::max(worst, max_err / max_abs);
        }
        // The peak: the reconstruction at the texel's own direction beats every lattice point.
        const auto dirs = fibonacci_directions(4096);
        const auto coeffs = channel(lighting, 0);
        double at_texel = 0;
        sh::reconstruct(coeffs.data(), 1, order, dir, &at_texel);
        double best = -INFINITY, angle_of_best = 0;
        for (const auto& d : dirs) {
          double v = 0;
          sh::reconstruct(coeffs.data(), 1, order, d.data(), &v);
          if (v > best) {
            best = v;
            angle_of_best = std::acos(std::min(1.0, d[0] * dir[0] + d[1] * dir[1] + d[2] * dir[2]));
          }
        }
        r.add("relative_coefficient_error", worst);
        r.add("peak_value_at_texel", at_texel);
        r.add("best_lattice_value", best);
        r.add("angle_of_best_lattice_point_deg", angle_of_best * 180.0 / kPi);
        // 1e-12: one texel, so the only difference is the separable path's rounding.
        r.passed = worst <= 1e-12 && at_texel >= best;
        r.detail = "peak within " + format(angle_of_best * 180.0 / kPi) +
                   "° of the texel (lattice spacing ~3°)";
      });
}

CaseResult check_nan_inf_pixels(const CaseOptions&) {
  return run_case(
      "environment", "nan_inf_pixels",
      "NaN and ±Inf texels are skipped, negative channels clamped to 0, all counted exactly; the "
      "coefficients equal the projection with those texels (channels) zeroed (1e-12); "
      "prt::ShLighting (and `prt env --strict`) refuse such a map with a message",
      [](CaseResult& r) {
        const int width = 64, height = 32;
        sh::EnvMap env = make_constant_latlong(width, height, 1.f, 0.5f, 0.25f);
        sh::EnvMap zeroed = env;
        const float nan = std::numeric_limits<float>::quiet_NaN();
        const float inf = std::numeric_limits<float>::infinity();
        struct Plant {
          int texel, channel;
          float value;
        };
        // 5 NaN texels (one with NaN and Inf: counted as NaN), 4 Inf texels (+ and −),
        // 3 negative texels.
        const Plant plants[] = {{0, 0, nan},     {100, 1, nan}, {517, 2, nan},   {2047, 0, nan},
                                {300, 0, nan},   {300, 1, inf}, {1000, 0, inf},  {1001, 1, -inf},
                                {1500, 2, inf},  {64, 0, -inf}, {700, 1, -0.5f}, {701, 0, -1e30f},
                                {1999, 2, -2.0f}};
        for (const Plant& p : plants) {
          env.rgb[static_cast<std::size_t>(p.texel) * 3 + p.channel] = p.value;
          const bool negative = std::isfinite(p.value) && p.value < 0.f;  // clamped channel only
          for (int c = 0; c < 3; ++c)
            if (!negative || c == p.channel)
              zeroed.rgb[static_cast<std::size_t>(p.texel) * 3 + c] = 0.f;
        }
        sh::ProjectionStats stats, stats_zeroed;
        const auto with_bad = sh::project(env, 9, &stats);
        const auto reference = sh::project(zeroed, 9, &stats_zeroed);
        if (with_bad.empty() || reference.empty()) throw std::runtime_error("projection failed");
        double max_abs = 0, max_err = 0;
        bool finite = true;
        for (std::size_t i = 0; i < with_bad.size(); ++i) {
          finite &= std::isfinite(with_bad[i]);
          max_abs = std::max(max_abs, std::fabs(reference[i]));
          max_err = std::max(max_err, std::fabs(with_bad[i] - reference[i]));
        }
        // ShLighting refuses such a map outright (its documented error), with a clear message.
        auto lighting = prt::ShLighting::from_env_map(env, 9);
        const std::string refusal = lighting.ok() ? "" : lighting.status().message();
        r.add("nan_texels", static_cast<double>(stats.nan_texels));
        r.add("inf_texels", static_cast<double>(stats.inf_texels));
        r.add("negative_texels", static_cast<double>(stats.negative_texels));
        r.add("relative_difference_to_zeroed", max_err / max_abs);
        const bool strict_refuses = stats.skipped_texels() > 0;
        r.passed = finite && stats.nan_texels == 5 && stats.inf_texels == 4 &&
                   stats.negative_texels == 3 && max_err <= 1e-12 * max_abs && !lighting.ok() &&
                   refusal.find("NaN") != std::string::npos && strict_refuses &&
                   stats_zeroed.skipped_texels() == 0;
        r.detail = "skipped " + std::to_string(stats.skipped_texels()) +
                   " texels (5 NaN, 4 Inf planted; 3 negative clamped); ShLighting refuses: " +
                   (lighting.ok() ? std::string("NOT refused") : refusal);
      });
}

CaseResult check_map_size(const CaseOptions&, int width, int height) {
  const std::string name = "map_" + std::to_string(width) + "x" + std::to_string(height);
  return run_case(
      "environment", name,
      "projection works: L00 = √(4π)·c exactly for a constant map, and a 1 + 0.5·y map gives "
      "L1,−1 = 0.5·√(4π/3) with other bands ~0 (2e-6 from 1024 rows); time and memory reported",
      [width, height, name](CaseResult& r) {
        const auto t0 = std::chrono::steady_clock::now();
        const int order = 9;
        // Constant (1, 2, 3) for tiny maps; 1 + 0.5·y (y = cos θ of the row centre) otherwise.
        const bool tiny = width * static_cast<long long>(height) < 64;
        sh::EnvMap env = make_constant_latlong(width, height, 1.f, 2.f, 3.f);
        if (!tiny) {
          for (int row = 0; row < height; ++row) {
            const float v = static_cast<float>(1.0 + 0.5 * std::cos(kPi * (row + 0.5) / height));
            float* p = &env.rgb[static_cast<std::size_t>(row) * width * 3];
            for (int i = 0; i < width * 3; ++i) p[i] = v;
          }
        }
        const double fill_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        const auto t1 = std::chrono::steady_clock::now();
        sh::ProjectionStats stats;
        const auto coeffs = sh::project(env, order, &stats);
        const double project_s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
        if (coeffs.empty()) throw std::runtime_error(name + ": projection refused the map");
        double err = 0;
        bool finite = true;
        for (double c : coeffs) finite &= std::isfinite(c);
        const int k_count = order * order;
        if (tiny) {
          // Every texel contributes ω·c·Y_k(centre): compare with a direct evaluation.
          std::vector<double> expected(3 * k_count, 0.0), y(k_count);
          for (int row = 0; row < height; ++row)
            for (int col = 0; col < width; ++col) {
              double d[3];
              sh::texel_direction(env.layout, width, height, col, row, d);
              const double w = sh::texel_solid_angle(env.layout, width, height, col, row);
              sh::evaluate(order, d[0], d[1], d[2], y.data());
              for (int c = 0; c < 3; ++c)
                for (int k = 0; k < k_count; ++k) expected[c * k_count + k] += w * (c + 1) * y[k];
            }
          for (int i = 0; i < 3 * k_count; ++i)
            err = std::max(err, std::fabs(coeffs[i] - expected[i]));
          for (int c = 0; c < 3; ++c)
            err = std::max(err, std::fabs(coeffs[c * k_count] - std::sqrt(4 * kPi) * (c + 1)));
          err /= std::sqrt(4 * kPi);
        } else {
          // The map holds 1 + 0.5·cos θ sampled at row centres; the projection integrates the
          // row's exact solid angle, so the difference is O((π/H)²/24): checked to 2e-6 from
          // 1024 rows (measured 1.2e-6 at 1024), 1e-3 below.
          for (int k = 0; k < k_count; ++k) {
            double expected = 0;
            if (k == 0) expected = std::sqrt(4 * kPi);
            if (k == sh::index(1, -1)) expected = 0.5 * std::sqrt(4 * kPi / 3);
            err = std::max(err, std::fabs(coeffs[k] - expected));
          }
          err /= std::sqrt(4 * kPi);
        }
        const double tolerance = tiny ? 1e-12 : (height >= 1024 ? 2e-6 : 1e-3);
        const double map_mb = static_cast<double>(env.rgb.size() * sizeof(float)) / 1048576.0;
        r.add("width", width);
        r.add("height", height);
        r.add("map_mb", map_mb);
        r.add("fill_seconds", fill_s);
        r.add("project_seconds_order9", project_s);
        r.add("solid_angle_sum_minus_4pi", stats.solid_angle_sum - 4 * kPi);
        r.add("max_coefficient_error", err);
        r.add("peak_rss_mb", static_cast<double>(peak_rss_mb()));
        r.passed = finite && err <= tolerance && std::fabs(stats.solid_angle_sum - 4 * kPi) < 1e-9;
        r.detail = "projected in " + format(project_s) + " s; map " + format(map_mb) +
                   " MB; process peak RSS " + std::to_string(peak_rss_mb()) + " MB";
      });
}

}  // namespace prt::report::stability
