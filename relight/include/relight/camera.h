// relight/camera.h — a pinhole camera for the preview renderer: framing, parsing, primary rays.
//
// Frame: glTF's (right-handed, +Y up, a camera looks down its −Z toward `target`); units are the
// scene's. yfov is the full vertical field of view in radians; the horizontal one follows from the
// image aspect ratio (width / height), as in glTF's perspective camera.
// Normalised device coordinates (NDC): x to the right and y up, both in [−1, 1] across the image;
// pixel (col, row) with row 0 at the top covers ndc_x ∈ [2col/W − 1, 2(col+1)/W − 1] and
// ndc_y ∈ [1 − 2(row+1)/H, 1 − 2row/H].
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "scene/scene.h"

namespace prt::relight {

struct Camera {
  glm::vec3 eye{0.f, 0.f, 1.f};
  glm::vec3 target{0.f};
  glm::vec3 up{0.f, 1.f, 0.f};
  float yfov_radians = 0.8f;
};

// An orthonormal camera basis: right × up_ortho = −forward (right-handed, looking down −Z).
struct CameraBasis {
  glm::vec3 right, up, forward;  // unit; forward points from eye toward target
  float tan_half_yfov;
  float aspect;  // width / height
};

// A pleasant three-quarter view from above (azimuth 35° off +Z toward +X, elevation 25°, 40°
// vertical field of view) that keeps the whole bounding sphere of [min, max] inside the view at
// the given aspect ratio (with a 5% margin). An empty or point-like box gets radius 1.
Camera frame_bounds(glm::vec3 min, glm::vec3 max, float aspect);

Camera from_scene_camera(const scene::SceneCamera& camera);

// Parses `NAME | ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg` (`auto` is the camera rule's own,
// choose_camera() in relight/auto_camera.h, which every command goes through):
//   NAME: the scene camera with that name;
//   ten numbers: eye, target, up and the vertical field of view in degrees (0 < fov < 180).
// Throws std::runtime_error with a one-line message for an unknown name, a malformed list, or a
// degenerate camera (eye = target, up parallel to the view direction, non-finite values), and
// std::invalid_argument for `auto` or an empty spec.
Camera parse_camera(const std::string& spec, const scene::Scene& scene, float aspect);

// Throws std::runtime_error (one line) when the camera cannot form a basis.
CameraBasis make_camera_basis(const Camera& camera, float aspect);

// Unit direction of the primary ray through the NDC point (ndc_x, ndc_y).
glm::vec3 ray_direction(const CameraBasis& basis, float ndc_x, float ndc_y);

// Projects a world point; false when it is not in front of the camera. ndc is in [−1, 1]² when
// the point is inside the view.
bool project_to_ndc(const CameraBasis& basis, const glm::vec3& eye, const glm::vec3& point,
                    glm::vec2* ndc);

}  // namespace prt::relight
