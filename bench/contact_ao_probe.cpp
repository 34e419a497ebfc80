// contact_ao_probe — AO of floor points beside a unit sphere resting on a ground of any size,
// against the closed form 1 − (R/L)³: the figures of docs/RAY_OFFSETS.md.
//
// Usage: contact_ao_probe [ground_extent=1000] [samples=4096] [shift=0]
// The ground is a 4 × 4 patch at 0.25 spacing around the contact point (its vertices are the
// probes) lying 1e-3 above a coarse ground `ground_extent` across; the whole scene is moved by
// (shift, 0, shift).
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "bake/transfer_baker.h"
#include "scene/procedural_mesh.h"

using namespace prt::bake;
using namespace prt::scene;

int main(int argc, char** argv) {
  const float extent = argc > 1 ? static_cast<float>(std::atof(argv[1])) : 1000.f;
  const int samples = argc > 2 ? std::atoi(argv[2]) : 4096;
  const float shift = argc > 3 ? static_cast<float>(std::atof(argv[3])) : 0.f;
  Scene s = make_quad({-2.f, 0, -2.f}, {0, 0, 4}, {4, 0, 0}, 16, 16, glm::vec3(0.5f), "patch");
  const float h = extent / 2;
  append_scene(s, make_quad({-h, -1e-3f, -h}, {0, 0, 2 * h}, {2 * h, 0, 0}, 4, 4, glm::vec3(0.5f),
                            "ground"));
  append_scene(s, make_uv_sphere({0, 1, 0}, 1.f, 48, 96, false, glm::vec3(0.5f), "sphere"));
  for (glm::vec3& p : s.positions) p += glm::vec3(shift, 0, shift);
  BakeOptions o;
  o.order = 1;
  o.samples = samples;
  o.ao = true;
  const BakeResult r = bake_transfer(s, o);
  // Patch vertex (i, j) sits at index j·17 + i, z = −2 + 0.25 i, x = −2 + 0.25 j; the contact
  // point is (8, 8).
  for (const int k : {1, 2, 4, 8}) {
    const double D = 0.25 * k, L = std::sqrt(D * D + 1), closed = 1 - std::pow(1 / L, 3);
    const float ao = r.data.ao[8 * 17 + 8 + static_cast<std::size_t>(k)];
    std::printf("ground %g across, shift %g, %d samples: D %.2f AO %.4f closed form %.4f (%+.4f)\n",
                extent, shift, samples, D, ao, closed, ao - closed);
  }
  return 0;
}
