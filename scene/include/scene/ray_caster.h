// scene/ray_caster.h — an RAII Embree 3 wrapper over a Scene: occlusion and closest-hit queries,
// single rays, 16-wide packets that share an origin (the baker's access pattern) and streams.
//
// Frame and units: the Scene's (glTF frame, +Y up; the file's units). Directions need not be
// normalised for occlusion, but Hit::t is in units of |d|, so pass unit directions when t matters.
// Barycentrics are Embree's: hit point = (1 − u − v)·p0 + u·p1 + v·p2 for triangle (p0, p1, p2).
// Front faces are counter-clockwise as seen by the ray (glTF's winding): front_face is
// dot((p1 − p0) × (p2 − p0), d) < 0, computed from the scene's own positions.
//
// Self-intersection: rays leaving a scene vertex start at vertex_origin(v), which stands ε_v off
// the surface along the vertex normal (scene/ray_offset.h: ε follows the float rounding of the
// point and of its own triangles, not the scene's size). Vertices on a sharp edge whose faces do
// not share the vertex (box edges) lie in the plane of the neighbouring face, so rays leaving
// them would hit that face at t = 0; vertex_origin() therefore also nudges the point by
// min(ε_v, half the way) toward the mean centroid of its own triangles, in the tangent plane:
// off the neighbouring face's plane, on the correct side. Rays leaving a hit point start at
// surface_origin(), ε of the hit triangle off it. All queries start at tnear ≥ 0.
// Every ray is cast with mask 0xFFFFFFFF. Embree device and build errors throw std::runtime_error
// with a one-line message. Queries are const and thread-safe.
// References: [14] of docs/REFERENCES.md.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "scene/ray_offset.h"
#include "scene/scene.h"

namespace prt::scene {

class RayCaster {
 public:
  // Builds the BVH (high quality, robust mode) over every triangle of `scene`.
  // The scene must outlive the RayCaster (positions are read by intersect()).
  explicit RayCaster(const Scene& scene);
  // The same BVH, with the ray starts of `count` vertices `starts_of[i]` only (a farm shard's
  // rows): vertex_origin(v) is then defined for those vertices alone, bit for bit as the
  // RayCaster above computes it, and vertex_ray_starts() is empty; max_ray_offset() is still
  // the whole scene's.
  RayCaster(const Scene& scene, const uint32_t* starts_of, std::size_t count);
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
  // With face_side = false, Hit::front_face is left false: no read of the hit triangle's
  // positions, for callers that judge the side themselves (the bakers' hit_side.h).
  void intersect_packet(const glm::vec3& origin, const glm::vec3* dirs, int count, float tfar,
                        Hit* out, bool face_side = true) const;

  // rtcIntersect1M: `count` rays with their own origins (tnear = 0) as one stream;
  // out[i] = closest hit of ray i, as intersect(). `coherent` passes Embree's coherent-stream
  // hint (it may then trace them as packets); otherwise the incoherent flag.
  void intersect_stream(const glm::vec3* origins, const glm::vec3* dirs, int count, float tfar,
                        bool coherent, Hit* out) const;

  // ε_v and τ_v of every vertex (scene/ray_offset.h); empty when built for some vertices only.
  const VertexRayStarts& vertex_ray_starts() const { return starts_; }
  // The largest ε_v over every vertex of the scene, as a float (rounded up, as ε_v is stored).
  double max_ray_offset() const { return max_offset_; }

  // Ray origin for scene vertex v: ε_v along its normal, nudged into its own triangles.
  glm::vec3 vertex_origin(uint32_t v) const {
    const uint32_t s = slot_.empty() ? v : slot_[v];
    const glm::vec3 n = glm::normalize(scene_->normals[v]);
    return scene_->positions[v] + offset_[s] * n + (inward_.empty() ? glm::vec3(0.f) : inward_[s]);
  }

  // Ray origin for a point p on `triangle` (a hit point) leaving along the unit normal n of the
  // side the ray continues on: p + ε·n with ε of that triangle (scene/ray_offset.h).
  glm::vec3 surface_origin(uint32_t triangle, const glm::vec3& p, const glm::vec3& n) const {
    return p + static_cast<float>(triangle_ray_offset(*scene_, triangle, glm::dvec3(p))) * n;
  }

  std::size_t triangle_count() const { return triangle_count_; }
  // Bytes Embree holds now and at its peak (BVH, buffers), from its memory monitor.
  std::size_t embree_bytes() const { return static_cast<std::size_t>(bytes_now_.load()); }
  std::size_t embree_peak_bytes() const { return static_cast<std::size_t>(bytes_peak_.load()); }

 private:
  static bool monitor_memory(void* self, long bytes, bool post);
  bool front_facing(uint32_t triangle, const glm::vec3& d) const;
  void build_bvh(const Scene& scene);

  const Scene* scene_;
  void* device_ = nullptr;     // RTCDevice
  void* rtc_scene_ = nullptr;  // RTCScene
  std::size_t triangle_count_ = 0;
  VertexRayStarts starts_;
  double max_offset_ = 0.0;
  std::vector<uint32_t> slot_;     // vertex → its entry below (empty: the vertex itself)
  std::vector<float> own_offset_;  // ε of the listed vertices (else starts_.offset is used)
  const float* offset_ = nullptr;  // ε of each vertex with a ray start
  std::vector<glm::vec3> inward_;  // tangential nudge of each such vertex (see vertex_origin)
  std::atomic<long long> bytes_now_{0};
  std::atomic<long long> bytes_peak_{0};
};

}  // namespace prt::scene
