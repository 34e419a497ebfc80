#include "relight/camera.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "sh/constants.h"

namespace prt::relight {
namespace {

using sh::kPiFloat;

float radians(float degrees) {
  return degrees * kPiFloat / 180.f;
}

bool is_finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

std::vector<std::string> split_commas(const std::string& text) {
  std::vector<std::string> parts;
  std::string part;
  std::istringstream stream(text);
  while (std::getline(stream, part, ',')) parts.push_back(part);
  if (!text.empty() && text.back() == ',') parts.push_back("");
  return parts;
}

bool parse_float(const std::string& text, float* value) {
  if (text.empty()) return false;
  char* end = nullptr;
  const double parsed = std::strtod(text.c_str(), &end);
  while (end && (*end == ' ' || *end == '\t')) ++end;
  if (end == text.c_str() || *end != '\0' || !std::isfinite(parsed)) return false;
  *value = static_cast<float>(parsed);
  return true;
}

}  // namespace

Camera frame_bounds(glm::vec3 min, glm::vec3 max, float aspect) {
  if (!(aspect > 0.f) || !std::isfinite(aspect)) aspect = 1.f;
  glm::vec3 center(0.f);
  float radius = 1.f;
  if (is_finite(min) && is_finite(max) && min.x <= max.x && min.y <= max.y && min.z <= max.z) {
    center = 0.5f * (min + max);
    const float half_diagonal = 0.5f * glm::length(max - min);
    if (half_diagonal > 0.f) radius = half_diagonal;
  }
  const float azimuth = radians(35.f), elevation = radians(25.f);
  const glm::vec3 toward_eye(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                             std::cos(elevation) * std::cos(azimuth));
  Camera camera;
  camera.yfov_radians = radians(40.f);
  const float half_v = 0.5f * camera.yfov_radians;
  const float half_h = std::atan(aspect * std::tan(half_v));
  const float half_min = std::min(half_v, half_h);
  // The sphere of radius r at distance d fills a cone of half-angle asin(r / d).
  const float distance = 1.05f * radius / std::sin(half_min);
  camera.eye = center + distance * toward_eye;
  camera.target = center;
  camera.up = glm::vec3(0.f, 1.f, 0.f);
  return camera;
}

Camera from_scene_camera(const scene::SceneCamera& camera) {
  Camera out;
  out.eye = camera.eye;
  out.target = camera.target;
  out.up = camera.up;
  out.yfov_radians = camera.yfov_radians;
  return out;
}

CameraBasis make_camera_basis(const Camera& camera, float aspect) {
  if (!is_finite(camera.eye) || !is_finite(camera.target) || !is_finite(camera.up))
    throw std::runtime_error("camera: non-finite eye, target or up");
  if (!(camera.yfov_radians > 0.f && camera.yfov_radians < kPiFloat))
    throw std::runtime_error("camera: the vertical field of view must be in (0, 180) degrees");
  if (!(aspect > 0.f) || !std::isfinite(aspect))
    throw std::runtime_error("camera: the image aspect ratio must be positive");
  const glm::vec3 view = camera.target - camera.eye;
  const float view_length = glm::length(view);
  if (!(view_length > 0.f)) throw std::runtime_error("camera: eye and target coincide");
  CameraBasis basis;
  basis.forward = view / view_length;
  const glm::vec3 right = glm::cross(basis.forward, camera.up);
  const float right_length = glm::length(right);
  if (!(right_length > 1e-6f * glm::length(camera.up)))
    throw std::runtime_error("camera: the up vector is parallel to the view direction");
  basis.right = right / right_length;
  basis.up = glm::cross(basis.right, basis.forward);
  basis.tan_half_yfov = std::tan(0.5f * camera.yfov_radians);
  basis.aspect = aspect;
  return basis;
}

glm::vec3 ray_direction(const CameraBasis& basis, float ndc_x, float ndc_y) {
  const float sx = ndc_x * basis.tan_half_yfov * basis.aspect;
  const float sy = ndc_y * basis.tan_half_yfov;
  return glm::normalize(basis.forward + sx * basis.right + sy * basis.up);
}

bool project_to_ndc(const CameraBasis& basis, const glm::vec3& eye, const glm::vec3& point,
                    glm::vec2* ndc) {
  const glm::vec3 d = point - eye;
  const float depth = glm::dot(d, basis.forward);
  if (!(depth > 0.f)) return false;
  ndc->x = glm::dot(d, basis.right) / (depth * basis.tan_half_yfov * basis.aspect);
  ndc->y = glm::dot(d, basis.up) / (depth * basis.tan_half_yfov);
  return true;
}

Camera parse_camera(const std::string& spec, const scene::Scene& scene, float aspect) {
  if (spec.empty() || spec == "auto")
    throw std::invalid_argument("parse_camera: 'auto' is resolved by choose_camera");
  if (spec.find(',') != std::string::npos) {
    const std::vector<std::string> parts = split_commas(spec);
    if (parts.size() != 10)
      throw std::runtime_error("--camera " + spec +
                               ": expected 10 numbers ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg, got " +
                               std::to_string(parts.size()));
    float v[10];
    for (int i = 0; i < 10; ++i)
      if (!parse_float(parts[i], &v[i]))
        throw std::runtime_error("--camera " + spec + ": '" + parts[i] + "' is not a number");
    Camera camera;
    camera.eye = glm::vec3(v[0], v[1], v[2]);
    camera.target = glm::vec3(v[3], v[4], v[5]);
    camera.up = glm::vec3(v[6], v[7], v[8]);
    camera.yfov_radians = radians(v[9]);
    try {
      make_camera_basis(camera, aspect);
    } catch (const std::runtime_error& e) {
      throw std::runtime_error("--camera " + spec + ": " + (e.what() + 8));  // drop "camera: "
    }
    return camera;
  }
  for (const scene::SceneCamera& camera : scene.cameras)
    if (camera.name == spec) return from_scene_camera(camera);
  std::string available;
  for (const scene::SceneCamera& camera : scene.cameras)
    available += (available.empty() ? "" : ", ") + ("'" + camera.name + "'");
  const std::string where = scene.source_path.empty() ? "--camera" : scene.source_path;
  throw std::runtime_error(where + ": no camera named '" + spec +
                           "' (cameras: " + (available.empty() ? "none" : available) +
                           "; use auto or ex,ey,ez,tx,ty,tz,ux,uy,uz,fov_deg)");
}

}  // namespace prt::relight
