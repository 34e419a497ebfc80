// The procedural game level (see scene/level_scene.h).
#include "scene/level_scene.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <utility>

#include "numerics/rng.h"

namespace prt::scene {
namespace {

constexpr double kPitch = 15.0;          // room grid pitch
constexpr double kDoorWidth = 1.6;       // corridor width = door width
constexpr double kDoorHeight = 2.3;      // corridor height = door height
constexpr double kWallClearance = 0.15;  // objects keep this far from walls
constexpr double kExtraCorridor = 0.3;   // chance of a corridor beyond the spanning tree

const glm::dvec3 kX(1, 0, 0), kY(0, 1, 0), kZ(0, 0, 1);

struct Random {
  numerics::SplitMix64 stream;
  double uniform(double a, double b) { return a + (b - a) * stream.uniform(); }
  int below(int n) { return std::min(n - 1, static_cast<int>(stream.uniform() * n)); }
  bool chance(double p) { return stream.uniform() < p; }
};

struct Rect {
  double x0, x1, z0, z1;
  bool overlaps(const Rect& o, double margin) const {
    return x0 < o.x1 + margin && o.x0 < x1 + margin && z0 < o.z1 + margin && o.z0 < z1 + margin;
  }
};

// Sides of a room: 0 the wall x = x0, 1 x = x1, 2 z = z0, 3 z = z1.
struct Door {
  int side;
  double centre;  // along the wall: z for sides 0 and 1, x for sides 2 and 3
};

struct Room {
  double x0, x1, z0, z1, height;
  std::vector<Door> doors;
  std::vector<Rect> taken;    // footprints of objects, pillars and door approaches
  std::vector<Rect> shelves;  // crate and table tops that take one clutter item each
  std::vector<double> shelf_heights;
  double area() const { return (x1 - x0) * (z1 - z0); }
};

// A horizontal rectangle [x0, x0+wx] × [z0, z0+wz] at height y, facing up or down.
PanelShape horizontal(double x0, double z0, double wx, double wz, double y, bool up) {
  return up ? make_panel({x0, y, z0}, kZ, wz, kX, wx) : make_panel({x0, y, z0}, kX, wx, kZ, wz);
}

// A vertical wall from `corner` along `along` (kX or kZ) for `length`, `height` high, facing
// `facing`, with door openings [a, b] × [0, kDoorHeight] (a, b measured along the wall).
PanelShape wall(glm::dvec3 corner, glm::dvec3 along, double length, double height,
                glm::dvec3 facing, const std::vector<std::pair<double, double>>& doors) {
  const bool along_first = glm::dot(glm::cross(along, kY), facing) > 0.0;
  PanelShape p = along_first ? make_panel(corner, along, length, kY, height)
                             : make_panel(corner, kY, height, along, length);
  for (const auto& [a, b] : doors) {
    PanelShape::Hole h;
    if (along_first)
      h = {a, b, 0.0, kDoorHeight};
    else
      h = {0.0, kDoorHeight, a, b};
    p.holes.push_back(h);
  }
  return p;
}

LayoutPart part(std::string name, std::string material, glm::vec3 albedo) {
  LayoutPart p;
  p.name = std::move(name);
  p.material = std::move(material);
  p.albedo = albedo;
  return p;
}

std::vector<Room> plan_rooms(Random& rng, int count, int columns) {
  std::vector<Room> rooms;
  for (int r = 0; r < count; ++r) {
    const double cx = (r % columns) * kPitch + rng.uniform(-1.0, 1.0);
    const double cz = (r / columns) * kPitch + rng.uniform(-1.0, 1.0);
    const double wx = rng.uniform(7.0, 11.0), wz = rng.uniform(7.0, 11.0);
    Room room;
    room.x0 = cx - 0.5 * wx;
    room.x1 = cx + 0.5 * wx;
    room.z0 = cz - 0.5 * wz;
    room.z1 = cz + 0.5 * wz;
    room.height = rng.uniform(3.0, 4.0);
    rooms.push_back(room);
  }
  return rooms;
}

// A random spanning tree of the room grid (Kruskal over shuffled edges) plus some loops.
std::vector<std::pair<int, int>> plan_corridors(Random& rng, int count, int columns) {
  std::vector<std::pair<int, int>> edges, chosen;
  for (int r = 0; r < count; ++r) {
    if (r % columns + 1 < columns && r + 1 < count) edges.emplace_back(r, r + 1);
    if (r + columns < count) edges.emplace_back(r, r + columns);
  }
  for (std::size_t i = edges.size(); i > 1; --i)  // Fisher–Yates
    std::swap(edges[i - 1], edges[static_cast<std::size_t>(rng.below(static_cast<int>(i)))]);
  std::vector<int> parent(static_cast<std::size_t>(count));
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const auto& [a, b] : edges) {
    const int ra = find(a), rb = find(b);
    const bool tree = ra != rb;
    if (tree) parent[ra] = rb;
    if (rng.chance(tree ? 1.0 : kExtraCorridor)) chosen.emplace_back(a, b);
  }
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// The corridor joining room a to room b (b to the +X or +Z of a): its parts, a lamp, and a door
// in each room's facing wall.
void add_corridor(ShapeLayout& layout, Room& a, Room& b, int index, Random& rng) {
  const bool along_x = b.x0 > a.x1;
  const double margin = 0.5 * kDoorWidth + 0.6;
  const double lo = along_x ? std::max(a.z0, b.z0) + margin : std::max(a.x0, b.x0) + margin;
  const double hi = along_x ? std::min(a.z1, b.z1) - margin : std::min(a.x1, b.x1) - margin;
  const double centre = rng.uniform(lo, hi), half = 0.5 * kDoorWidth;
  a.doors.push_back({along_x ? 1 : 3, centre});
  b.doors.push_back({along_x ? 0 : 2, centre});
  const std::string name = "corridor" + std::to_string(index);
  LayoutPart floor = part(name + "_floor", "floor", {0.45f, 0.4f, 0.35f});
  LayoutPart walls = part(name + "_walls", "wall", {0.7f, 0.68f, 0.62f});
  LayoutPart ceiling = part(name + "_ceiling", "ceiling", glm::vec3(0.8f));
  LayoutPart lamp = part(name + "_lamp", "lamp_corridor", glm::vec3(0.8f));
  lamp.emission = kCorridorLampRadiance * glm::vec3(1.f, 0.9f, 0.75f);
  const double y_lamp = kDoorHeight - 0.02;
  if (along_x) {
    const double x0 = a.x1, length = b.x0 - a.x1, z0 = centre - half;
    floor.panels.push_back(horizontal(x0, z0, length, kDoorWidth, 0.0, true));
    ceiling.panels.push_back(horizontal(x0, z0, length, kDoorWidth, kDoorHeight, false));
    walls.panels.push_back(wall({x0, 0, z0}, kX, length, kDoorHeight, kZ, {}));
    walls.panels.push_back(wall({x0, 0, z0 + kDoorWidth}, kX, length, kDoorHeight, -kZ, {}));
    const double mid = x0 + 0.5 * length;
    lamp.boxes.push_back(
        {{mid - 0.4, y_lamp - 0.05, centre - 0.15}, {mid + 0.4, y_lamp, centre + 0.15}, true});
  } else {
    const double z0 = a.z1, length = b.z0 - a.z1, x0 = centre - half;
    floor.panels.push_back(horizontal(x0, z0, kDoorWidth, length, 0.0, true));
    ceiling.panels.push_back(horizontal(x0, z0, kDoorWidth, length, kDoorHeight, false));
    walls.panels.push_back(wall({x0, 0, z0}, kZ, length, kDoorHeight, kX, {}));
    walls.panels.push_back(wall({x0 + kDoorWidth, 0, z0}, kZ, length, kDoorHeight, -kX, {}));
    const double mid = z0 + 0.5 * length;
    lamp.boxes.push_back(
        {{centre - 0.15, y_lamp - 0.05, mid - 0.4}, {centre + 0.15, y_lamp, mid + 0.4}, true});
  }
  for (LayoutPart* p : {&floor, &walls, &ceiling, &lamp}) layout.parts.push_back(std::move(*p));
}

// Room r's floor, walls (with its doors) and ceiling; the doors' approaches are kept free.
void add_room(ShapeLayout& layout, Room& room, int r, Random& rng) {
  static const char* const kWallMaterials[] = {"wall", "wall_red", "wall_blue", "wall_green"};
  static const glm::vec3 kWallAlbedo[] = {
      {0.7f, 0.68f, 0.62f}, {0.7f, 0.25f, 0.2f}, {0.25f, 0.35f, 0.7f}, {0.3f, 0.6f, 0.3f}};
  const std::string name = "room" + std::to_string(r);
  const double wx = room.x1 - room.x0, wz = room.z1 - room.z0, h = room.height;
  LayoutPart floor = part(name + "_floor", "floor", {0.45f, 0.4f, 0.35f});
  floor.panels.push_back(horizontal(room.x0, room.z0, wx, wz, 0.0, true));
  LayoutPart ceiling = part(name + "_ceiling", "ceiling", glm::vec3(0.8f));
  ceiling.panels.push_back(horizontal(room.x0, room.z0, wx, wz, h, false));
  const int colour = rng.chance(0.5) ? 0 : 1 + rng.below(3);
  LayoutPart walls = part(name + "_walls", kWallMaterials[colour], kWallAlbedo[colour]);
  std::vector<std::pair<double, double>> openings[4];
  for (const Door& d : room.doors) {
    const double start = d.side < 2 ? room.z0 : room.x0;
    openings[d.side].emplace_back(d.centre - start - 0.5 * kDoorWidth,
                                  d.centre - start + 0.5 * kDoorWidth);
    const double depth = 1.8, half = 0.5 * kDoorWidth + 0.5;
    switch (d.side) {  // the approach in front of the door stays clear
      case 0:
        room.taken.push_back({room.x0, room.x0 + depth, d.centre - half, d.centre + half});
        break;
      case 1:
        room.taken.push_back({room.x1 - depth, room.x1, d.centre - half, d.centre + half});
        break;
      case 2:
        room.taken.push_back({d.centre - half, d.centre + half, room.z0, room.z0 + depth});
        break;
      default:
        room.taken.push_back({d.centre - half, d.centre + half, room.z1 - depth, room.z1});
    }
  }
  walls.panels.push_back(wall({room.x0, 0, room.z0}, kZ, wz, h, kX, openings[0]));
  walls.panels.push_back(wall({room.x1, 0, room.z0}, kZ, wz, h, -kX, openings[1]));
  walls.panels.push_back(wall({room.x0, 0, room.z0}, kX, wx, h, kZ, openings[2]));
  walls.panels.push_back(wall({room.x0, 0, room.z1}, kX, wx, h, -kZ, openings[3]));
  for (LayoutPart* p : {&floor, &walls, &ceiling}) layout.parts.push_back(std::move(*p));
}

// Room r's ceiling lamps: one per 8.5 m or less of each side, on a grid; a lamp over a pillar
// moves 1.1 m toward the room's middle.
void add_lamps(ShapeLayout& layout, const Room& room, int r, const std::vector<Rect>& pillars,
               LevelSummary& summary) {
  const std::string name = "room" + std::to_string(r);
  const double wx = room.x1 - room.x0, wz = room.z1 - room.z0, h = room.height;
  const bool warm = (r % 2 == 0);
  const std::string lamp_material = warm ? "lamp_warm" : "lamp_cool";
  const glm::vec3 colour = warm ? glm::vec3(1.f, 0.78f, 0.5f) : glm::vec3(0.62f, 0.78f, 1.f);
  const int nx = wx > 8.5 ? 2 : 1, nz = wz > 8.5 ? 2 : 1;
  for (int i = 0; i < nx * nz; ++i) {
    const double cx = room.x0 + wx * ((i % nx) + 0.5) / nx;
    double cz = room.z0 + wz * ((i / nx) + 0.5) / nz;
    const Rect footprint{cx - 0.5, cx + 0.5, cz - 0.5, cz + 0.5};
    for (const Rect& p : pillars)
      if (footprint.overlaps(p, 0.1)) cz += cz < 0.5 * (room.z0 + room.z1) ? 1.1 : -1.1;
    LayoutPart lamp = part(name + "_lamp" + std::to_string(i), lamp_material, glm::vec3(0.8f));
    lamp.emission = kLampRadiance * colour;
    lamp.boxes.push_back({{cx - 0.5, h - 0.1, cz - 0.5}, {cx + 0.5, h - 0.02, cz + 0.5}, true});
    layout.parts.push_back(std::move(lamp));
    ++summary.lamps;
    if (std::find(summary.emitter_materials.begin(), summary.emitter_materials.end(),
                  lamp_material) == summary.emitter_materials.end())
      summary.emitter_materials.push_back(lamp_material);
  }
}

// Pillars from floor to ceiling in the larger rooms, two or four on a grid of quarters.
std::vector<Rect> add_pillars(ShapeLayout& layout, Room& room, int& counter, Random& rng) {
  std::vector<Rect> placed;
  const double wx = room.x1 - room.x0, wz = room.z1 - room.z0, radius = 0.28;
  std::vector<glm::dvec2> at;
  const double cx = 0.5 * (room.x0 + room.x1), cz = 0.5 * (room.z0 + room.z1);
  if (wx > 8.5 && wz > 8.5 && rng.chance(0.7)) {
    for (int i = 0; i < 4; ++i)
      at.emplace_back(cx + (i % 2 ? 0.25 : -0.25) * wx, cz + (i / 2 ? 0.25 : -0.25) * wz);
  } else if (std::max(wx, wz) > 9.0) {
    for (double side : {-0.25, 0.25})
      at.push_back(wx > wz ? glm::dvec2(cx + side * wx, cz) : glm::dvec2(cx, cz + side * wz));
  }
  for (const glm::dvec2& p : at) {
    const Rect footprint{p.x - radius, p.x + radius, p.y - radius, p.y + radius};
    bool free = true;
    for (const Rect& t : room.taken) free = free && !footprint.overlaps(t, 0.1);
    if (!free) continue;
    LayoutPart pillar = part("pillar_" + std::to_string(counter++), "stone", {0.6f, 0.58f, 0.55f});
    pillar.cylinders.push_back({{p.x, 0.0, p.y}, radius, room.height});
    layout.parts.push_back(std::move(pillar));
    room.taken.push_back(footprint);
    placed.push_back(footprint);
  }
  return placed;
}

// A free spot for a footprint of half-sizes (hx, hz) on the room's floor, or false.
bool find_spot(Room& room, double hx, double hz, Random& rng, Rect& out) {
  for (int attempt = 0; attempt < 40; ++attempt) {
    const double x = rng.uniform(room.x0 + kWallClearance + hx, room.x1 - kWallClearance - hx);
    const double z = rng.uniform(room.z0 + kWallClearance + hz, room.z1 - kWallClearance - hz);
    const Rect r{x - hx, x + hx, z - hz, z + hz};
    bool free = true;
    for (const Rect& t : room.taken) free = free && !r.overlaps(t, 0.05);
    if (free) {
      room.taken.push_back(r);
      out = r;
      return true;
    }
  }
  return false;
}

struct Counters {
  int crate = 0, table = 0, sphere = 0, clutter = 0;
};

glm::vec3 paint(Random& rng, std::string& material) {
  static const char* const kNames[] = {"paint_red", "paint_blue", "paint_yellow"};
  static const glm::vec3 kAlbedo[] = {
      {0.75f, 0.12f, 0.1f}, {0.12f, 0.25f, 0.7f}, {0.8f, 0.65f, 0.1f}};
  const int k = rng.below(3);
  material = kNames[k];
  return kAlbedo[k];
}

// One crate (maybe with a smaller one on it), table, sphere or clutter item; returns how many
// objects it placed.
int place_object(ShapeLayout& layout, Room& room, Counters& n, Random& rng) {
  const double kind = rng.stream.uniform();
  Rect r{};
  if (kind < 0.28) {  // a crate, a third of them with a smaller one on top
    const double s = rng.uniform(0.5, 1.0);
    const double hx = 0.5 * s * rng.uniform(0.85, 1.15), hz = 0.5 * s * rng.uniform(0.85, 1.15);
    const double height = s * rng.uniform(0.8, 1.1);
    if (!find_spot(room, hx, hz, rng, r)) return 0;
    const bool dark = rng.chance(0.4), stacked = rng.chance(0.35);
    LayoutPart crate = part("crate_" + std::to_string(n.crate++), dark ? "crate_dark" : "crate",
                            dark ? glm::vec3(0.35f, 0.25f, 0.15f) : glm::vec3(0.55f, 0.4f, 0.22f));
    crate.boxes.push_back({{r.x0, 0.0, r.z0}, {r.x1, height, r.z1}, false});
    layout.parts.push_back(std::move(crate));
    if (!stacked) {
      room.shelves.push_back(r);
      room.shelf_heights.push_back(height);
      return 1;
    }
    const double f = rng.uniform(0.5, 0.8), cx = 0.5 * (r.x0 + r.x1), cz = 0.5 * (r.z0 + r.z1);
    const Rect top{cx - f * hx, cx + f * hx, cz - f * hz, cz + f * hz};
    const double top_height = height + 2.0 * f * hx * rng.uniform(0.8, 1.1);
    LayoutPart upper = part("crate_" + std::to_string(n.crate++), "crate", {0.55f, 0.4f, 0.22f});
    upper.boxes.push_back({{top.x0, height, top.z0}, {top.x1, top_height, top.z1}, false});
    layout.parts.push_back(std::move(upper));
    room.shelves.push_back(top);
    room.shelf_heights.push_back(top_height);
    return 2;
  }
  if (kind < 0.36) {  // a table: a top on four legs
    const bool turned = rng.chance(0.5);
    const double hx = turned ? 0.4 : 0.6, hz = turned ? 0.6 : 0.4, top = 0.75, leg = 0.06;
    if (!find_spot(room, hx, hz, rng, r)) return 0;
    LayoutPart table = part("table_" + std::to_string(n.table++), "wood", {0.5f, 0.33f, 0.18f});
    table.boxes.push_back({{r.x0, top - 0.05, r.z0}, {r.x1, top, r.z1}, true});
    for (int i = 0; i < 4; ++i) {
      const double x = i % 2 ? r.x1 - leg - 0.03 : r.x0 + 0.03,
                   z = i / 2 ? r.z1 - leg - 0.03 : r.z0 + 0.03;
      table.boxes.push_back({{x, 0.0, z}, {x + leg, top - 0.05, z + leg}, false});
    }
    layout.parts.push_back(std::move(table));
    room.shelves.push_back(r);
    room.shelf_heights.push_back(top);
    return 1;
  }
  std::string material;
  if (kind < 0.48) {  // a sphere on the floor
    const double radius = rng.uniform(0.25, 0.55);
    if (!find_spot(room, radius, radius, rng, r)) return 0;
    const glm::vec3 albedo = paint(rng, material);
    LayoutPart sphere = part("sphere_" + std::to_string(n.sphere++), material, albedo);
    sphere.spheres.push_back({{0.5 * (r.x0 + r.x1), radius, 0.5 * (r.z0 + r.z1)}, radius});
    layout.parts.push_back(std::move(sphere));
    return 1;
  }
  // Clutter: a small box or ball, on a free crate or table top when there is one, else the floor.
  const bool ball = rng.chance(0.35);
  double size = ball ? rng.uniform(0.05, 0.14) : rng.uniform(0.04, 0.15);
  const double stretch = ball ? 1.0 : rng.uniform(0.6, 1.4);
  const double height_ratio = ball ? 1.0 : rng.uniform(0.5, 1.5);
  double y = 0.0;
  if (!room.shelves.empty() && rng.chance(0.5)) {  // centred on the top, inside its edges
    const Rect s = room.shelves.back();
    y = room.shelf_heights.back();
    room.shelves.pop_back();
    room.shelf_heights.pop_back();
    size = std::min({size, 0.4 * (s.x1 - s.x0), 0.4 * (s.z1 - s.z0) / stretch});
    const double cx = 0.5 * (s.x0 + s.x1), cz = 0.5 * (s.z0 + s.z1);
    r = {cx - size, cx + size, cz - size * stretch, cz + size * stretch};
  } else if (!find_spot(room, size, size * stretch, rng, r)) {
    return 0;
  }
  glm::vec3 albedo(0.5f, 0.5f, 0.45f);
  material = "clutter";
  if (rng.chance(0.3))
    albedo = paint(rng, material);
  else if (rng.chance(0.3))
    material = "metal", albedo = glm::vec3(0.6f);
  LayoutPart item = part("clutter_" + std::to_string(n.clutter++), material, albedo);
  if (ball)
    item.spheres.push_back({{0.5 * (r.x0 + r.x1), y + size, 0.5 * (r.z0 + r.z1)}, size});
  else
    item.boxes.push_back({{r.x0, y, r.z0}, {r.x1, y + 2.0 * size * height_ratio, r.z1}, false});
  layout.parts.push_back(std::move(item));
  return 1;
}

}  // namespace

LevelLayout make_level_layout(const LevelOptions& options) {
  if (options.rooms < 1 || options.rooms > kMaxLevelRooms)
    throw std::invalid_argument("--rooms " + std::to_string(options.rooms) + ": expected 1 to " +
                                std::to_string(kMaxLevelRooms));
  if (options.objects < 0 || options.objects > kMaxLevelObjects)
    throw std::invalid_argument("--objects " + std::to_string(options.objects) +
                                ": expected 0 to " + std::to_string(kMaxLevelObjects));
  LevelLayout level;
  ShapeLayout& layout = level.layout;
  layout.source_path = "procedural:level";
  Random rng{numerics::SplitMix64{numerics::hash_seed(options.seed, 0x1e7e1)}};
  const int columns = static_cast<int>(std::ceil(std::sqrt(double(options.rooms))));
  std::vector<Room> rooms = plan_rooms(rng, options.rooms, columns);
  const std::vector<std::pair<int, int>> corridors = plan_corridors(rng, options.rooms, columns);
  for (std::size_t c = 0; c < corridors.size(); ++c)
    add_corridor(layout, rooms[corridors[c].first], rooms[corridors[c].second], int(c), rng);

  // The camera: a corner of room 0 at eye height, looking at the middle of the far
  // wall (past the pillars, which stand on the quarters), kept clear.
  Room& first = rooms[0];
  SceneCamera camera;
  camera.name = "camera";
  camera.eye = glm::vec3(float(first.x0 + 0.7), 1.7f, float(first.z1 - 0.7));
  camera.target = glm::vec3(float(first.x1 - 1.0), 1.0f, float(0.5 * (first.z0 + first.z1)));
  camera.yfov_radians = 1.1f;
  layout.cameras.push_back(camera);
  first.taken.push_back({first.x0, first.x0 + 1.6, first.z1 - 1.6, first.z1});

  int pillars = 0;
  for (int r = 0; r < options.rooms; ++r) {
    add_room(layout, rooms[r], r, rng);
    const std::vector<Rect> columns_here = add_pillars(layout, rooms[r], pillars, rng);
    add_lamps(layout, rooms[r], r, columns_here, level.summary);
  }

  double total_area = 0.0;
  for (const Room& room : rooms) total_area += room.area();
  Counters counters;
  int placed = 0;
  for (int attempt = 0; placed < options.objects && attempt < 3 * options.objects; ++attempt) {
    double pick = rng.uniform(0.0, total_area);  // a room, by floor area
    std::size_t r = 0;
    while (r + 1 < rooms.size() && pick >= rooms[r].area()) pick -= rooms[r++].area();
    placed += place_object(layout, rooms[r], counters, rng);
  }
  level.summary.rooms = options.rooms;
  level.summary.corridors = static_cast<int>(corridors.size());
  level.summary.objects = placed + pillars;
  return level;
}

}  // namespace prt::scene
