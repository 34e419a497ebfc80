// The BVH build's small-pages scope (scene/src/small_pages_scope.h): inside it the process takes
// no transparent huge pages; after it, and after a RayCaster is built, the setting is what it
// was, so that the compact gather's huge-page arrays (bake/src/huge_pages.h) keep their 2 MB
// pages. Linux only (elsewhere the scope is a no-op and nothing is checked).
#include <catch2/catch.hpp>

#include "../../scene/src/small_pages_scope.h"
#include "scene/procedural_mesh.h"
#include "scene/ray_caster.h"

#if defined(__linux__) && defined(PR_GET_THP_DISABLE)

namespace {
int thp_disabled() {
  return prctl(PR_GET_THP_DISABLE, 0, 0, 0, 0);
}
}  // namespace

TEST_CASE("small pages scope: huge pages off inside, the previous setting restored after",
          "[scene][ray_caster]") {
  const int before = thp_disabled();
  REQUIRE(before >= 0);
  {
    const prt::scene::detail::SmallPagesScope scope;
    CHECK(thp_disabled() == 1);
  }
  CHECK(thp_disabled() == before);
  {  // a process that had them off already keeps them off
    REQUIRE(prctl(PR_SET_THP_DISABLE, 1, 0, 0, 0) == 0);
    { const prt::scene::detail::SmallPagesScope scope; }
    CHECK(thp_disabled() == 1);
    REQUIRE(prctl(PR_SET_THP_DISABLE, before, 0, 0, 0) == 0);
  }
  const prt::scene::Scene sphere =
      prt::scene::make_uv_sphere(glm::vec3(0.f), 1.f, 16, 32, false, glm::vec3(0.5f));
  const prt::scene::RayCaster caster(sphere);
  CHECK(caster.triangle_count() > 0);
  CHECK(thp_disabled() == before);
}

#endif
