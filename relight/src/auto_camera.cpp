#include "relight/auto_camera.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "sh/constants.h"

namespace prt::relight {
namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

bool finite_bounds(const scene::Scene& scene) {
  if (scene.vertex_count() == 0 || scene.triangles.empty()) return false;
  const glm::vec3 lo = scene.bounds_min(), hi = scene.bounds_max();
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(lo[i]) || !std::isfinite(hi[i]) || !(hi[i] >= lo[i])) return false;
  return glm::length(hi - lo) > 0.f;
}

// Point i of a spherical Fibonacci lattice of n points (unit vectors, near-uniform).
glm::vec3 fibonacci_direction(int i, int n) {
  const double golden = sh::kPi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * i + 1.0) / n;
  const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double phi = golden * i;
  return glm::vec3(static_cast<float>(r * std::cos(phi)), static_cast<float>(z),
                   static_cast<float>(r * std::sin(phi)));
}

// Distance from p (inside the box) along unit d to the boundary of [lo, hi].
float distance_to_box(glm::vec3 p, glm::vec3 d, glm::vec3 lo, glm::vec3 hi) {
  float t = kInfinity;
  for (int i = 0; i < 3; ++i) {
    if (d[i] > 0.f) t = std::min(t, (hi[i] - p[i]) / d[i]);
    if (d[i] < 0.f) t = std::min(t, (lo[i] - p[i]) / d[i]);
  }
  return std::max(0.f, t);
}

// Free distance from p along unit d: the first hit, or the box boundary when nothing is hit.
float free_distance(const scene::RayCaster& caster, glm::vec3 p, glm::vec3 d, glm::vec3 lo,
                    glm::vec3 hi) {
  const scene::RayCaster::Hit hit = caster.intersect(p, d, 0.f, kInfinity);
  return hit.hit ? hit.t : distance_to_box(p, d, lo, hi);
}

// Up for a view along unit `forward`: +Y unless within 25° of vertical.
glm::vec3 up_for(glm::vec3 forward) {
  const float cos_vertical = std::cos(sh::kPiFloat * 25.f / 180.f);
  return std::abs(forward.y) < cos_vertical ? glm::vec3(0, 1, 0)
         : forward.y < 0.f                  ? glm::vec3(0, 0, -1)
                                            : glm::vec3(0, 0, 1);
}

// A camera at `eye` looking along unit `forward`, its field of view fitted to the box's
// cross-section at 80% of the way to where the view leaves the box.
Camera inside_camera(glm::vec3 eye, glm::vec3 forward, glm::vec3 lo, glm::vec3 hi, float aspect) {
  Camera camera;
  camera.eye = eye;
  camera.target = eye + forward;
  camera.up = up_for(forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  const glm::vec3 half = 0.5f * (hi - lo);
  const float half_w = glm::dot(glm::abs(right), half), half_h = glm::dot(glm::abs(up), half);
  const float depth =
      std::max(0.8f * distance_to_box(eye, forward, lo, hi), 1e-6f * glm::length(half));
  const float tan_half = 1.05f * std::max(half_h / depth, half_w / (depth * aspect));
  const float lo_fov = sh::kPiFloat * 40.f / 180.f, hi_fov = sh::kPiFloat * 100.f / 180.f;
  camera.yfov_radians = std::clamp(2.f * std::atan(tan_half), lo_fov, hi_fov);
  return camera;
}

// Closed room: look along the horizontal direction of the longest free span through `centre`,
// from 80% of the way to the wall behind.
Camera closed_room_camera(const scene::RayCaster& caster, glm::vec3 centre, glm::vec3 lo,
                          glm::vec3 hi, float aspect) {
  constexpr int kAzimuths = 16;
  glm::vec3 best_forward(0, 0, -1);
  float best_span = -1.f, best_behind = 0.f;
  for (int a = 0; a < kAzimuths / 2; ++a) {
    const float phi = 2.f * sh::kPiFloat * static_cast<float>(a) / kAzimuths;
    const glm::vec3 d(std::cos(phi), 0.f, std::sin(phi));
    const float ahead = free_distance(caster, centre, d, lo, hi);
    const float behind = free_distance(caster, centre, -d, lo, hi);
    if (ahead + behind > best_span) {
      best_span = ahead + behind;
      best_forward = ahead >= behind ? d : -d;
      best_behind = std::min(ahead, behind);
    }
  }
  return inside_camera(centre - 0.8f * best_behind * best_forward, best_forward, lo, hi, aspect);
}

// The open side: `d` snapped to the nearest box axis when within 15° of it.
glm::vec3 snap_to_axis(glm::vec3 d) {
  int axis = 0;
  for (int i = 1; i < 3; ++i)
    if (std::abs(d[i]) > std::abs(d[axis])) axis = i;
  if (std::abs(d[axis]) < std::cos(sh::kPiFloat * 15.f / 180.f)) return d;
  glm::vec3 snapped(0.f);
  snapped[axis] = d[axis] > 0.f ? 1.f : -1.f;
  return snapped;
}

// Looking in through the open side d (unit, from the centre): 40° vertical field of view, the
// box's cross-section at the open side fitted with a 5% margin.
Camera through_opening_camera(glm::vec3 centre, glm::vec3 d, glm::vec3 lo, glm::vec3 hi,
                              float aspect) {
  Camera camera;
  const glm::vec3 forward = -d;
  camera.up = up_for(forward);
  camera.yfov_radians = sh::kPiFloat * 40.f / 180.f;
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera.up));
  const glm::vec3 up = glm::cross(right, forward);
  const glm::vec3 half = 0.5f * (hi - lo);
  const float half_w = glm::dot(glm::abs(right), half), half_h = glm::dot(glm::abs(up), half);
  const float tan_half = std::tan(0.5f * camera.yfov_radians);
  const float back = 1.05f * std::max(half_h, half_w / aspect) / tan_half;
  camera.eye = centre + (distance_to_box(centre, d, lo, hi) + back) * d;
  camera.target = centre;
  return camera;
}

// The fraction of a camera's hits (a kOutsideRaysX × kOutsideRaysY grid) that are back faces.
double back_fraction(const scene::RayCaster& caster, const Camera& camera, float aspect) {
  const CameraBasis basis = make_camera_basis(camera, aspect);
  int hits = 0, back = 0;
  for (int row = 0; row < kOutsideRaysY; ++row) {
    for (int col = 0; col < kOutsideRaysX; ++col) {
      const float x = 2.f * (static_cast<float>(col) + 0.5f) / kOutsideRaysX - 1.f;
      const float y = 1.f - 2.f * (static_cast<float>(row) + 0.5f) / kOutsideRaysY;
      const scene::RayCaster::Hit hit =
          caster.intersect(camera.eye, ray_direction(basis, x, y), 0.f, kInfinity);
      if (!hit.hit) continue;
      ++hits;
      if (!hit.front_face) ++back;
    }
  }
  return hits > 0 ? double(back) / hits : 0.0;
}

}  // namespace

RoomProbe probe_room(const scene::Scene& scene, const scene::RayCaster& caster, float aspect) {
  RoomProbe probe;
  if (!finite_bounds(scene)) return probe;
  const glm::vec3 lo = scene.bounds_min(), hi = scene.bounds_max();
  const glm::vec3 centre = 0.5f * (lo + hi);
  int front = 0, open = 0;
  glm::dvec3 open_sum(0.0);
  for (int i = 0; i < kCentreRays; ++i) {
    const glm::vec3 d = fibonacci_direction(i, kCentreRays);
    const scene::RayCaster::Hit hit = caster.intersect(centre, d, 0.f, kInfinity);
    if (!hit.hit) {
      ++open;
      open_sum += glm::dvec3(d);
    } else if (hit.front_face) {
      ++front;
    }
  }
  probe.enclosed_fraction = double(front) / kCentreRays;
  probe.open_fraction = double(open) / kCentreRays;
  if (glm::length(open_sum) > 0.0) probe.open_direction = glm::vec3(glm::normalize(open_sum));

  probe.outside_back_fraction = back_fraction(caster, frame_bounds(lo, hi, aspect), aspect);
  probe.is_room =
      probe.enclosed_fraction >= kRoomThreshold && probe.outside_back_fraction >= kRoomThreshold;
  return probe;
}

AutoCamera choose_auto_camera(const scene::Scene& scene, const scene::RayCaster& caster,
                              float aspect) {
  if (!(aspect > 0.f) || !std::isfinite(aspect)) aspect = 1.f;
  AutoCamera out;
  out.probe = probe_room(scene, caster, aspect);
  const glm::vec3 lo = scene.bounds_min(), hi = scene.bounds_max();
  char text[256];
  if (!out.probe.is_room) {
    out.camera = frame_bounds(lo, hi, aspect);
    std::snprintf(text, sizeof text, "automatic, an object seen from outside (its bounds fitted)");
    out.note = text;
    return out;
  }
  out.inside = true;
  const glm::vec3 centre = 0.5f * (lo + hi);
  const bool open = out.probe.open_fraction >= kOpenThreshold;
  const char* where = "looking along the longest span";
  if (open) {
    const glm::vec3 d = snap_to_axis(out.probe.open_direction);
    out.camera = through_opening_camera(centre, d, lo, hi, aspect);
    where = "looking in through its open side";
    if (back_fraction(caster, out.camera, aspect) > kMaxBackFraction) {
      const float reach =
          std::min(distance_to_box(centre, d, lo, hi), free_distance(caster, centre, d, lo, hi));
      out.camera = inside_camera(centre + 0.95f * reach * d, -d, lo, hi, aspect);
      where = "inside, by its open side (seen from outside it shows wall backs)";
    }
  } else {
    out.camera = closed_room_camera(caster, centre, lo, hi, aspect);
  }
  std::snprintf(text, sizeof text,
                "automatic, a room (%.0f%% of the rays from its centre meet inward faces, %.0f%% "
                "of the outside view is wall backs), %s",
                100.0 * out.probe.enclosed_fraction, 100.0 * out.probe.outside_back_fraction,
                where);
  out.note = text;
  return out;
}

CameraChoice choose_camera(const std::string& spec, const scene::Scene& scene,
                           const scene::RayCaster& caster, float aspect) {
  CameraChoice choice;
  if (spec.empty() || spec == "auto") {
    if (!scene.cameras.empty()) {
      choice.camera = from_scene_camera(scene.cameras.front());
      choice.origin = "scene camera '" + scene.cameras.front().name + "' (its first)";
    } else {
      AutoCamera chosen = choose_auto_camera(scene, caster, aspect);
      choice.camera = chosen.camera;
      choice.origin = chosen.note;
    }
  } else {
    choice.camera = parse_camera(spec, scene, aspect);
    choice.origin =
        spec.find(',') != std::string::npos ? "options (--camera)" : "scene camera '" + spec + "'";
  }
  make_camera_basis(choice.camera, aspect);  // throws for a degenerate scene camera
  return choice;
}

std::string describe_camera(const CameraChoice& choice) {
  const Camera& c = choice.camera;
  char text[200];
  std::snprintf(text, sizeof text,
                "camera: eye (%.4g, %.4g, %.4g), target (%.4g, %.4g, %.4g), vertical fov %.1f°; ",
                double(c.eye.x), double(c.eye.y), double(c.eye.z), double(c.target.x),
                double(c.target.y), double(c.target.z), double(c.yfov_radians) * 180.0 / sh::kPi);
  return text + choice.origin;
}

Camera resolve_camera(const std::string& spec, const scene::Scene& scene,
                      const scene::RayCaster& caster, float aspect, std::string* note) {
  const CameraChoice choice = choose_camera(spec, scene, caster, aspect);
  if (note) *note = describe_camera(choice);
  return choice.camera;
}

}  // namespace prt::relight
