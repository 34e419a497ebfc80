// relight/auto_camera.h — THE camera rule: every command that renders (prt relight of SH, Haar,
// glossy and emitter-response files, its turntables, prt radiosity, prt demo, prt report's
// images) resolves its camera with choose_camera(), and prints describe_camera()'s line.
//
// choose_camera(SPEC):
//   * ten numbers ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg: that camera ("options");
//   * NAME: the scene camera of that name ("scene camera NAME");
//   * auto (or empty): the scene's first camera if it has one, else the automatic camera below
//     ("automatic"). The automatic camera depends on the geometry only (positions and winding),
//     so a scene and its subdivision (prt radiosity's patches, a .prte's mesh) get the same one.
//
// The automatic camera. An object is framed from outside: frame_bounds() (relight/camera.h). A
// room — walls whose front faces look inward, like the Cornell box — seen from there shows only
// the backs of its walls, so probe_room() asks two questions with rays (closest hits, front faces
// by winding as in scene/ray_caster.h):
//   1. enclosed: of kCentreRays directions (a spherical Fibonacci lattice) from the centre of the
//      bounding box, the fraction whose first hit is a front face;
//   2. seen from behind: of a kOutsideRaysX × kOutsideRaysY grid of primary rays of the outside
//      camera, the fraction of the hits that are back faces.
// The scene is a room when both fractions are at least kRoomThreshold (an object has its centre
// inside it or seen from outside on front faces; a ground plane seen from the outside camera,
// which looks down, shows its front). A room is viewed so that the camera sees its inside:
//   * open (at least kOpenThreshold of the centre's rays escape): the open side is the mean
//     escaping direction d, snapped to the nearest axis of the box when within 15° of it. The
//     camera looks through the open side along −d, the eye on the line centre + s·d, with a 40°
//     vertical field of view, far enough back that the box's cross-section at the open side
//     fits the view with a 5% margin (the classic Cornell box view: eye outside the opening,
//     only the inside in the picture). When more than kMaxBackFraction of that view's hits are
//     back faces (the opening is a window in a wall), the eye stands inside instead, on the same
//     line 95% of the way to the nearer of the first hit and the bounding box, with the field of
//     view of the closed case;
//   * closed: the eye stands 80% of the way from the centre to the wall behind it, looking along
//     the horizontal direction of the longest free span through the centre (the largest
//     interior extent); the vertical field of view fits the bounding box's cross-section at 80%
//     of the way to where the view axis leaves the box (5% margin), clamped to [40°, 100°].
// Up is +Y unless the view is within 25° of vertical (then −Z for a view down, +Z for a view up).
//
// Back faces. Every renderer of relight/renderer.h shows the back of a one-sided surface black
// (see there), so a camera that sees backs shows black walls, never the front's light.
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
constexpr double kMaxBackFraction = 0.1;

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
  bool inside = false;  // true: a room (seen from inside or through its open side)
  RoomProbe probe;
  std::string note;  // one line for the user: which camera and why
};

// The automatic camera for a scene without cameras (see above).
AutoCamera choose_auto_camera(const scene::Scene& scene, const scene::RayCaster& caster,
                              float aspect);

// Where a camera came from, and the camera.
struct CameraChoice {
  Camera camera;
  std::string origin;  // "automatic, …", "scene camera NAME" or "options"
};

// The camera rule (see above) for `spec` at the image's aspect ratio. Throws std::runtime_error
// (one line) for an unknown name, a malformed list or a degenerate camera.
CameraChoice choose_camera(const std::string& spec, const scene::Scene& scene,
                           const scene::RayCaster& caster, float aspect);

// One line for the user: "camera: eye (x, y, z), target (x, y, z), vertical fov F°; ORIGIN".
std::string describe_camera(const CameraChoice& choice);

// choose_camera(); `note` (optional) receives describe_camera()'s line.
Camera resolve_camera(const std::string& spec, const scene::Scene& scene,
                      const scene::RayCaster& caster, float aspect, std::string* note = nullptr);

}  // namespace prt::relight
