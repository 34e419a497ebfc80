// geometry_check.cpp — mesh fingerprint and comparison; see prt/formats/geometry_check.h.
#include "prt/formats/geometry_check.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "numerics/hash.h"

namespace prt {

uint64_t geometry_fingerprint(const float* positions_xyz, std::size_t vertex_count) noexcept {
  numerics::WordHash h;
  h.add_u64(static_cast<uint64_t>(vertex_count));
  const std::size_t n = 3 * vertex_count;
  for (std::size_t i = 0; i < n; ++i) h.add_float(positions_xyz[i]);  // −0 enters as +0
  return h.finish();
}

Status check_geometry(const TransferData& data, const float* positions_xyz,
                      std::size_t vertex_count, float tolerance_fraction_of_extent) {
  if (vertex_count != data.vertex_count) {
    std::ostringstream os;
    os << "mesh: vertex count " << vertex_count << " differs from the baked mesh's "
       << data.vertex_count;
    return Status::Error(os.str());
  }
  if (!(tolerance_fraction_of_extent >= 0.0f) || !std::isfinite(tolerance_fraction_of_extent)) {
    return Status::Error("mesh: tolerance must be a finite fraction >= 0");
  }
  if (vertex_count == 0) return Status::Ok();
  if (positions_xyz == nullptr) return Status::Error("mesh: positions pointer is null");
  if (geometry_fingerprint(positions_xyz, vertex_count) == data.fingerprint) return Status::Ok();
  if (data.positions.size() != 3 * vertex_count) {
    return Status::Error("mesh: fingerprint differs and the transfer data holds no positions");
  }
  double lo[3], hi[3];
  for (int a = 0; a < 3; ++a) {
    lo[a] = std::numeric_limits<double>::infinity();
    hi[a] = -lo[a];
  }
  for (std::size_t v = 0; v < vertex_count; ++v) {
    for (int a = 0; a < 3; ++a) {
      const double p = data.positions[3 * v + a];
      lo[a] = std::min(lo[a], p);
      hi[a] = std::max(hi[a], p);
    }
  }
  const double extent =
      std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                (hi[2] - lo[2]) * (hi[2] - lo[2]));
  const double tolerance = static_cast<double>(tolerance_fraction_of_extent) * extent;
  double worst = 0.0;
  std::size_t worst_vertex = 0;
  for (std::size_t v = 0; v < vertex_count; ++v) {
    double d2 = 0.0;
    for (int a = 0; a < 3; ++a) {
      const double q = positions_xyz[3 * v + a];
      if (!std::isfinite(q)) {
        std::ostringstream os;
        os << "mesh: vertex " << v << " has a non-finite coordinate";
        return Status::Error(os.str());
      }
      const double d = q - static_cast<double>(data.positions[3 * v + a]);
      d2 += d * d;
    }
    const double dist = std::sqrt(d2);
    if (dist > worst) {
      worst = dist;
      worst_vertex = v;
    }
  }
  if (worst <= tolerance) return Status::Ok();
  std::ostringstream os;
  os.precision(9);
  os << "mesh: not the baked mesh: vertex " << worst_vertex << " is " << worst
     << " away from the baked position (tolerance " << tolerance << " = "
     << tolerance_fraction_of_extent << " x extent " << extent << ")";
  return Status::Error(os.str());
}

}  // namespace prt
