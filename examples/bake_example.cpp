// A tool that bakes, linking the installed prt::bake (and through it prt::scene) as a separate
// component from the runtime: ambient occlusion of a floor beside a wall, against the closed form
// of the visible fraction ½ + ½·d/√(d² + H²) at distance d from a wall of height H.
// Exits 0 when every probe is within 0.01 (4096 scrambled Sobol' samples: their error is far
// below that), 1 otherwise.
#include <cmath>
#include <cstdio>

#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"

int main() {
  // Floor facing +Y: rows z = −1 (d = 2) and z = 0 (d = 1) of a 20-segment strip; vertex
  // (i, j) at index j·2 + i. Wall z = 1, height 1, 40 wide (its finite length hides < 2e-5).
  prt::scene::Scene scene =
      prt::scene::make_quad({-2.f, 0, -1.f}, {0, 0, 1}, {4, 0, 0}, 1, 20, glm::vec3(0.5f), "floor");
  prt::scene::append_scene(scene, prt::scene::make_quad({-20.f, 0, 1.f}, {40, 0, 0}, {0, 1, 0}, 8,
                                                        1, glm::vec3(0.5f), "wall"));
  prt::bake::BakeOptions options;
  options.order = 1;
  options.samples = 4096;
  options.ao = true;
  const prt::bake::BakeResult baked = prt::bake::bake_transfer(scene, options);
  int failures = 0;
  for (int row = 0; row < 2; ++row) {
    const double d = row == 1 ? 1.0 : 2.0, visible = 0.5 + 0.5 * d / std::sqrt(d * d + 1.0);
    for (int j = 5; j <= 15; ++j) {
      const double ao = baked.data.ao[static_cast<std::size_t>(j * 2 + row)];
      if (std::fabs(ao - visible) > 0.01) {
        std::printf("d = %g, vertex %d: AO %.4f, closed form %.4f\n", d, j * 2 + row, ao, visible);
        ++failures;
      }
    }
  }
  std::printf("bake_example: %s\n", failures == 0 ? "AO matches the closed form" : "FAILED");
  return failures == 0 ? 0 : 1;
}
