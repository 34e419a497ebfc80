// scale_scene: writes a level-sized diffuse benchmark scene as binary glTF — a subdivided ground
// plane (grey, albedo 0.6) with a row of coloured spheres and boxes standing on it — with about
// the requested number of vertices (the ground takes ~80% of them, the objects the rest).
//
//   scale_scene VERTICES OUT.glb
//
// Deterministic: the same arguments give the same file. The ground is 40 × 40 units; the
// objects (radius 1.5 spheres, 3-unit boxes) sit on it along a 5 × 2 layout, so rays from
// the ground hit the objects and rays from the objects hit the ground and each other.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"

namespace {

using prt::scene::Scene;

Scene make_scale_scene(double vertices) {
  const int ground_segments = std::max(8, static_cast<int>(std::sqrt(0.8 * vertices)) - 1);
  Scene scene = prt::scene::make_quad({-20.f, 0.f, 20.f}, {40.f, 0.f, 0.f}, {0.f, 0.f, -40.f},
                                      ground_segments, ground_segments, glm::vec3(0.6f), "ground");
  // Ten objects share the remaining 20%: a sphere has ~2·rings² vertices (segments = 2·rings),
  // a box 6·(s+1)².
  const double per_object = std::max(100.0, 0.2 * vertices / 10.0);
  const int rings = std::max(4, static_cast<int>(std::sqrt(per_object / 2.0)));
  const int box_segments = std::max(2, static_cast<int>(std::sqrt(per_object / 6.0)) - 1);
  const glm::vec3 colours[5] = {{0.8f, 0.2f, 0.2f},
                                {0.2f, 0.7f, 0.2f},
                                {0.2f, 0.3f, 0.8f},
                                {0.8f, 0.8f, 0.3f},
                                {0.7f, 0.7f, 0.7f}};
  for (int i = 0; i < 5; ++i) {
    const float x = -12.f + 6.f * static_cast<float>(i);
    const Scene sphere = prt::scene::make_uv_sphere({x, 1.5f, -4.f}, 1.5f, rings, 2 * rings, false,
                                                    colours[i], "sphere" + std::to_string(i));
    prt::scene::append_scene(scene, sphere);
    const Scene box =
        prt::scene::make_box({x - 1.5f, 0.f, 2.5f}, {x + 1.5f, 3.f, 5.5f}, box_segments, false,
                             colours[4 - i], "box" + std::to_string(i));
    prt::scene::append_scene(scene, box);
  }
  return scene;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: scale_scene VERTICES OUT.glb\n");
    return 2;
  }
  const double vertices = std::atof(argv[1]);
  if (!(vertices >= 1000 && vertices <= 1e8)) {
    std::fprintf(stderr, "scale_scene: VERTICES must be in [1000, 1e8], not '%s'\n", argv[1]);
    return 2;
  }
  try {
    const Scene scene = make_scale_scene(vertices);
    prt::scene::write_glb(argv[2], scene);
    std::printf("%s: %zu vertices, %zu triangles\n", argv[2], scene.positions.size(),
                scene.triangles.size());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 1;
  }
  return 0;
}
