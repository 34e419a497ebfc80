// tests/golden/image_compare.cpp — see image_compare.h.
#include "image_compare.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "relight/image_io.h"

namespace prt::golden {
namespace {

std::string lower_extension(const std::filesystem::path& path) {
  std::string e = path.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e;
}

// Each pixel's difference in the tolerance's unit (see image_compare.h).
std::vector<double> pixel_differences(const relight::FloatImage& reference,
                                      const relight::FloatImage& render, PixelMetric metric) {
  const std::size_t pixels =
      static_cast<std::size_t>(reference.width) * static_cast<std::size_t>(reference.height);
  const std::size_t channels = static_cast<std::size_t>(reference.channels);
  double floor = 0;
  if (metric == PixelMetric::Relative) {
    double sum = 0;
    for (float v : reference.pixels) sum += std::fabs(static_cast<double>(v));
    floor = 0.05 * sum / static_cast<double>(std::max<std::size_t>(1, reference.pixels.size()));
    if (floor <= 0) floor = 1e-30;  // an all-black reference: any change is infinitely relative
  }
  std::vector<double> difference(pixels, 0.0);
  for (std::size_t p = 0; p < pixels; ++p) {
    double d = 0;
    for (std::size_t c = 0; c < channels; ++c) {
      double a = reference.pixels[p * channels + c], b = render.pixels[p * channels + c];
      if (metric == PixelMetric::Levels8) a = std::round(a * 255), b = std::round(b * 255);
      double e = std::fabs(b - a);
      if (std::isnan(e)) e = std::isnan(a) && std::isnan(b) ? 0 : HUGE_VAL;
      d = std::max(d, metric == PixelMetric::Levels8 ? e : e / std::max(std::fabs(a), floor));
    }
    difference[p] = d;
  }
  return difference;
}

std::string format_amount(double value, PixelMetric metric) {
  char text[64];
  if (metric == PixelMetric::Levels8)
    std::snprintf(text, sizeof text, "%.3g levels", value);
  else
    std::snprintf(text, sizeof text, "%.3g%%", 100 * value);
  return text;
}

}  // namespace

Tolerance tolerance_for(const std::filesystem::path& reference) {
  if (lower_extension(reference) == ".png") return {PixelMetric::Levels8, 2.0, 0.001, 0.5};
  return {PixelMetric::Relative, 0.005, 0.001, 0.001};
}

std::string Comparison::describe() const {
  if (!same_shape) return "shape differs: " + shape_problem;
  char text[320];
  std::snprintf(text, sizeof text,
                "%zu px, %zu beyond %s (%zu allowed), %zu differ, max %s, mean %s (at most %s)",
                pixels, beyond, format_amount(tolerance.per_pixel, tolerance.metric).c_str(),
                allowed, differing, format_amount(max_difference, tolerance.metric).c_str(),
                format_amount(mean_difference, tolerance.metric).c_str(),
                format_amount(tolerance.mean, tolerance.metric).c_str());
  return text;
}

Comparison compare_images(const relight::FloatImage& reference, const relight::FloatImage& render,
                          const Tolerance& tolerance) {
  Comparison c;
  c.tolerance = tolerance;
  if (reference.width != render.width || reference.height != render.height ||
      reference.channels != render.channels) {
    c.same_shape = false;
    c.shape_problem = "render " + std::to_string(render.width) + "x" +
                      std::to_string(render.height) + "x" + std::to_string(render.channels) +
                      ", reference " + std::to_string(reference.width) + "x" +
                      std::to_string(reference.height) + "x" + std::to_string(reference.channels);
    return c;
  }
  const std::vector<double> d = pixel_differences(reference, render, tolerance.metric);
  c.pixels = d.size();
  c.allowed = static_cast<std::size_t>(tolerance.outlier_fraction * static_cast<double>(c.pixels));
  double sum = 0;
  for (double v : d) {
    sum += v;
    c.max_difference = std::max(c.max_difference, v);
    if (v > tolerance.per_pixel) ++c.beyond;
    if (v != 0) ++c.differing;
  }
  c.mean_difference = c.pixels ? sum / static_cast<double>(c.pixels) : 0;
  return c;
}

Comparison compare_files(const std::filesystem::path& reference,
                         const std::filesystem::path& render) {
  return compare_images(relight::read_image(reference.string()),
                        relight::read_image(render.string()), tolerance_for(reference));
}

void write_difference_image(const std::filesystem::path& output,
                            const relight::FloatImage& reference, const relight::FloatImage& render,
                            const Tolerance& tolerance) {
  const std::vector<double> d = pixel_differences(reference, render, tolerance.metric);
  std::vector<float> rgb(d.size() * 3);
  for (std::size_t p = 0; p < d.size(); ++p) {
    const double t = tolerance.per_pixel > 0 ? d[p] / tolerance.per_pixel : (d[p] > 0 ? 2 : 0);
    float* out = &rgb[p * 3];
    if (t <= 1) {
      out[0] = out[1] = out[2] = static_cast<float>(0.5 * t);
    } else {
      out[0] = 1.f;
      out[1] = static_cast<float>(std::min(1.0, t - 1));
      out[2] = 0.f;
    }
  }
  relight::write_image(output.string(), reference.width, reference.height, 3, rgb.data());
}

}  // namespace prt::golden
