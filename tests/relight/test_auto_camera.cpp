// The automatic camera (relight/auto_camera.h): inside a room, outside an object.
//
// What a camera "sees" is measured with an independent grid of primary rays (24 × 16, not the
// probe's grid): the fraction of rays that hit something (coverage) and the fraction of hits that
// are front faces. Inside a room every view direction meets an inward-facing wall, so both are
// near 1; the outside camera of a room (the failure this guards against) sees wall backs.
#include <cmath>
#include <string>

#include <catch2/catch.hpp>
#include <glm/glm.hpp>

#include "relight/auto_camera.h"
#include "relight/camera.h"
#include "relight/radiosity_render.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "scene/subdivide.h"
#include "support/test_data.h"

using prt::relight::Camera;
using prt::scene::Scene;

namespace {

constexpr float kAspect = 16.f / 9.f;

enum Side { kFloor, kCeiling, kLeft, kRight, kBack, kFront };  // y=0, y=1, x=0, x=1, z=1, z=0

// The unit cube [0, 1]³ as six inward-facing walls (4 × 4 cells each), without `open` (or
// closed when open < 0). The front wall z = 0 faces away from frame_bounds' camera, which
// looks from +X, +Y, +Z.
Scene make_room(int open) {
  const glm::vec3 grey(0.6f);
  struct Wall {
    glm::vec3 corner, u, v;  // normal = cross(u, v), pointing into the cube
  };
  const Wall walls[6] = {
      {{0, 0, 0}, {0, 0, 1}, {1, 0, 0}},  // floor, +Y
      {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},  // ceiling, −Y
      {{0, 0, 0}, {0, 1, 0}, {0, 0, 1}},  // x = 0, +X
      {{1, 0, 0}, {0, 0, 1}, {0, 1, 0}},  // x = 1, −X
      {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}},  // z = 1, −Z
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},  // z = 0, +Z
  };
  Scene room;
  for (int w = 0; w < 6; ++w)
    if (w != open)
      prt::scene::append_scene(room, prt::scene::make_quad(walls[w].corner, walls[w].u, walls[w].v,
                                                           4, 4, grey, "wall" + std::to_string(w)));
  return room;
}

struct View {
  double coverage = 0, front = 0;
};

View look(const prt::scene::RayCaster& caster, const Camera& camera) {
  const auto basis = prt::relight::make_camera_basis(camera, kAspect);
  int rays = 0, hits = 0, front = 0;
  for (int row = 0; row < 16; ++row) {
    for (int col = 0; col < 24; ++col) {
      const float x = -1.f + (2.f * static_cast<float>(col) + 1.f) / 24.f;
      const float y = 1.f - (2.f * static_cast<float>(row) + 1.f) / 16.f;
      const auto hit =
          caster.intersect(camera.eye, prt::relight::ray_direction(basis, x, y), 0.f, 1e30f);
      ++rays;
      hits += hit.hit ? 1 : 0;
      front += hit.hit && hit.front_face ? 1 : 0;
    }
  }
  View view;
  view.coverage = double(hits) / rays;
  view.front = hits ? double(front) / hits : 0.0;
  return view;
}

bool inside_bounds(const Scene& scene, glm::vec3 p) {
  const glm::vec3 lo = scene.bounds_min(), hi = scene.bounds_max();
  return p.x > lo.x && p.y > lo.y && p.z > lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
}

// A room's automatic view: it sees the room's inside (front faces, the view filled). A closed
// room is seen from inside its bounds; an open one through its open side (from outside).
void require_inside_view(const Scene& scene, bool closed = true) {
  const prt::scene::RayCaster caster(scene);
  const prt::relight::AutoCamera chosen = prt::relight::choose_auto_camera(scene, caster, kAspect);
  INFO("enclosed " << chosen.probe.enclosed_fraction << ", outside backs "
                   << chosen.probe.outside_back_fraction << ", open "
                   << chosen.probe.open_fraction);
  REQUIRE(chosen.inside);
  if (closed) CHECK(inside_bounds(scene, chosen.camera.eye));
  const View view = look(caster, chosen.camera);
  INFO("coverage " << view.coverage << ", front " << view.front);
  // The view is filled by the room (through a square opening at 16:9: its height and a little
  // over half its width) ...
  CHECK(view.coverage > (closed ? 0.95 : 0.45));
  CHECK(view.front > 0.95);  // ... seen from inside
  // The failure this replaces: from outside, the same room shows mostly wall backs.
  const View outside =
      look(caster, prt::relight::frame_bounds(scene.bounds_min(), scene.bounds_max(), kAspect));
  CHECK(outside.front < 0.5);
  CHECK(chosen.note.find("a room") != std::string::npos);
}

void require_outside_view(const Scene& scene) {
  const prt::scene::RayCaster caster(scene);
  const prt::relight::AutoCamera chosen = prt::relight::choose_auto_camera(scene, caster, kAspect);
  INFO("enclosed " << chosen.probe.enclosed_fraction << ", outside backs "
                   << chosen.probe.outside_back_fraction);
  CHECK_FALSE(chosen.inside);
  const Camera expected =
      prt::relight::frame_bounds(scene.bounds_min(), scene.bounds_max(), kAspect);
  CHECK(chosen.camera.eye == expected.eye);
  CHECK(chosen.camera.target == expected.target);
  CHECK(look(caster, chosen.camera).front > 0.95);
}

}  // namespace

TEST_CASE("auto camera: an open box facing away from the default view is looked into") {
  const Scene room = make_room(kFront);
  require_inside_view(room, false);
  const prt::scene::RayCaster caster(room);
  const auto chosen = prt::relight::choose_auto_camera(room, caster, kAspect);
  // It stands in front of the open side (z = 0), on the box's axis, and looks through the room
  // toward the back wall (+Z), the opening's frame just outside the 40° view (5% margin):
  // distance 1.05 · 0.5 / tan 20° = 1.4425 from the opening.
  const glm::vec3 forward = glm::normalize(chosen.camera.target - chosen.camera.eye);
  CHECK(forward.z == 1.f);
  CHECK(chosen.camera.eye.x == Approx(0.5f));
  CHECK(chosen.camera.eye.y == Approx(0.5f));
  CHECK(chosen.camera.eye.z ==
        Approx(-1.05 * 0.5 / std::tan(20.0 * 3.14159265358979 / 180.0)).epsilon(1e-5));
  CHECK(chosen.camera.yfov_radians == Approx(40.0 * 3.14159265358979 / 180.0).epsilon(1e-6));
  CHECK(chosen.probe.open_fraction > 0.1);  // the missing wall subtends 1/6 of the sphere
}

TEST_CASE("auto camera: an open box with its open side up is looked into through the opening") {
  const Scene room = make_room(kCeiling);
  const prt::scene::RayCaster caster(room);
  const auto chosen = prt::relight::choose_auto_camera(room, caster, kAspect);
  // From frame_bounds' elevated view the opening shows the inside: either camera is right as
  // long as the view shows front faces.
  CHECK(look(caster, chosen.camera).front > 0.9);
}

TEST_CASE("auto camera: a closed room gets a camera inside, along its longest span") {
  require_inside_view(make_room(-1));
  // A long closed room (4 × 1 × 1): the view runs along x.
  Scene hall = make_room(-1);
  for (glm::vec3& p : hall.positions) p.x *= 4.f;
  const prt::scene::RayCaster caster(hall);
  const auto chosen = prt::relight::choose_auto_camera(hall, caster, kAspect);
  REQUIRE(chosen.inside);
  const glm::vec3 forward = glm::normalize(chosen.camera.target - chosen.camera.eye);
  CHECK(std::abs(forward.x) > 0.99f);
  CHECK(look(caster, chosen.camera).front > 0.95);
}

TEST_CASE("auto camera: objects keep the outside camera (sphere, sphere on a ground, bunny)") {
  SECTION("a closed sphere") {
    require_outside_view(
        prt::scene::make_uv_sphere({0, 0, 0}, 1.f, 16, 32, false, glm::vec3(0.5f)));
  }
  SECTION("a sphere resting on a ground quad") {
    Scene scene =
        prt::scene::make_quad({-3, 0, -3}, {0, 0, 6}, {6, 0, 0}, 8, 8, glm::vec3(0.5f), "ground");
    prt::scene::append_scene(
        scene, prt::scene::make_uv_sphere({0, 1, 0}, 1.f, 16, 32, false, glm::vec3(0.5f)));
    require_outside_view(scene);
  }
  SECTION("the Stanford bunny (decimated)") {
    const auto path = prt::test::shared_data("meshes/bunny_small.obj");
    PRT_REQUIRE_SHARED_DATA(path);
    require_outside_view(prt::scene::load_scene(path.string()));
  }
}

TEST_CASE("auto camera: a room whose opening is a window is seen from inside") {
  // The front wall with a hole of 2 × 2 of its 4 × 4 cells: open (the hole subtends about 6% of
  // the centre's sphere), but seen through the hole from outside, most of the view is the
  // wall's back. The eye then stands inside.
  const prt::scene::Scene window = [] {
    Scene wall = prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}, 4, 4, glm::vec3(0.6f),
                                       "window_wall");
    std::vector<glm::uvec3> kept;
    for (const glm::uvec3& t : wall.triangles) {
      const glm::vec3 c = (wall.positions[t.x] + wall.positions[t.y] + wall.positions[t.z]) / 3.f;
      if (!(c.x > 0.25f && c.x < 0.75f && c.y > 0.25f && c.y < 0.75f)) kept.push_back(t);
    }
    wall.triangles = kept;
    wall.primitives[0].triangle_count = static_cast<uint32_t>(kept.size());
    return wall;
  }();
  Scene room = make_room(kFront);
  prt::scene::append_scene(room, window);
  const prt::scene::RayCaster caster(room);
  const auto chosen = prt::relight::choose_auto_camera(room, caster, kAspect);
  INFO(chosen.note);
  REQUIRE(chosen.inside);
  CHECK(chosen.probe.open_fraction > prt::relight::kOpenThreshold);
  CHECK(inside_bounds(room, chosen.camera.eye));
  CHECK(look(caster, chosen.camera).front > 0.95);
}

TEST_CASE("auto camera: the Cornell box is looked into through its open side") {
  const auto path = prt::test::shared_data("meshes/cornell_box.obj");
  PRT_REQUIRE_SHARED_DATA(path);
  const Scene cornell = prt::scene::load_scene(path.string());
  require_inside_view(cornell, false);
  // Its front wall (z = 0) is commented out in the file: the camera looks toward +Z.
  const prt::scene::RayCaster caster(cornell);
  const auto chosen = prt::relight::choose_auto_camera(cornell, caster, kAspect);
  CHECK(glm::normalize(chosen.camera.target - chosen.camera.eye).z > 0.99f);
}

TEST_CASE("resolve_camera: a scene camera or an explicit one wins over the room test") {
  Scene room = make_room(kFront);
  const prt::scene::RayCaster caster(room);
  std::string note;
  const Camera given =
      prt::relight::resolve_camera("5,5,5,0,0,0,0,1,0,40", room, caster, kAspect, &note);
  CHECK(given.eye == glm::vec3(5.f));
  CHECK_THAT(note, Catch::EndsWith("options (--camera)"));
  prt::scene::SceneCamera own;
  own.name = "own";
  own.eye = {0.5f, 0.5f, -2.f};
  own.target = {0.5f, 0.5f, 0.5f};
  room.cameras.push_back(own);
  const Camera first = prt::relight::resolve_camera("auto", room, caster, kAspect, &note);
  CHECK(first.eye == own.eye);
  CHECK(note.find("scene camera 'own'") != std::string::npos);
}

TEST_CASE("the camera rule: radiosity, a subdivided scene and relight get the same camera") {
  // prt radiosity draws its patch scene (subdivided), prt relight the scene or a .prte's mesh
  // (the same patches): the automatic camera must not depend on the tessellation, and the
  // radiosity image must take it (before, it framed the bounds from outside, where a room
  // shows the backs of its walls).
  const Scene room = make_room(kFront);
  const Scene patches = prt::scene::subdivide_to_edge_length(room, 0.1);
  REQUIRE(patches.triangles.size() > 4 * room.triangles.size());
  const prt::scene::RayCaster caster(room), patch_caster(patches);
  const auto a = prt::relight::choose_camera("auto", room, caster, kAspect);
  const auto b = prt::relight::choose_camera("auto", patches, patch_caster, kAspect);
  CHECK(a.camera.eye == b.camera.eye);
  CHECK(a.camera.target == b.camera.target);
  CHECK(a.camera.yfov_radians == b.camera.yfov_radians);
  prt::relight::RadiosityRenderRequest request;
  request.render.width = 160;
  request.render.height = 90;  // kAspect
  const auto drawn = prt::relight::radiosity_camera(request, patches);
  CHECK(drawn.camera.eye == b.camera.eye);
  CHECK(drawn.origin == b.origin);
  CHECK(look(patch_caster, drawn.camera).front > 0.95);
}

TEST_CASE("the camera rule says where the camera came from, in one line") {
  Scene room = make_room(kFront);
  const prt::scene::RayCaster caster(room);
  const auto automatic = prt::relight::choose_camera("auto", room, caster, kAspect);
  const std::string line = prt::relight::describe_camera(automatic);
  CHECK(line.find('\n') == std::string::npos);
  CHECK_THAT(line, Catch::StartsWith("camera: eye (0.5, 0.5, -1.442), target (0.5, 0.5, 0.5), "
                                     "vertical fov 40.0°; automatic"));
  const auto given = prt::relight::choose_camera("5,5,5,0,0,0,0,1,0,40", room, caster, kAspect);
  CHECK_THAT(prt::relight::describe_camera(given),
             Catch::EndsWith("vertical fov 40.0°; options (--camera)"));
  prt::scene::SceneCamera own;
  own.name = "own";
  own.eye = {0.5f, 0.5f, -2.f};
  own.target = {0.5f, 0.5f, 0.5f};
  room.cameras.push_back(own);
  CHECK_THAT(prt::relight::describe_camera(prt::relight::choose_camera("", room, caster, kAspect)),
             Catch::EndsWith("; scene camera 'own' (its first)"));
  CHECK_THAT(prt::relight::describe_camera(prt::relight::choose_camera("own", room, caster, 1.f)),
             Catch::EndsWith("; scene camera 'own'"));
}
