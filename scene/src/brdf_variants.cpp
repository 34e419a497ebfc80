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

namespace {

// Levels per component for the greedy grid (see the header).
std::vector<std::size_t> grid_levels(const std::vector<std::vector<double>>& columns,
                                     std::size_t budget) {
  const std::size_t k_count = columns.size();
  std::vector<std::size_t> levels(k_count, 1), distinct(k_count);
  std::vector<double> width(k_count);
  for (std::size_t k = 0; k < k_count; ++k) {
    distinct[k] = distinct_count(columns[k]);
    const auto [lo, hi] = std::minmax_element(columns[k].begin(), columns[k].end());
    width[k] = columns[k].empty() ? 0.0 : *hi - *lo;
  }
  std::size_t product = 1;
  for (;;) {
    std::size_t best = k_count;
    for (std::size_t k = 0; k < k_count; ++k) {
      if (levels[k] >= distinct[k] || product / levels[k] * (levels[k] + 1) > budget) continue;
      if (best == k_count || width[k] / double(levels[k]) > width[best] / double(levels[best]))
        best = k;
    }
    if (best == k_count) return levels;
    product = product / levels[best] * (levels[best] + 1);
    ++levels[best];
  }
}

}  // namespace

QuantisedVectors quantise_parameters(const std::vector<std::vector<double>>& samples,
                                     int max_variants) {
  if (max_variants < 1 || max_variants > kMaxBrdfVariants)
    throw std::invalid_argument("quantise_parameters: max_variants outside [1, 64]");
  const std::size_t budget = std::size_t(max_variants);
  const std::size_t k_count = samples.empty() ? 0 : samples.front().size();
  std::vector<std::vector<double>> columns(k_count, std::vector<double>(samples.size()));
  for (std::size_t i = 0; i < samples.size(); ++i) {
    if (samples[i].size() != k_count)
      throw std::invalid_argument("quantise_parameters: vectors of different lengths");
    for (std::size_t k = 0; k < k_count; ++k)
      columns[k][i] = std::isnan(samples[i][k]) ? 0.0 : samples[i][k];
  }
  QuantisedVectors out;
  out.max_error.assign(k_count, 0.0);
  const auto row = [&](std::size_t i) {
    std::vector<double> r(k_count);
    for (std::size_t k = 0; k < k_count; ++k) r[k] = columns[k][i];
    return r;
  };
  std::map<std::vector<double>, uint32_t> distinct;
  for (std::size_t i = 0; i < samples.size(); ++i) distinct.emplace(row(i), 0u);
  bool only_first_two = k_count >= 2;
  for (std::size_t k = 2; k < k_count && only_first_two; ++k)
    only_first_two = distinct_count(columns[k]) <= 1;
  if (distinct.size() > budget && only_first_two) {
    // The two-parameter grid; the constant components ride along.
    std::vector<glm::dvec2> pairs(samples.size());
    for (std::size_t i = 0; i < samples.size(); ++i) pairs[i] = {columns[0][i], columns[1][i]};
    const QuantisedParameters q = quantise_metal_roughness(pairs, max_variants);
    for (const glm::dvec2& level : q.levels) {
      std::vector<double> v = row(0);
      v[0] = level.x;
      v[1] = level.y;
      out.levels.push_back(std::move(v));
    }
    out.level_of = q.level_of;
    out.max_error[0] = q.max_roughness_error;
    out.max_error[1] = q.max_metalness_error;
    return out;
  }
  std::vector<Axis> axes;
  const std::vector<std::size_t> levels =
      distinct.size() <= budget ? std::vector<std::size_t>() : grid_levels(columns, budget);
  for (std::size_t k = 0; k < levels.size(); ++k) axes.emplace_back(columns[k], levels[k]);
  // Exact: every distinct vector its own cell (the axes are left empty).
  std::map<std::vector<double>, uint32_t> cells;
  std::vector<std::vector<double>> cell_of(samples.size());
  for (std::size_t i = 0; i < samples.size(); ++i) {
    cell_of[i] = row(i);
    for (std::size_t k = 0; k < axes.size(); ++k)
      cell_of[i][k] = double(axes[k].index(cell_of[i][k]));
    cells.emplace(cell_of[i], 0u);
  }
  for (auto& [cell, index] : cells) {
    index = static_cast<uint32_t>(out.levels.size());
    std::vector<double> value = cell;
    for (std::size_t k = 0; k < axes.size(); ++k) value[k] = axes[k].value(std::size_t(cell[k]));
    out.levels.push_back(std::move(value));
  }
  for (std::size_t i = 0; i < samples.size(); ++i) {
    const uint32_t level = cells.at(cell_of[i]);
    out.level_of.push_back(level);
    for (std::size_t k = 0; k < k_count; ++k)
      out.max_error[k] =
          std::max(out.max_error[k], std::fabs(out.levels[level][k] - columns[k][i]));
  }
  return out;
}

}  // namespace prt::scene
