// relight/auto_camera.h — the camera `--camera auto` picks when the scene has none: outside the
// bounds for an object, inside for a room.
//
// The outside camera is frame_bounds() (relight/camera.h). It suits an object, but a room — walls
// whose front faces look inward, like the Cornell box — seen from outside shows only the backs of
// its walls. probe_room() asks two questions with rays (closest hits, front faces as in
// scene/ray_caster.h):
//   1. enclosed: of kCentreRays directions (a spherical Fibonacci lattice) from the centre of the
//      bounding box, the fraction whose first hit is a front face;
//   2. seen from behind: of a kOutsideRaysX × kOutsideRaysY grid of primary rays of the outside
//      camera, the fraction of the hits that are back faces.
// The scene is a room when both fractions are at least kRoomThreshold (an object has its centre
// inside it or seen from outside on front faces; a ground plane seen from the outside camera,
// which looks down, shows its front). A room gets a camera inside:
//   * open (at least kOpenThreshold of the centre's rays escape): the eye stands on the line from
//     the centre toward the mean escaping direction, 95% of the way to the nearer of the first
//     hit and the bounding box, and looks back through the centre (into the room, away from the
//     open side);
//   * closed: the eye stands 80% of the way from the centre to the wall behind it, looking along
//     the horizontal direction of the longest free span through the centre (the largest
//     interior extent).
// Up is +Y unless the view is within 25° of vertical (then −Z for a view down, +Z for a view up).
// The vertical field of view fits the bounding box's cross-section at 80% of the way to where
// the view axis leaves the box (near the far wall of a room; 5% margin), clamped to
// [40°, 100°], so the walls beside the view show too.
// Conventions: glTF frame (+Y up), the scene's units; camera conventions of relight/camera.h.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "relight/camera.h"
#include "scene/ray_caster.h"
#include "scene/scene.h"

namespace prt::relight {

constexpr int kCentreRays = 1024;
constexpr int kOutsideRaysX = 64, kOutsideRaysY = 36;
constexpr double kRoomThreshold = 0.5;
constexpr double kOpenThreshold = 0.02;

struct RoomProbe {
  double enclosed_fraction = 0;      // centre rays whose first hit is a front face
  double open_fraction = 0;          // centre rays that hit nothing
  double outside_back_fraction = 0;  // outside camera's hits that are back faces
  glm::vec3 open_direction{0.f};     // unit mean of the escaping directions (zero when closed)
  bool is_room = false;
};

// The two fractions above for `scene` (whose bounds are non-empty), at the image aspect ratio.
RoomProbe probe_room(const scene::Scene& scene, const scene::RayCaster& caster, float aspect);

struct AutoCamera {
  Camera camera;
  bool inside = false;  // true: a room, camera inside
  RoomProbe probe;
  std::string note;  // one line for the user: which camera and why
};

// The automatic camera for a scene without cameras (see above).
AutoCamera choose_auto_camera(const scene::Scene& scene, const scene::RayCaster& caster,
                              float aspect);

// `--camera SPEC` with the room test: "auto" (or empty) on a scene without cameras gives
// choose_auto_camera(); everything else is parse_camera(). `note` (optional) receives a line
// saying which camera was used.
Camera resolve_camera(const std::string& spec, const scene::Scene& scene,
                      const scene::RayCaster& caster, float aspect, std::string* note = nullptr);

}  // namespace prt::relight
