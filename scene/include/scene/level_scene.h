// scene/level_scene.h — a procedural game level for benchmarks at scale: rooms on a grid joined
// by corridors, walls with door openings, floors and ceilings (closed: from inside, every ray
// meets a front face), pillars, crates (some stacked), tables, spheres and small clutter, and
// emissive lamps on the ceilings, with one camera. Deterministic: the same options give the same
// layout (and, tessellated, the same bytes) on every machine (SplitMix64, numerics/rng.h).
//
// Frame: glTF's (+Y up); units: metres. Rooms are 7–11 m wide and deep and 3–4 m high, on a
// grid of pitch 15 m (jittered by up to 1 m); corridors are 1.6 m wide and 2.3 m high, and their
// ends are exactly the door openings of the two rooms they join; the rooms and corridors form a
// random spanning tree of the grid plus some loops, so every room can be reached.
// Names (radiosity's --emission, --albedo and --move): every object is its own primitive, named
// crate_K, table_K, sphere_K, clutter_K, pillar_K; room R's surfaces are roomR_floor,
// roomR_walls, roomR_ceiling, its lamps roomR_lampK; corridor C's corridorC_floor,
// corridorC_walls, corridorC_ceiling, corridorC_lamp. Materials: floor, ceiling, wall (or
// wall_red, wall_blue, wall_green), stone, crate, crate_dark, wood, paint_red, paint_blue,
// paint_yellow, metal, clutter; emitters lamp_warm and lamp_cool (rooms, alternating) and
// lamp_corridor (kLampRadiance and kCorridorLampRadiance times their colour).
// Objects rest on the floor (or on a crate or table top), so boxes have no bottom face; lamps
// are thin boxes 2 cm under the ceiling, emitting from every face.
// The camera ("camera") stands in a corner of room 0 at eye height, looking at the middle of the
// far wall.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene/shape_layout.h"

namespace prt::scene {

constexpr int kMaxLevelRooms = 64;
constexpr int kMaxLevelObjects = 20000;
// The cell size of `prt make-scene --scene level` without a size target (metres).
constexpr double kLevelDefaultCell = 0.5;
// Room lamps' emitted radiance (times a colour of maximum 1) and the corridors'.
constexpr float kLampRadiance = 12.f;
constexpr float kCorridorLampRadiance = 6.f;

struct LevelOptions {
  uint64_t seed = 1;
  int rooms = 6;      // 1..kMaxLevelRooms
  int objects = 400;  // asked for, 0..kMaxLevelObjects (placement may leave a few out)
};

struct LevelSummary {
  int rooms = 0, corridors = 0, objects = 0, lamps = 0;
  std::vector<std::string> emitter_materials;  // in the order of their first lamp
};

struct LevelLayout {
  ShapeLayout layout;
  LevelSummary summary;
};

// The level's layout; throws std::invalid_argument when rooms or objects are out of range.
LevelLayout make_level_layout(const LevelOptions& options);

}  // namespace prt::scene
