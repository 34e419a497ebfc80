// scene/src/brdf_variants.cpp — quantising per-vertex material parameters (scene/brdf_variants.h).
#include "scene/brdf_variants.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

namespace prt::scene {
namespace {

// Distinct values of one parameter kept as they are.
constexpr std::size_t kFewValues = 8;

// The quantiser of one parameter: its distinct values kept exactly, or `bins` uniform bins over
// [lo, hi] valued at their centres.
class Axis {
 public:
  Axis(std::vector<double> values, std::size_t levels) {
    std::sort(values.begin(), values.end());
    values.erase(std::unique(values.begin(), values.end()), values.end());
    exact_ = values.size() <= levels;
    if (exact_) {
      values_ = std::move(values);
    } else {
      lo_ = values.front();
      hi_ = values.back();
      bins_ = levels;
    }
  }

  std::size_t index(double v) const {
    if (exact_)
      return std::size_t(std::lower_bound(values_.begin(), values_.end(), v) - values_.begin());
    const double t = (v - lo_) / (hi_ - lo_) * double(bins_);
    return std::min(bins_ - 1, std::size_t(std::max(0.0, std::floor(t))));
  }

  double value(std::size_t i) const {
    return exact_ ? values_[i] : lo_ + (double(i) + 0.5) * (hi_ - lo_) / double(bins_);
  }

 private:
  bool exact_ = true;
  std::vector<double> values_;
  double lo_ = 0, hi_ = 0;
  std::size_t bins_ = 1;
};

std::size_t distinct_count(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return std::size_t(std::unique(values.begin(), values.end()) - values.begin());
}

}  // namespace

QuantisedParameters quantise_metal_roughness(const std::vector<glm::dvec2>& samples,
                                             int max_variants) {
  if (max_variants < 1 || max_variants > kMaxBrdfVariants)
    throw std::invalid_argument("quantise_metal_roughness: max_variants outside [1, 64]");
  const std::size_t budget = std::size_t(max_variants);
  std::vector<double> r(samples.size()), m(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    r[i] = std::isnan(samples[i].x) ? 0.0 : std::clamp(samples[i].x, 0.0, 1.0);
    m[i] = std::isnan(samples[i].y) ? 0.0 : std::clamp(samples[i].y, 0.0, 1.0);
  }
  QuantisedParameters out;
  std::map<std::pair<double, double>, uint32_t> distinct;
  for (std::size_t i = 0; i < r.size(); ++i) distinct.emplace(std::make_pair(r[i], m[i]), 0u);
  if (distinct.size() <= budget) {  // exact
    for (auto& [pair, index] : distinct) {
      index = static_cast<uint32_t>(out.levels.size());
      out.levels.emplace_back(pair.first, pair.second);
    }
    for (std::size_t i = 0; i < r.size(); ++i) out.level_of.push_back(distinct.at({r[i], m[i]}));
    return out;
  }
  // Levels per axis: an axis with few distinct values keeps them; the other gets the rest.
  const std::size_t dr = distinct_count(r), dm = distinct_count(m);
  std::size_t nr = std::min<std::size_t>(16, budget), nm = std::max<std::size_t>(1, budget / nr);
  if (dm <= std::min(kFewValues, budget)) {
    nm = dm;
    nr = budget / dm;
  } else if (dr <= std::min(kFewValues, budget)) {
    nr = dr;
    nm = budget / dr;
  }
  const Axis axis_r(r, nr), axis_m(m, nm);
  std::map<std::pair<std::size_t, std::size_t>, uint32_t> cells;
  std::vector<std::pair<std::size_t, std::size_t>> cell_of(r.size());
  for (std::size_t i = 0; i < r.size(); ++i) {
    cell_of[i] = {axis_r.index(r[i]), axis_m.index(m[i])};
    cells.emplace(cell_of[i], 0u);
  }
  for (auto& [cell, index] : cells) {
    index = static_cast<uint32_t>(out.levels.size());
    out.levels.emplace_back(axis_r.value(cell.first), axis_m.value(cell.second));
  }
  for (std::size_t i = 0; i < r.size(); ++i) {
    const uint32_t level = cells.at(cell_of[i]);
    out.level_of.push_back(level);
    out.max_roughness_error =
        std::max(out.max_roughness_error, std::fabs(out.levels[level].x - r[i]));
    out.max_metalness_error =
        std::max(out.max_metalness_error, std::fabs(out.levels[level].y - m[i]));
  }
  return out;
}

}  // namespace prt::scene
