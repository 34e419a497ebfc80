// hemicube_resolution_error — the error of hemicube form factors (radiosity/hemicube.h) against
// the resolution R (cells across the top face), R = 16, 32, … up to MAX_R:
//   two unit squares (parallel and perpendicular; the sender whole or in 8 × 8 squares): F
//   against Howell's closed forms, and the worst point error (the hemicube at a centroid against
//   Lambert's point-to-polygon value there);
//   the Cornell box subdivided to MAX_EDGE: each row's L1 difference to the analytic rows
//   (centroid rule, one visibility ray per pair), area-weighted mean and worst.
// Figures in docs/RADIOSITY.md ("The hemicube: error against resolution").
// Usage: hemicube_resolution_error [MAX_R [CORNELL_MAX_EDGE [CORNELL_OBJ]]]
//   defaults 512, 100 and ../shared/data/meshes/cornell_box.obj (skipped when missing).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "fixtures/radiosity/hemicube_errors.h"
#include "fixtures/radiosity/radiosity_fixtures.h"
#include "radiosity/form_factors.h"
#include "radiosity/patches.h"
#include "scene/ray_caster.h"

int main(int argc, char** argv) {
  using namespace prt::radiosity;
  const int max_r = argc > 1 ? std::atoi(argv[1]) : 512;
  const double max_edge = argc > 2 ? std::atof(argv[2]) : 100.0;
  const std::string obj =
      argc > 3 ? argv[3] : std::string(PRT_SHARED_DATA_DIR) + "/meshes/cornell_box.obj";
  if (argc > 4 || max_r < 16 || max_r > 4096 || !(max_edge > 0.0)) {
    std::fprintf(stderr,
                 "usage: hemicube_resolution_error [MAX_R (16..4096) [CORNELL_MAX_EDGE (> 0) "
                 "[CORNELL_OBJ]]]\n");
    return 2;
  }
  bool finite = true;
  for (int segments : {1, 8}) {
    for (bool perpendicular : {false, true}) {
      const std::vector<Patch> patches =
          make_patches(prt::test::two_squares(perpendicular, segments));
      const std::size_t half = patches.size() / 2;
      const double exact =
          perpendicular ? prt::test::kPerpendicularUnitSquares : prt::test::kParallelUnitSquares;
      const std::vector<glm::dvec3>& b =
          perpendicular ? prt::test::kPerpendicularUnitSquare : prt::test::kOppositeUnitSquare;
      for (int r = 16; r <= max_r; r *= 2) {
        const double f = prt::test::hemicube_square_to_square(patches, half, r);
        const double point = prt::test::worst_point_error(patches, half, b, r);
        finite = finite && std::isfinite(f) && std::isfinite(point);
        std::printf("%s segments %d R %4d: F %.6f  |F - closed| %.2e  worst point error %.2e\n",
                    perpendicular ? "perpendicular" : "parallel", segments, r, f,
                    std::abs(f - exact), point);
      }
    }
  }
  if (!std::filesystem::exists(obj)) {
    std::printf("Cornell box: skipped, %s is missing\n", obj.c_str());
    return finite ? 0 : 1;
  }
  const prt::scene::Scene scene = prt::test::cornell_box(obj, max_edge);
  const prt::scene::RayCaster caster(scene);
  const std::vector<Patch> patches = make_patches(scene);
  FormFactorOptions analytic;
  analytic.quadrature_points = 1;  // the hemicube's point: its centroid
  const FormFactorMatrix reference = compute_form_factors(patches, caster, analytic);
  for (int r = 16; r <= max_r; r *= 2) {
    FormFactorOptions o;
    o.method = FormFactorMethod::Hemicube;
    o.hemicube_resolution = r;
    const auto d =
        prt::test::row_difference(patches, compute_form_factors(patches, caster, o), reference);
    finite = finite && std::isfinite(d.first) && std::isfinite(d.second);
    std::printf("Cornell box, %zu patches, R %4d: mean row L1 %.2e, worst row %.2e\n",
                patches.size(), r, d.first, d.second);
  }
  return finite ? 0 : 1;
}
