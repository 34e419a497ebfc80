// tests/golden/golden_scenes.h — the small scenes of the golden-image set that prt does not ship
// in data/, written as OBJ (+ MTL, + a PNG texture) into a work folder before they are rendered.
// Each is deterministic (fixed coordinates, no randomness), coarse (the commands subdivide with
// --max-edge) and flat-shaded (one `vn` per face, so box edges stay sharp).
//
//   cornell_box.obj/.mtl   the Cornell box (Cornell University Program of Computer Graphics'
//                          published geometry, in metres: x 0..0.556, y 0..0.549, z 0..0.559, open
//                          at z = 0), white/red/green walls with its albedos, a lamp 1 cm below the
//                          ceiling whose material `light` emits Ke 20 (docs/RADIOSITY.md's values).
//   sun_pillar.obj         a 4 × 4 grey floor (albedo 0.5) and a 0.5 × 1.5 × 0.5 pillar, for a
//                          sharp sun shadow.
//   textured_wall.obj/.mtl a 4 × 2 wall textured with bricks.png (map_Kd, repeated 2 × 2) behind
//   bricks.png             a grey floor and a white cube; bricks.png is a 128 × 64 running-bond
//                          brick pattern (sRGB).
// Throws std::runtime_error "PATH: problem" when a file cannot be written.
#pragma once

#include <filesystem>

namespace prt::golden {

void write_cornell_box(const std::filesystem::path& dir);
void write_sun_pillar(const std::filesystem::path& dir);
void write_textured_wall(const std::filesystem::path& dir);

}  // namespace prt::golden
