// The C++ side of the JavaScript SH test (check_sh_js.mjs): prints, as JSON, what the sh library
// computes on fixed inputs — the basis at order 8 in 50 directions (a spherical Fibonacci set,
// the six axes and two near the poles), rotation matrices from yaw/pitch/roll, coefficient
// vectors rotated at orders 1..8, the windows' band factors and the clamped-cosine factors —
// so that web/sh.js can be compared with it on the same inputs.
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "sh/basis.h"
#include "sh/rotation.h"
#include "sh/window.h"
#include "sh/zonal.h"

namespace {

void print_array(const double* v, int n) {
  std::printf("[");
  for (int i = 0; i < n; ++i) std::printf("%s%.17g", i ? "," : "", v[i]);
  std::printf("]");
}

std::vector<std::array<double, 3>> directions() {
  std::vector<std::array<double, 3>> d;
  const int n = 42;
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - (2.0 * i + 1.0) / n, r = std::sqrt(1.0 - z * z);
    const double phi = i * 3.14159265358979323846 * (3.0 - std::sqrt(5.0));
    d.push_back({r * std::cos(phi), r * std::sin(phi), z});
  }
  for (int a = 0; a < 3; ++a)
    for (double s : {1.0, -1.0}) {
      std::array<double, 3> v{0, 0, 0};
      v[a] = s;
      d.push_back(v);
    }
  const double e = 1e-4;
  d.push_back({e, 0, std::sqrt(1 - e * e)});
  d.push_back({0, -e, -std::sqrt(1 - e * e)});
  return d;
}

}  // namespace

int main() {
  constexpr int kOrder = 8;
  std::printf("{\"order\":%d,\"basis\":[", kOrder);
  bool first = true;
  for (const auto& d : directions()) {
    double y[kOrder * kOrder];
    prt::sh::evaluate(kOrder, d[0], d[1], d[2], y);
    std::printf("%s{\"direction\":", first ? "" : ",");
    print_array(d.data(), 3);
    std::printf(",\"values\":");
    print_array(y, kOrder * kOrder);
    std::printf("}");
    first = false;
  }
  std::printf("],\"rotations\":[");
  const double angles[][3] = {{0, 0, 0}, {90, 0, 0}, {30, 20, 10}, {-135, 75, -40}, {200, -89, 33}};
  first = true;
  for (const auto& a : angles) {
    const std::array<double, 9> m = prt::sh::rotation_from_yaw_pitch_roll(a[0], a[1], a[2]);
    for (int order = 1; order <= kOrder; ++order) {
      std::vector<double> in(order * order), out(order * order);
      for (int k = 0; k < order * order; ++k) in[k] = std::sin(1.7 * k + 0.3) + 0.1 * k;
      prt::sh::Rotation(order, m).apply(in.data(), out.data());
      std::printf("%s{\"yaw_pitch_roll\":", first ? "" : ",");
      print_array(a, 3);
      std::printf(",\"matrix\":");
      print_array(m.data(), 9);
      std::printf(",\"order\":%d,\"input\":", order);
      print_array(in.data(), order * order);
      std::printf(",\"output\":");
      print_array(out.data(), order * order);
      std::printf("}");
      first = false;
    }
  }
  std::printf("],\"windows\":[");
  first = true;
  const std::pair<prt::sh::Window, double> windows[] = {
      {prt::sh::Window::None, 0},          {prt::sh::Window::Hanning, 0},
      {prt::sh::Window::Hanning, 5.5},     {prt::sh::Window::Lanczos, 0},
      {prt::sh::Window::Lanczos, 2},       {prt::sh::Window::Laplacian, 0},
      {prt::sh::Window::Laplacian, 0.0126}};
  for (const auto& [w, strength] : windows) {
    const std::vector<double> h = prt::sh::window_band_factors(w, kOrder, strength);
    std::printf("%s{\"name\":\"%s\",\"strength\":%.17g,\"factors\":", first ? "" : ",",
                prt::sh::window_name(w), strength);
    print_array(h.data(), kOrder);
    std::printf("}");
    first = false;
  }
  std::printf("],\"clamped_cosine\":");
  double a[kOrder];
  for (int l = 0; l < kOrder; ++l) a[l] = prt::sh::clamped_cosine_band_factor(l);
  print_array(a, kOrder);
  std::printf("}\n");
  return 0;
}
