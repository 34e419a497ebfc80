// bake/ray_caster.h — an RAII Embree 3 wrapper over a Scene: occlusion and closest-hit queries,
// single rays and 16-wide packets that share an origin (the baker's access pattern).
//
// Frame and units: the Scene's (glTF frame, +Y up; the file's units). Directions need not be
// normalised for occlusion, but Hit::t is in units of |d|, so pass unit directions when t matters.
// Barycentrics are Embree's: hit point = (1 − u − v)·p0 + u·p1 + v·p2 for triangle (p0, p1, p2).
// Front faces are counter-clockwise as seen by the ray (glTF's winding): front_face is
// dot((p1 − p0) × (p2 − p0), d) < 0, computed from the scene's own positions.
//
// Self-intersection: offset_origin() moves a surface point along its normal by
//   ε = max(1e-4 · extent, 64 · ulp(max_i |p_i|))
// (extent = bounding-box diagonal), so scenes in millimetres and in kilometres both avoid
// shadow acne; all queries start at tnear ≥ 0 from that offset point.
// Vertices on a sharp edge whose faces do not share the vertex (box edges) lie in the plane of
// the neighbouring face, so rays leaving them would hit that face at t = 0. vertex_origin()
// therefore also nudges the point by min(ε, half the way) toward the mean centroid of its own
// triangles, in the tangent plane: off the neighbouring face's plane, on the correct side.
// Every ray is cast with mask 0xFFFFFFFF. Embree device and build errors throw std::runtime_error
// with a one-line message. Queries are const and thread-safe.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "bake/scene.h"

namespace prt::bake {

// ε of the scene (see above): what offset_origin() moves a point along its normal.
float ray_offset_scale(const Scene& scene);

class RayCaster {
 public:
  // Builds the BVH (high quality, robust mode) over every triangle of `scene`.
  // The scene must outlive the RayCaster (positions are read by intersect()).
  explicit RayCaster(const Scene& scene);
  ~RayCaster();
  RayCaster(const RayCaster&) = delete;
  RayCaster& operator=(const RayCaster&) = delete;

  struct Hit {
    bool hit = false;
    float t = 0.f;           // ray parameter of the hit (distance when |d| = 1)
    uint32_t triangle = 0;   // index into Scene::triangles
    float u = 0.f, v = 0.f;  // Embree barycentrics (see above)
    bool front_face = false;
  };

  // True when anything lies on the open segment o + t·d, t ∈ (tnear, tfar).
  bool occluded(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const;
  // rtcOccluded16 for `count` ≤ 16 rays sharing `origin` (tnear = 0); out[i] = occluded.
  void occluded_packet(const glm::vec3& origin, const glm::vec3* dirs, int count, float tfar,
                       bool* out) const;
  // Closest hit on (tnear, tfar).
  Hit intersect(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const;
  // rtcIntersect16 for `count` ≤ 16 rays sharing `origin` (tnear = 0); out[i] = closest hit.
  void intersect_packet(const glm::vec3& origin, const glm::vec3* dirs, int count, float tfar,
                        Hit* out) const;

  // ε of the header comment, in scene units.
  float offset_scale() const { return offset_scale_; }
  // p + ε·n: the origin of rays leaving a surface point p with unit normal n.
  glm::vec3 offset_origin(const glm::vec3& p, const glm::vec3& n) const {
    return p + offset_scale_ * n;
  }

  // Ray origin for scene vertex v: offset along its normal and nudged into its own triangles.
  glm::vec3 vertex_origin(uint32_t v) const {
    return offset_origin(scene_->positions[v], glm::normalize(scene_->normals[v])) +
           (inward_.empty() ? glm::vec3(0.f) : inward_[v]);
  }

  std::size_t triangle_count() const { return triangle_count_; }
  // Bytes Embree holds now and at its peak (BVH, buffers), from its memory monitor.
  std::size_t embree_bytes() const { return static_cast<std::size_t>(bytes_now_.load()); }
  std::size_t embree_peak_bytes() const { return static_cast<std::size_t>(bytes_peak_.load()); }

 private:
  static bool monitor_memory(void* self, long bytes, bool post);
  bool front_facing(uint32_t triangle, const glm::vec3& d) const;

  const Scene* scene_;
  void* device_ = nullptr;     // RTCDevice
  void* rtc_scene_ = nullptr;  // RTCScene
  std::size_t triangle_count_ = 0;
  float offset_scale_ = 0.f;
  std::vector<glm::vec3> inward_;  // per-vertex tangential nudge (see vertex_origin)
  std::atomic<long long> bytes_now_{0};
  std::atomic<long long> bytes_peak_{0};
};

}  // namespace prt::bake
