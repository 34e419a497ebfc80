// relight/src/shown_window.cpp — the automatic window chosen on the rendered vertices
// (relight/shown_window.h).
#include "relight/shown_window.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include <tbb/parallel_for.h>

namespace prt::relight {
namespace {

constexpr double kLargestLambda = 1e6;

// The band-l part of `lighting` alone (all other coefficients zero).
prt::ShLighting band_only(const prt::ShLighting& lighting, int l) {
  const int n2 = lighting.coefficient_count();
  std::vector<double> rgb(3 * static_cast<std::size_t>(n2), 0.0);
  for (int c = 0; c < 3; ++c) {
    const double* source = lighting.coefficients_double(c);
    for (int k = l * l; k < (l + 1) * (l + 1); ++k) rgb[c * n2 + k] = source[k];
  }
  prt::Result<prt::ShLighting> band =
      prt::ShLighting::from_coefficients(lighting.order(), rgb.data());
  if (!band.ok()) throw std::runtime_error("window auto: " + band.status().message());
  return std::move(band).value();
}

}  // namespace

ShownWindowSearch::ShownWindowSearch(int order) : order_(std::max(1, order)) {
  lambdas_.push_back(0.0);
  if (order_ > 1) {
    const double n1 = order_ - 1.0, n = order_;
    const double lambda1 = 1.0 / (100.0 * n1 * n1 * n * n);
    for (int j = 0;; ++j) {
      const double lambda = lambda1 * std::exp2(0.25 * j);
      lambdas_.push_back(lambda);
      if (lambda >= kLargestLambda) break;
    }
  }
  factors_.assign(lambdas_.size() * order_, 1.0);
  for (std::size_t j = 1; j < lambdas_.size(); ++j) {
    const std::vector<double> h =
        sh::window_band_factors(sh::Window::Laplacian, order_, lambdas_[j]);
    std::copy(h.begin(), h.end(), factors_.begin() + static_cast<std::ptrdiff_t>(j * order_));
  }
  failing_.assign(lambdas_.size(), 0);
  negative_.assign(lambdas_.size(), 0);
}

ShownWindowSearch::RangeCounts ShownWindowSearch::count_range(const std::vector<float>& bands,
                                                              std::size_t first,
                                                              std::size_t end) const {
  const std::size_t candidates = lambdas_.size();
  RangeCounts out;
  out.failing.assign(candidates, 0);
  out.negative.assign(candidates, 0);
  std::vector<char> vertex_fails(candidates), vertex_negative(candidates);
  for (std::size_t v = first; v < end; ++v) {
    bool any = false, unremovable = false;
    std::fill(vertex_fails.begin(), vertex_fails.end(), 0);
    std::fill(vertex_negative.begin(), vertex_negative.end(), 0);
    for (int c = 0; c < 3; ++c) {
      const float* s = &bands[(v * 3 + c) * order_];
      double magnitude = 0.0, rest = 0.0;
      for (int l = 0; l < order_; ++l) magnitude += std::fabs(double(s[l]));
      rest = magnitude - std::fabs(double(s[0]));
      if (double(s[0]) - rest >= kShownWindowMargin * magnitude) continue;  // passes every window
      any = true;
      for (std::size_t j = candidates; j-- > 0;) {  // strongest first
        const double* h = &factors_[j * order_];
        double value = 0.0, scale = 0.0;
        for (int l = 0; l < order_; ++l) {
          value += h[l] * double(s[l]);
          scale += h[l] * std::fabs(double(s[l]));
        }
        if (value < 0.0) vertex_negative[j] = 1;
        if (value < kShownWindowMargin * scale) {
          if (j + 1 == candidates) unremovable = true;
          vertex_fails[j] = 1;
        }
      }
    }
    if (!any) continue;
    out.intrinsic += unremovable ? 1 : 0;
    for (std::size_t j = 0; j < candidates; ++j) {
      out.failing[j] += vertex_fails[j] && !unremovable;
      out.negative[j] += vertex_negative[j];
    }
  }
  return out;
}

void ShownWindowSearch::add_view_bands(const std::vector<float>& bands, std::size_t vertex_count) {
  if (bands.size() != vertex_count * 3 * static_cast<std::size_t>(order_))
    throw std::invalid_argument("window auto: band sums do not match the vertex count");
  if (views_ > 0 && vertex_count != vertices_)
    throw std::invalid_argument("window auto: views with different vertex counts");
  vertices_ = vertex_count;
  ++views_;
  const std::size_t candidates = lambdas_.size();
  // Counted in fixed ranges of vertices in parallel, then summed: integer counts, the same for
  // any thread count.
  constexpr std::size_t kRange = 16384;
  const std::size_t ranges = (vertex_count + kRange - 1) / kRange;
  std::vector<RangeCounts> counts(ranges);
  tbb::parallel_for(std::size_t{0}, ranges, [&](std::size_t r) {
    counts[r] = count_range(bands, r * kRange, std::min(vertex_count, (r + 1) * kRange));
  });
  std::vector<std::size_t> failing(candidates, 0), negative(candidates, 0);
  std::size_t intrinsic = 0;
  for (const RangeCounts& c : counts) {
    for (std::size_t j = 0; j < candidates; ++j) {
      failing[j] += c.failing[j];
      negative[j] += c.negative[j];
    }
    intrinsic += c.intrinsic;
  }
  for (std::size_t j = 0; j < candidates; ++j) {
    failing_[j] = std::max(failing_[j], failing[j]);
    negative_[j] = std::max(negative_[j], negative[j]);
  }
  unremovable_ = std::max(unremovable_, intrinsic);
}

void ShownWindowSearch::add_view(const prt::ShLighting& lighting, const ShadeVertices& shade) {
  if (lighting.order() != order_)
    throw std::invalid_argument("window auto: lighting order differs from the search's");
  std::vector<float> bands;
  std::size_t vertex_count = 0;
  for (int l = 0; l < order_; ++l) {
    const std::vector<float> radiance = shade(band_only(lighting, l));
    if (l == 0) {
      vertex_count = radiance.size() / 3;
      bands.assign(vertex_count * 3 * order_, 0.f);
    } else if (radiance.size() != 3 * vertex_count) {
      throw std::runtime_error("window auto: the shading's vertex count changed between bands");
    }
    for (std::size_t i = 0; i < 3 * vertex_count; ++i) bands[i * order_ + l] = radiance[i];
  }
  add_view_bands(bands, vertex_count);
}

ShownWindowChoice ShownWindowSearch::choose() const {
  ShownWindowChoice choice;
  choice.vertices = vertices_;
  choice.views = views_;
  std::size_t chosen = 0;
  bool found = false;
  for (std::size_t j = 0; j < lambdas_.size() && !found; ++j) {
    if (failing_[j] == 0) {
      chosen = j;
      found = true;
    }
  }
  if (!found) chosen = lambdas_.size() - 1;  // only for order 1: None is the only candidate
  choice.window = chosen == 0 ? sh::Window::None : sh::Window::Laplacian;
  choice.strength = lambdas_[chosen];
  choice.negative_before = negative_[0];
  choice.negative_after = negative_[chosen];
  choice.unremovable = unremovable_;
  return choice;
}

std::string describe_shown_window(const ShownWindowChoice& c) {
  char text[480];
  const char* name = sh::window_name(c.window);
  const char* views = c.views == 1 ? "view" : "views";
  if (c.unremovable == 0) {
    std::snprintf(text, sizeof text,
                  "window auto: %s, strength %.3g, the weakest that leaves none of the %zu "
                  "vertices negative in the %d %s rendered (%zu are without a window)",
                  name, c.strength, c.vertices, c.views, views, c.negative_before);
  } else {
    std::snprintf(text, sizeof text,
                  "window auto: %s, strength %.3g, the weakest that leaves no vertex of the %zu "
                  "negative in the %d %s rendered but those no window lifts (%zu in a view, "
                  "negative under the lighting's mean alone: the transfer itself rings there); "
                  "%zu are negative with it, %zu without a window",
                  name, c.strength, c.vertices, c.views, views, c.unremovable, c.negative_after,
                  c.negative_before);
  }
  return text;
}

std::string apply_shown_window(const ShownWindowChoice& choice, prt::ShLighting* lighting) {
  const prt::Status windowed = lighting->apply_window(choice.window, choice.strength);
  if (!windowed.ok()) throw std::runtime_error("--window: " + windowed.message());
  return describe_shown_window(choice);
}

}  // namespace prt::relight
