#include "relight/auto_exposure.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

namespace prt::relight {

float choose_auto_exposure(const std::vector<float>& radiance_rgb) {
  std::vector<double> luminance;
  luminance.reserve(radiance_rgb.size() / 3);
  for (std::size_t v = 0; v + 2 < radiance_rgb.size(); v += 3) {
    const double y = 0.2126 * double(radiance_rgb[v]) + 0.7152 * double(radiance_rgb[v + 1]) +
                     0.0722 * double(radiance_rgb[v + 2]);
    if (std::isfinite(y) && y > 0) luminance.push_back(y);
  }
  if (luminance.empty()) return 0.f;
  const auto middle = luminance.begin() + static_cast<std::ptrdiff_t>(luminance.size() / 2);
  std::nth_element(luminance.begin(), middle, luminance.end());
  const double ev = std::log2(kAutoExposureKey / *middle);
  return static_cast<float>(std::round(4 * ev) / 4);
}

std::string describe_exposure(float exposure_ev, bool automatic) {
  char text[160];
  if (automatic)
    std::snprintf(text, sizeof text,
                  "exposure %+.2f EV (automatic: median vertex luminance brought to %.2g, "
                  "rounded to 1/4 EV; --exposure EV sets it)",
                  double(exposure_ev), kAutoExposureKey);
  else
    std::snprintf(text, sizeof text, "exposure %+.2f EV (--exposure)", double(exposure_ev));
  return text;
}

}  // namespace prt::relight
