// Tests of prt/formats/geometry_check.h: fingerprint sensitivity and the tolerant mesh comparison.
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "prt/formats/geometry_check.h"
#include "transfer_fixtures.h"

TEST_CASE("the fingerprint sees every coordinate to the last bit", "[geometry]") {
  const prt::TransferData d = prt::test::make_transfer_data(40, 1, 1, prt::Precision::F32, 6);
  std::vector<float> copy = d.positions;
  const uint64_t base = prt::geometry_fingerprint(copy.data(), 40);
  CHECK(base == prt::geometry_fingerprint(d.positions.data(), 40));  // equal data, equal hash
  for (std::size_t i = 0; i < copy.size(); ++i) {
    std::vector<float> changed = copy;
    changed[i] = std::nextafter(changed[i], INFINITY);  // 1 ulp
    INFO("coordinate " << i);
    REQUIRE(prt::geometry_fingerprint(changed.data(), 40) != base);
  }
  // Swapping two vertices changes it (order matters); a prefix of the mesh differs.
  std::vector<float> swapped = copy;
  std::swap(swapped[0], swapped[3]);
  std::swap(swapped[1], swapped[4]);
  std::swap(swapped[2], swapped[5]);
  CHECK(prt::geometry_fingerprint(swapped.data(), 40) != base);
  CHECK(prt::geometry_fingerprint(copy.data(), 39) != base);
  // −0 and +0 are the same position.
  std::vector<float> zero = {0.0f, 1.0f, 2.0f}, negative_zero = {-0.0f, 1.0f, 2.0f};
  CHECK(prt::geometry_fingerprint(zero.data(), 1) ==
        prt::geometry_fingerprint(negative_zero.data(), 1));
  // Zero vertices hash the count only, and differ from one vertex at the origin.
  const float origin[3] = {0, 0, 0};
  CHECK(prt::geometry_fingerprint(nullptr, 0) != prt::geometry_fingerprint(origin, 1));
}

TEST_CASE("check_geometry accepts the baked mesh and tiny re-export noise only", "[geometry]") {
  const prt::TransferData d = prt::test::make_transfer_data(50, 1, 1, prt::Precision::F32, 8);
  std::vector<float> mesh = d.positions;
  CHECK(prt::check_geometry(d, mesh.data(), 50, 0.0f).ok());

  // Extent: the diagonal of the positions' bounding box (coordinates in [−10, 10]).
  double lo[3] = {1e9, 1e9, 1e9}, hi[3] = {-1e9, -1e9, -1e9};
  for (std::size_t v = 0; v < 50; ++v) {
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min<double>(lo[a], mesh[3 * v + a]);
      hi[a] = std::max<double>(hi[a], mesh[3 * v + a]);
    }
  }
  const double extent =
      std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  // Move vertex 7 by 0.5e-5 × extent: inside a 1e-5 tolerance, outside a 1e-6 one.
  std::vector<float> nudged = mesh;
  nudged[3 * 7 + 1] += static_cast<float>(0.5e-5 * extent);
  CHECK(prt::check_geometry(d, nudged.data(), 50, 1e-5f).ok());
  const prt::Status refused = prt::check_geometry(d, nudged.data(), 50, 1e-6f);
  REQUIRE_FALSE(refused.ok());
  INFO(refused.message());
  CHECK(refused.message().find("vertex 7") != std::string::npos);

  // A different mesh with the same count.
  const prt::TransferData other = prt::test::make_transfer_data(50, 1, 1, prt::Precision::F32, 9);
  CHECK_FALSE(prt::check_geometry(d, other.positions.data(), 50, 1e-3f).ok());
  // A different count.
  const prt::Status count = prt::check_geometry(d, mesh.data(), 49, 1.0f);
  REQUIRE_FALSE(count.ok());
  CHECK(count.message().find("49") != std::string::npos);
  // Non-finite caller positions and a bad tolerance.
  nudged[5] = NAN;
  CHECK_FALSE(prt::check_geometry(d, nudged.data(), 50, 1e-3f).ok());
  CHECK_FALSE(prt::check_geometry(d, mesh.data(), 50, -1.0f).ok());
  CHECK_FALSE(prt::check_geometry(d, mesh.data(), 50, NAN).ok());
}
