// scene/src/ray_caster.cpp — Embree 3 device, scene and queries (see ray_caster.h).
#include "scene/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include <embree3/rtcore.h>

#include "scene/scene_label.h"
#include "small_pages_scope.h"

namespace prt::scene {
namespace {

constexpr unsigned kMaskAll = 0xFFFFFFFFu;

std::string describe(RTCError e) {
  switch (e) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

void throw_if_error(RTCDevice device, const Scene& scene, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE)
    throw std::runtime_error(scene_label(scene) + ": Embree " + what + " failed (" + describe(e) +
                             ")");
}

void fill_ray16(RTCRay16& r, const glm::vec3& origin, const glm::vec3* dirs, int count, float tfar,
                int* valid) {
  for (int i = 0; i < 16; ++i) {
    const bool on = i < count;
    valid[i] = on ? -1 : 0;
    const glm::vec3 d = on ? dirs[i] : glm::vec3(0.f, 0.f, 1.f);
    r.org_x[i] = origin.x;
    r.org_y[i] = origin.y;
    r.org_z[i] = origin.z;
    r.dir_x[i] = d.x;
    r.dir_y[i] = d.y;
    r.dir_z[i] = d.z;
    r.tnear[i] = 0.f;
    r.tfar[i] = tfar;
    r.time[i] = 0.f;
    r.mask[i] = kMaskAll;
    r.id[i] = static_cast<unsigned>(i);
    r.flags[i] = 0;
  }
}

}  // namespace

bool RayCaster::monitor_memory(void* self, long bytes, bool /*post*/) {
  auto* caster = static_cast<RayCaster*>(self);
  const long long now = caster->bytes_now_.fetch_add(bytes) + bytes;
  long long peak = caster->bytes_peak_.load();
  while (now > peak && !caster->bytes_peak_.compare_exchange_weak(peak, now)) {
  }
  return true;
}

namespace {

// The tangential nudge of vertex v (see vertex_origin): toward the mean centroid of its
// triangles, by min(ε_v, half the way).
glm::vec3 inward_nudge(const glm::vec3& position, const glm::vec3& normal,
                       const glm::dvec3& centroid_sum, uint32_t count, float offset) {
  if (count == 0) return glm::vec3(0.f);
  const glm::dvec3 p(position);
  const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
  glm::dvec3 to = centroid_sum / static_cast<double>(count) - p;
  to -= n * glm::dot(n, to);
  const double len = glm::length(to);
  if (!(len > 0.0) || !std::isfinite(len)) return glm::vec3(0.f);
  return glm::vec3(to / len * std::min(static_cast<double>(offset), 0.5 * len));
}

glm::dvec3 centroid(const Scene& scene, const glm::uvec3& t) {
  return (glm::dvec3(scene.positions[t.x]) + glm::dvec3(scene.positions[t.y]) +
          glm::dvec3(scene.positions[t.z])) /
         3.0;
}

void check_indices(const Scene& scene) {
  const std::size_t nv = scene.positions.size();
  // Only triangles whose indices are in range reach Embree (a loader bug must not crash it).
  for (const glm::uvec3& t : scene.triangles)
    if (t.x >= nv || t.y >= nv || t.z >= nv)
      throw std::runtime_error(scene_label(scene) + ": triangle index out of range");
}

}  // namespace

RayCaster::RayCaster(const Scene& scene) : scene_(&scene) {
  check_indices(scene);
  starts_ = compute_vertex_ray_starts(scene);
  for (const float eps : starts_.offset) max_offset_ = std::max(max_offset_, double(eps));
  const std::size_t nv = scene.positions.size();
  if (scene.normals.size() == nv) {
    std::vector<glm::dvec3> centroid_sum(nv, glm::dvec3(0.0));
    std::vector<uint32_t> count(nv, 0);
    for (const glm::uvec3& t : scene.triangles) {
      const glm::dvec3 c = centroid(scene, t);
      for (const uint32_t v : {t.x, t.y, t.z}) {
        centroid_sum[v] += c;
        ++count[v];
      }
    }
    inward_.resize(nv);
    for (std::size_t v = 0; v < nv; ++v)
      inward_[v] = inward_nudge(scene.positions[v], scene.normals[v], centroid_sum[v], count[v],
                                starts_.offset[v]);
  }
  offset_ = starts_.offset.data();
  build_bvh(scene);
}

RayCaster::RayCaster(const Scene& scene, const uint32_t* starts_of, std::size_t count)
    : scene_(&scene) {
  check_indices(scene);
  max_offset_ = max_vertex_ray_offset(scene);
  const std::size_t nv = scene.positions.size();
  constexpr uint32_t kNone = ~0u;
  slot_.assign(nv, kNone);
  for (std::size_t i = 0; i < count; ++i)
    if (starts_of[i] < nv) slot_[starts_of[i]] = static_cast<uint32_t>(i);
  // As compute_vertex_ray_starts and the nudges above, for the listed vertices only: the same
  // sums in the same (triangle) order, so the same bits.
  std::vector<double> edge(count, 0.0);
  std::vector<glm::dvec3> centroid_sum(count, glm::dvec3(0.0));
  std::vector<uint32_t> triangles(count, 0);
  for (const glm::uvec3& t : scene.triangles) {
    const uint32_t sx = slot_[t.x], sy = slot_[t.y], sz = slot_[t.z];
    if (sx == kNone && sy == kNone && sz == kNone) continue;
    const glm::dvec3 a(scene.positions[t.x]), b(scene.positions[t.y]), c(scene.positions[t.z]);
    const double L = longest_edge(a, b, c);
    const glm::dvec3 mid = centroid(scene, t);
    for (const uint32_t s : {sx, sy, sz}) {
      if (s == kNone) continue;
      edge[s] = std::max(edge[s], L);
      centroid_sum[s] += mid;
      ++triangles[s];
    }
  }
  own_offset_.resize(count);
  offset_ = own_offset_.data();
  const bool nudge = scene.normals.size() == nv;
  if (nudge) inward_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    const uint32_t v = starts_of[i];
    own_offset_[i] = offset_as_float(ray_offset(glm::dvec3(scene.positions[v]), edge[i]));
    if (nudge)
      inward_[i] = inward_nudge(scene.positions[v], scene.normals[v], centroid_sum[i], triangles[i],
                                own_offset_[i]);
  }
  build_bvh(scene);
}

void RayCaster::build_bvh(const Scene& scene) {
  RTCDevice device = rtcNewDevice(nullptr);
  if (!device)
    throw std::runtime_error(scene_label(scene) + ": cannot create the Embree device (" +
                             describe(rtcGetDeviceError(nullptr)) + ")");
  device_ = device;
  rtcSetDeviceMemoryMonitorFunction(device, &RayCaster::monitor_memory, this);

  RTCScene rs = rtcNewScene(device);
  rtc_scene_ = rs;
  throw_if_error(device, scene, "scene creation");
  rtcSetSceneFlags(rs, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(rs, RTC_BUILD_QUALITY_HIGH);

  const std::size_t nv = scene.positions.size();
  triangle_count_ = scene.triangles.size();
  if (triangle_count_ > 0) {
    RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vb = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    auto* ib = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), triangle_count_));
    if (!vb || !ib) {
      rtcReleaseGeometry(geom);
      throw_if_error(device, scene, "buffer allocation");
      throw std::runtime_error(scene_label(scene) + ": Embree buffer allocation failed");
    }
    for (std::size_t i = 0; i < nv; ++i) {
      vb[3 * i + 0] = scene.positions[i].x;
      vb[3 * i + 1] = scene.positions[i].y;
      vb[3 * i + 2] = scene.positions[i].z;
    }
    std::memcpy(ib, scene.triangles.data(), triangle_count_ * sizeof(glm::uvec3));
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(rs, geom, 0);
    rtcReleaseGeometry(geom);
  }
  {
    const detail::SmallPagesScope small_pages;  // the build on 4 KB pages (small_pages_scope.h)
    rtcCommitScene(rs);
  }
  try {
    throw_if_error(device, scene, "BVH build");
  } catch (...) {
    rtcReleaseScene(rs);
    rtcReleaseDevice(device);
    throw;
  }
}

RayCaster::~RayCaster() {
  if (rtc_scene_) rtcReleaseScene(static_cast<RTCScene>(rtc_scene_));
  if (device_) rtcReleaseDevice(static_cast<RTCDevice>(device_));
}

bool RayCaster::front_facing(uint32_t triangle, const glm::vec3& d) const {
  const glm::uvec3 t = scene_->triangles[triangle];
  const glm::vec3 p0 = scene_->positions[t.x];
  const glm::vec3 ng = glm::cross(scene_->positions[t.y] - p0, scene_->positions[t.z] - p0);
  return glm::dot(ng, d) < 0.f;
}

bool RayCaster::occluded(const glm::vec3& o, const glm::vec3& d, float tnear, float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay ray;
  ray.org_x = o.x;
  ray.org_y = o.y;
  ray.org_z = o.z;
  ray.dir_x = d.x;
  ray.dir_y = d.y;
  ray.dir_z = d.z;
  ray.tnear = tnear;
  ray.tfar = tfar;
  ray.time = 0.f;
  ray.mask = kMaskAll;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(static_cast<RTCScene>(rtc_scene_), &ctx, &ray);
  return ray.tfar < 0.f;  // Embree sets tfar = −inf on occlusion
}

void RayCaster::occluded_packet(const glm::vec3& origin, const glm::vec3* dirs, int count,
                                float tfar, bool* out) const {
  count = std::clamp(count, 0, 16);
  if (count == 0) return;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) int valid[16];
  alignas(64) RTCRay16 ray;
  fill_ray16(ray, origin, dirs, count, tfar, valid);
  rtcOccluded16(valid, static_cast<RTCScene>(rtc_scene_), &ctx, &ray);
  for (int i = 0; i < count; ++i) out[i] = ray.tfar[i] < 0.f;
}

RayCaster::Hit RayCaster::intersect(const glm::vec3& o, const glm::vec3& d, float tnear,
                                    float tfar) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  rh.ray.org_x = o.x;
  rh.ray.org_y = o.y;
  rh.ray.org_z = o.z;
  rh.ray.dir_x = d.x;
  rh.ray.dir_y = d.y;
  rh.ray.dir_z = d.z;
  rh.ray.tnear = tnear;
  rh.ray.tfar = tfar;
  rh.ray.time = 0.f;
  rh.ray.mask = kMaskAll;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(static_cast<RTCScene>(rtc_scene_), &ctx, &rh);
  Hit h;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
  h.hit = true;
  h.t = rh.ray.tfar;
  h.triangle = rh.hit.primID;
  h.u = rh.hit.u;
  h.v = rh.hit.v;
  h.front_face = front_facing(h.triangle, d);
  return h;
}

void RayCaster::intersect_packet(const glm::vec3& origin, const glm::vec3* dirs, int count,
                                 float tfar, Hit* out, bool face_side) const {
  count = std::clamp(count, 0, 16);
  if (count == 0) return;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) int valid[16];
  alignas(64) RTCRayHit16 rh;
  fill_ray16(rh.ray, origin, dirs, count, tfar, valid);
  for (int i = 0; i < 16; ++i) {
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, static_cast<RTCScene>(rtc_scene_), &ctx, &rh);
  for (int i = 0; i < count; ++i) {
    Hit h;
    if (rh.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID) {
      h.hit = true;
      h.t = rh.ray.tfar[i];
      h.triangle = rh.hit.primID[i];
      h.u = rh.hit.u[i];
      h.v = rh.hit.v[i];
      if (face_side) h.front_face = front_facing(h.triangle, dirs[i]);
    }
    out[i] = h;
  }
}

void RayCaster::intersect_stream(const glm::vec3* origins, const glm::vec3* dirs, int count,
                                 float tfar, bool coherent, Hit* out) const {
  if (count <= 0) return;
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  ctx.flags =
      coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  thread_local std::vector<RTCRayHit> rays;
  rays.resize(static_cast<std::size_t>(count));
  for (int i = 0; i < count; ++i) {
    RTCRayHit& rh = rays[static_cast<std::size_t>(i)];
    rh.ray.org_x = origins[i].x;
    rh.ray.org_y = origins[i].y;
    rh.ray.org_z = origins[i].z;
    rh.ray.dir_x = dirs[i].x;
    rh.ray.dir_y = dirs[i].y;
    rh.ray.dir_z = dirs[i].z;
    rh.ray.tnear = 0.f;
    rh.ray.tfar = tfar;
    rh.ray.time = 0.f;
    rh.ray.mask = kMaskAll;
    rh.ray.id = static_cast<unsigned>(i);
    rh.ray.flags = 0;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect1M(static_cast<RTCScene>(rtc_scene_), &ctx, rays.data(), static_cast<unsigned>(count),
                 sizeof(RTCRayHit));
  for (int i = 0; i < count; ++i) {
    const RTCRayHit& rh = rays[static_cast<std::size_t>(i)];
    Hit h;
    if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      h.hit = true;
      h.t = rh.ray.tfar;
      h.triangle = rh.hit.primID;
      h.u = rh.hit.u;
      h.v = rh.hit.v;
      h.front_face = front_facing(h.triangle, dirs[i]);
    }
    out[i] = h;
  }
}

}  // namespace prt::scene
