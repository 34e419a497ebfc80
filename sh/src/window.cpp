// sh/src/window.cpp — window factors and the automatic window choice.
#include "sh/window.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "sh/basis.h"
#include "sh/constants.h"
#include "sh/zonal.h"

namespace prt::sh {
namespace {

char lower_ascii(char c) {
  return (c >= 'A' && c <= 'Z') ? char(c - 'A' + 'a') : c;
}

bool equals_ignoring_case(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (lower_ascii(a[i]) != lower_ascii(b[i])) return false;
  }
  return true;
}

// λ_1 of the automatic sequence: the last band keeps 99 %.
double auto_base_lambda(int order) {
  const double n1 = order - 1.0, n = order;
  return order < 2 ? 0.0 : 1.0 / (100.0 * n1 * n1 * n * n);
}

}  // namespace

const char* window_name(Window w) noexcept {
  switch (w) {
    case Window::None:
      return "none";
    case Window::Hanning:
      return "hanning";
    case Window::Lanczos:
      return "lanczos";
    case Window::Laplacian:
      return "laplacian";
    case Window::Auto:
      return "auto";
  }
  return "unknown";
}

bool parse_window(std::string_view name, Window* w) noexcept {
  static constexpr Window kAll[] = {Window::None, Window::Hanning, Window::Lanczos,
                                    Window::Laplacian, Window::Auto};
  for (Window candidate : kAll) {
    if (equals_ignoring_case(name, window_name(candidate))) {
      *w = candidate;
      return true;
    }
  }
  if (equals_ignoring_case(name, "hann")) {
    *w = Window::Hanning;
    return true;
  }
  return false;
}

double default_window_strength(Window w, int order) noexcept {
  switch (w) {
    case Window::Hanning:
      return order;
    case Window::Lanczos:
      return 1.0;
    case Window::Laplacian: {
      const double n1 = order - 1.0, n = order;
      return order < 2 ? 0.0 : 1.0 / (n1 * n1 * n * n);
    }
    case Window::None:
    case Window::Auto:
      return 0.0;
  }
  return 0.0;
}

std::vector<double> window_band_factors(Window w, int order, double strength) {
  if (order < 1) return {};
  std::vector<double> h(order, 1.0);
  if (!(strength > 0.0) || !std::isfinite(strength)) strength = default_window_strength(w, order);
  for (int l = 1; l < order; ++l) {
    switch (w) {
      case Window::Hanning:
        h[l] = l < strength ? 0.5 * (1.0 + std::cos(kPi * l / strength)) : 0.0;
        break;
      case Window::Lanczos: {
        const double x = kPi * l / order;  // l < order, so x < π and sinc(x) > 0
        h[l] = std::pow(std::sin(x) / x, strength);
        break;
      }
      case Window::Laplacian: {
        const double ll1 = double(l) * (l + 1.0);
        h[l] = 1.0 / (1.0 + strength * ll1 * ll1);
        break;
      }
      case Window::None:
      case Window::Auto:
        break;
    }
  }
  return h;
}

WindowChoice choose_window_auto(const double* coefficients, int channels, int order,
                                const WindowProgress& progress) {
  WindowChoice choice{Window::None, 0.0, 0.0, 0.0};
  if (order < 1 || order > kMaxOrder || channels < 1 || coefficients == nullptr) return choice;
  const int n2 = order * order;

  // Candidates: index 0 is None, index j ≥ 1 is Laplacian with λ = λ_1·2^(j−1).
  std::vector<double> lambdas{0.0};
  const double lambda1 = auto_base_lambda(order);
  if (order > 1) {
    for (double lambda = lambda1;; lambda *= 2.0) {
      lambdas.push_back(lambda);
      if (lambda >= 1e6) break;
    }
  }
  const int candidates = int(lambdas.size());
  // h[j·order + l] · A_l
  std::vector<double> weights(std::size_t(candidates) * order);
  for (int j = 0; j < candidates; ++j) {
    const std::vector<double> h = window_band_factors(Window::Laplacian, order, lambdas[j]);
    for (int l = 0; l < order; ++l) {
      weights[j * order + l] = (j == 0 ? 1.0 : h[l]) * clamped_cosine_band_factor(l);
    }
  }

  const int lattice = std::clamp(64 * n2, 1024, 65536);
  std::vector<double> y(n2), band(order);
  std::vector<double> minimum(candidates, std::numeric_limits<double>::infinity());
  double largest = 0.0;  // max |E| unwindowed
  const double golden = kPi * (3.0 - std::sqrt(5.0));
  bool finite = true;
  const auto total = static_cast<std::uint64_t>(lattice + 6);
  for (int i = 0; i < lattice + 6; ++i) {
    if (progress && i % 256 == 0) progress(static_cast<std::uint64_t>(i), total);
    double x, yy, z;
    if (i < lattice) {
      z = 1.0 - (2.0 * i + 1.0) / lattice;
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z)), phi = golden * i;
      x = r * std::cos(phi);
      yy = r * std::sin(phi);
    } else {
      const int a = i - lattice;  // ±x, ±y, ±z
      const double s = a % 2 == 0 ? 1.0 : -1.0;
      x = a / 2 == 0 ? s : 0.0;
      yy = a / 2 == 1 ? s : 0.0;
      z = a / 2 == 2 ? s : 0.0;
    }
    evaluate(order, x, yy, z, y.data());
    for (int c = 0; c < channels; ++c) {
      const double* L = coefficients + std::size_t(c) * n2;
      for (int l = 0; l < order; ++l) {
        double s = 0.0;
        for (int k = l * l; k < (l + 1) * (l + 1); ++k) s += L[k] * y[k];
        band[l] = s;
      }
      for (int j = 0; j < candidates; ++j) {
        double e = 0.0;
        for (int l = 0; l < order; ++l) e += weights[j * order + l] * band[l];
        if (!std::isfinite(e)) finite = false;
        minimum[j] = std::min(minimum[j], e);
        if (j == 0) largest = std::max(largest, std::fabs(e));
      }
    }
  }
  if (progress) progress(total, total);
  if (!finite) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    return {Window::None, 0.0, nan, nan};
  }

  const double threshold = -1e-12 * largest;
  int chosen = -1, best = 0;
  for (int j = 0; j < candidates; ++j) {
    if (minimum[j] >= threshold) {
      chosen = j;
      break;
    }
    if (minimum[j] > minimum[best]) best = j;
  }
  if (chosen < 0) chosen = best;
  choice.window = chosen == 0 ? Window::None : Window::Laplacian;
  choice.strength = lambdas[chosen];
  choice.min_irradiance_before = minimum[0];
  choice.min_irradiance_after = minimum[chosen];
  return choice;
}

}  // namespace prt::sh
