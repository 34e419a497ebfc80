// "NAME=VALUE" material assignments (scene/material_assignment.h): where NAME ends, the colour
// values of --emission / --albedo / --emitter and their one-line errors, name matching ('*',
// material before primitive name) and applying emission and albedo.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <catch2/catch.hpp>

#include "scene/material_assignment.h"
#include "scene/procedural_mesh.h"

using prt::scene::AssignedValue;
using prt::scene::MaterialColour;
using prt::scene::parse_material_assignment;
using prt::scene::parse_material_colour;
using prt::scene::Scene;

namespace {

// Three quads: primitives "floor" and "wall" of material "white", "lamp" of material "light".
Scene three_quads() {
  Scene s;
  const std::vector<std::pair<std::string, std::string>> parts = {
      {"floor", "white"}, {"wall", "white"}, {"lamp", "light"}};
  float z = 0.f;
  for (const auto& [name, material] : parts) {
    Scene part = prt::scene::make_quad({0, 0, z}, {1, 0, 0}, {0, 1, 0}, 1, 1, glm::vec3(0.5f));
    part.primitives[0].name = name;
    part.primitives[0].material = material;
    prt::scene::append_scene(s, part);
    z += 1.f;
  }
  s.source_path = "three.obj";
  return s;
}

std::string error_of(const std::string& option, const std::string& text) {
  try {
    parse_material_colour(option, text);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "accepted";
}

}  // namespace

TEST_CASE("colour assignments: NAME=r,g,b or NAME=v, the name up to the last '='",
          "[scene][assignment]") {
  const MaterialColour c = parse_material_colour("--emission", "lamp=1,0.5,0");
  CHECK(c.name == "lamp");
  CHECK(c.rgb == glm::vec3(1.f, 0.5f, 0.f));
  CHECK(c.option == "--emission");
  CHECK(c.text == "lamp=1,0.5,0");
  CHECK(parse_material_colour("--albedo", "white=0.25").rgb == glm::vec3(0.25f));
  // A colour holds no '=', so a material name may: the name ends at the last one.
  CHECK(parse_material_colour("--albedo", "a=b=0.5").name == "a=b");
  CHECK(parse_material_colour("--emission", "*=2").name == "*");
}

TEST_CASE("bad colour assignments are refused with one line naming the option and the problem",
          "[scene][assignment]") {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"light=-1,0,0", "--emission light=-1,0,0: every component must be finite and non-negative"},
      {"light=nan", "--emission light=nan: every component must be finite and non-negative"},
      {"light=inf,1,1",
       "--emission light=inf,1,1: every component must be finite and non-negative"},
      {"light=1e39", "--emission light=1e39: every component must be finite and non-negative"},
      {"light=1,2", "--emission light=1,2: expected 1 or 3 numbers"},
      {"=1", "--emission =1: expected MATERIAL=r,g,b"},
      {"light=", "--emission light=: expected MATERIAL=r,g,b"},
      {"light", "--emission light: expected MATERIAL=r,g,b"},
      {"light=1,x,2", "--emission light=1,x,2: 'x' is not a number"},
      {"light=1,,2", "--emission light=1,,2: '' is not a number"},
  };
  for (const auto& [text, message] : cases) CHECK(error_of("--emission", text) == message);
}

TEST_CASE("BRDF assignments: the name up to the first '=', the value may be empty",
          "[scene][assignment]") {
  const auto a = parse_material_assignment("--material", "m=ggx:alpha=0.1", AssignedValue::Brdf);
  CHECK(a.name == "m");
  CHECK(a.value == "ggx:alpha=0.1");
  CHECK(parse_material_assignment("--material", "m=", AssignedValue::Brdf).value.empty());
  CHECK_THROWS_WITH(parse_material_assignment("--material", "=ggx", AssignedValue::Brdf),
                    "--material =ggx: expected NAME=MODEL[:KEY=VALUE,...]");
  CHECK_THROWS_WITH(parse_material_assignment("--material", "ggx", AssignedValue::Brdf),
                    "--material ggx: expected NAME=MODEL[:KEY=VALUE,...]");
}

TEST_CASE("assignments match a material, else a primitive name, '*' every primitive",
          "[scene][assignment]") {
  const Scene s = three_quads();
  using prt::scene::matched_primitives;
  using Indices = std::vector<std::size_t>;
  CHECK(matched_primitives(s, parse_material_colour("--albedo", "white=0.5")) == Indices{0, 1});
  CHECK(matched_primitives(s, parse_material_colour("--albedo", "wall=0.5")) == Indices{1});
  CHECK(matched_primitives(s, parse_material_colour("--albedo", "*=0.5")) == Indices{0, 1, 2});
  // "lamp" is both a primitive's name and not a material: the primitive; "light" the material.
  CHECK(matched_primitives(s, parse_material_colour("--albedo", "lamp=0.5")) == Indices{2});
  CHECK(matched_primitives(s, parse_material_colour("--albedo", "light=0.5")) == Indices{2});
  CHECK_THROWS_WITH(matched_primitives(s, parse_material_colour("--emission", "glass=1")),
                    "--emission glass=1: no material or primitive named 'glass' in three.obj "
                    "(materials: 'white', 'light')");
}

TEST_CASE("apply_emission and apply_albedo set what they match, a later value winning",
          "[scene][assignment]") {
  Scene s = three_quads();
  prt::scene::apply_emission(s, {parse_material_colour("--emission", "light=4,2,1"),
                                 parse_material_colour("--emission", "wall=0.5")});
  CHECK(s.primitives[0].emission == glm::vec3(0.f));
  CHECK(s.primitives[1].emission == glm::vec3(0.5f));
  CHECK(s.primitives[2].emission == glm::vec3(4.f, 2.f, 1.f));
  prt::scene::apply_albedo(s, {parse_material_colour("--albedo", "*=0.2"),
                               parse_material_colour("--albedo", "floor=0.1,0.2,0.3")});
  const glm::vec3 floor(0.1f, 0.2f, 0.3f);
  CHECK(s.primitives[0].albedo == floor);
  CHECK(s.primitives[1].albedo == glm::vec3(0.2f));
  for (uint32_t v = 0; v < s.primitives[0].vertex_count; ++v)
    CHECK(s.albedo[s.primitives[0].first_vertex + v] == floor);
  for (uint32_t v = 0; v < s.primitives[2].vertex_count; ++v)
    CHECK(s.albedo[s.primitives[2].first_vertex + v] == glm::vec3(0.2f));
  CHECK_THROWS_AS(prt::scene::apply_albedo(s, {parse_material_colour("--albedo", "nosuch=0.5")}),
                  std::invalid_argument);
}
