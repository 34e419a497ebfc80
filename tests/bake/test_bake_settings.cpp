// tests/bake/test_bake_settings.cpp — the canonical bake settings (bake/bake_settings.h) that
// part files carry: every key the writer emits is read back (a key changed in the JSON comes
// back changed in the options), and the members that are not carried are the run settings, the
// seed and what a sharded bake refuses. That every member of the options structs is in a table
// is a static_assert in bake/src/bake_settings.cpp: a new member without a line does not compile.
#include <functional>
#include <string>
#include <utility>

#include <catch2/catch.hpp>
#include <nlohmann/json.hpp>

#include "bake/bake_settings.h"

using namespace prt::bake;
using nlohmann::json;

namespace {

// Another valid value for the setting `key` holding `v`.
json changed(const std::string& key, const json& v) {
  if (key == "transfer") return v == "interreflected" ? "unshadowed" : "interreflected";
  if (key == "precision" || key == "bounce_precision") return v == "f16" ? "f32" : "f16";
  if (key == "falloff") return v == "smoothstep" ? "linear" : "smoothstep";
  if (key == "quantization_bits") return v == 8 ? 16 : 8;
  if (v.is_boolean()) return !v.get<bool>();
  if (v.is_number_integer() || v.is_number_unsigned()) return v.get<int64_t>() + 1;
  if (v.is_number_float()) return v.get<double>() * 2 + 0.25;
  FAIL("setting " << key << " of an unexpected type: " << v.dump());
  return v;
}

using CheckChanged = std::function<void(const json& modified, const std::string& name)>;

// Hands `check` a copy of `base` with one leaf under its key `key` changed (changed()), for each
// leaf: the value itself, or each member of an object, named "key" or "key.member".
void for_each_changed_leaf(const json& base, const std::string& key, const CheckChanged& check) {
  const json& value = base.at(key);
  if (!value.is_object()) {
    json modified = base;
    modified[key] = changed(key, value);
    check(modified, key);
    return;
  }
  for (auto sub = value.begin(); sub != value.end(); ++sub) {
    json modified = base;
    modified[key][sub.key()] = changed(sub.key(), sub.value());
    check(modified, key + "." + sub.key());
  }
}

using RoundTrip = std::function<std::string(const std::string&)>;

// The check of one changed setting (`base` with a leaf changed, named `name`): it differs from
// `base` and comes back through `round_trip` as it is. Counts the leaves checked in *leaves.
CheckChanged carried_check(const json& base, RoundTrip round_trip, int* leaves) {
  return [&base, round_trip = std::move(round_trip), leaves](const json& modified,
                                                             const std::string& name) {
    INFO("setting " << name);
    ++*leaves;
    CHECK(modified != base);
    CHECK(json::parse(round_trip(modified.dump())) == modified);
  };
}

// Every leaf of `settings` but "basis", changed one at a time, must come back changed through
// `read` and `write` (the reader reads every key the writer writes).
void check_every_key_carried(const std::string& settings, const RoundTrip& round_trip) {
  const json base = json::parse(settings);
  CHECK(json::parse(round_trip(settings)) == base);
  int leaves = 0;
  const CheckChanged check = carried_check(base, round_trip, &leaves);
  for (auto it = base.begin(); it != base.end(); ++it)
    if (it.key() != "basis") for_each_changed_leaf(base, it.key(), check);
  CHECK(leaves >= 6);
}

}  // namespace

TEST_CASE("bake settings: every key of an SH bake's settings is read back") {
  BakeOptions o;
  o.ao = true;
  o.obscurance.distance = 0.5;
  const std::string s = sh_bake_settings(o);
  CHECK(json::parse(s).at("obscurance").at("distance") == 0.5);
  check_every_key_carried(s, [](const std::string& t) {
    return sh_bake_settings(sh_options_from_settings(t, 7, "test"));
  });
  CHECK(sh_options_from_settings(s, 7, "test").seed == 7);
  CHECK(sh_options_from_settings(s, 7, "test").obscurance.distance == 0.5);
}

TEST_CASE("bake settings: every key of Haar and glossy settings is read back") {
  check_every_key_carried(haar_bake_settings(HaarBakeOptions{}), [](const std::string& t) {
    return haar_bake_settings(haar_options_from_settings(t, 1, "test"));
  });
  GlossyBakeOptions g;
  g.bounces = -1;
  check_every_key_carried(glossy_bake_settings(g), [](const std::string& t) {
    return glossy_bake_settings(glossy_options_from_settings(t, 1, "test"));
  });
}

TEST_CASE("bake settings: only run settings, the seed and refused options are not carried") {
  const std::vector<std::string> left = settings_not_carried();
  int sh = 0;
  for (const std::string& line : left) {
    INFO(line);
    const std::string member = line.substr(0, line.find(':'));
    const bool allowed = member == "seed" || member == "threads" || member == "memory_limit" ||
                         member == "adaptive" || member == "keep_albedo_apart" ||
                         member == "dense_gather" || member == "direct_override" ||
                         member == "vertex_material";
    CHECK(allowed);
    sh += member == "adaptive" || member == "dense_gather";
  }
  CHECK(sh == 2);
}

// The subsurface options: every coefficient of every material, the scale and the gather options
// come back changed when changed in the JSON (a material's arrays are not covered by
// check_every_key_carried, so each component is changed here).
TEST_CASE("bake settings: every key of a subsurface bake's settings is read back") {
  SubsurfaceBakeOptions o;
  o.materials.resize(2);
  for (std::size_t m = 0; m < 2; ++m)
    o.materials[m] = {{0.01 * (m + 1), 0.02, 0.03}, {1.0, 2.0 + m, 3.0}, 1.3 + 0.1 * m};
  o.vertex_material = {0, 1, -1};
  o.mm_per_unit = 2.5;
  o.gather.epsilon = 0.3;
  const std::string s = subsurface_bake_settings(o);
  const auto round_trip = [](const std::string& t) {
    return subsurface_bake_settings(subsurface_options_from_settings(t, "test"));
  };
  CHECK(round_trip(s) == s);
  CHECK(subsurface_options_from_settings(s, "test").vertex_material.empty());
  const json base = json::parse(s);
  int leaves = 0;
  const CheckChanged check = carried_check(base, round_trip, &leaves);
  for (auto it = base.begin(); it != base.end(); ++it) {
    if (it.key() == "materials") {
      for (std::size_t m = 0; m < 2; ++m)
        for (const char* field : {"sigma_a", "sigma_s_prime"})
          for (int c = 0; c < 3; ++c) {
            json modified = base;
            modified["materials"][m][field][c] = base["materials"][m][field][c].get<double>() * 2;
            check(modified, std::string(field) + "[" + std::to_string(c) + "]");
          }
      for (std::size_t m = 0; m < 2; ++m) {
        json modified = base;
        modified["materials"][m]["eta"] = 1.7;
        check(modified, "eta");
      }
    } else {
      for_each_changed_leaf(base, it.key(), check);
    }
  }
  CHECK(leaves == 2 * 6 + 2 + 1 + 3);  // coefficients, η, mm per unit, gather
  json missing = base;
  missing["gather"].erase("epsilon");
  CHECK_THROWS_WITH(subsurface_options_from_settings(missing.dump(), "p.prtpart: settings"),
                    Catch::StartsWith("p.prtpart: settings: "));
}

TEST_CASE("bake settings: a missing or malformed key is a BakeError naming the part") {
  json s = json::parse(sh_bake_settings(BakeOptions{}));
  s.erase("samples");
  CHECK_THROWS_WITH(sh_options_from_settings(s.dump(), 1, "p.prtpart: settings"),
                    Catch::StartsWith("p.prtpart: settings: "));
  s = json::parse(sh_bake_settings(BakeOptions{}));
  s["transfer"] = "sideways";
  CHECK_THROWS_AS(sh_options_from_settings(s.dump(), 1, "p"), BakeError);
}
