// tests/golden/test_golden_images.cpp — golden-image regression tests: each image of the set
// (golden_set.h) is rendered by the prt executable and compared per pixel with its committed
// reference in tests/golden/references/ (tolerances: image_compare.h, README.md). On failure the
// message names the image, the pixels beyond tolerance, the max and mean difference, and the
// render and difference image written under the build folder (tests/output/golden/). Then the
// comparison itself: it passes an identical image and flags an exposure 1/4 EV off, another
// tone curve, a swapped channel and a one-pixel shift.
//
// Tolerances (image_compare.h): PNG 2 levels per pixel, at most 0.1% of the pixels beyond, mean
// at most 0.5 levels; EXR 0.5%, 0.1%, 0.1%. Why: the renders are bit-identical run to run and
// across thread counts here (the EXR references differ from a render only by half-float rounding,
// ≤ 0.049%), while a quarter stop moves every pixel of the demo by 3–13 levels; the margin is for
// another CPU's vector paths. The measurements are in tests/golden/README.md.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "golden_set.h"
#include "image_compare.h"
#include "relight/image_io.h"
#include "relight/tone_map.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using namespace prt::golden;
using prt::relight::FloatImage;

namespace {

fs::path work_dir(const std::string& name) {
  return prt::test::output_path("golden") / name;
}

// Renders one image of the set and compares it with its reference; a failure says why and
// leaves the render and a difference image beside it.
void check_golden(const std::string& name) {
  const GoldenImage& image = golden_image(name);
  const fs::path reference = references_dir() / image.file;
  if (!fs::exists(reference))
    FAIL(reference.string() << " is missing: make it with scripts/update-golden.sh \"REASON\"");
  const fs::path work = work_dir(name);
  const Render render = render_golden(image, PRT_CLI_PATH, work);
  const FloatImage ref = prt::relight::read_image(reference.string());
  const FloatImage got = prt::relight::read_image(render.image.string());
  const Tolerance tolerance = tolerance_for(reference);
  const Comparison c = compare_images(ref, got, tolerance);
  const fs::path diff = work / (name + "_diff.png");
  if (c.same_shape) write_difference_image(diff, ref, got, tolerance);
  INFO("golden image '" << name << "' (" << image.file << "): " << c.describe());
  INFO("render: " << render.image.string() << "; reference: " << reference.string()
                  << "; difference image: " << diff.string()
                  << "; commands and output: " << render.log.string());
  INFO("if the change is intended: scripts/update-golden.sh \"why the image changed\"");
  CHECK(c.passed());
}

FloatImage constant_image(int w, int h, int channels, float value) {
  FloatImage image;
  image.width = w;
  image.height = h;
  image.channels = channels;
  image.pixels.assign(static_cast<std::size_t>(w * h * channels), value);
  return image;
}

// 8-bit PNG values of linear pixels through exposure and curve (what a PNG render stores).
FloatImage tone_mapped(const FloatImage& linear, float exposure, prt::relight::ToneCurve curve) {
  FloatImage out = linear;
  prt::relight::tone_map(linear.pixels.data(), linear.pixels.size(), exposure, out.pixels.data(),
                         curve);
  for (float& v : out.pixels) v = std::round(std::clamp(v, 0.f, 1.f) * 255.f) / 255.f;
  return out;
}

// Relights the demo again in `work` (where render_golden left demo.prt), with the last command
// of its set entry plus `extra`, into work/NAME.EXT.
Render relight_demo_again(const fs::path& work, const std::string& name, const std::string& ext,
                          const std::vector<std::string>& extra) {
  GoldenImage again = golden_image("demo");
  again.name = name;
  again.file = name + ext;
  again.commands = {again.commands.back()};
  return render_golden(again, PRT_CLI_PATH, work, extra);
}

}  // namespace

TEST_CASE("golden image: demo (interreflected SH bake, auto exposure PNG)") {
  check_golden("demo");
}

TEST_CASE("golden image: glossy_sphere (GGX glossy transfer, linear EXR)") {
  check_golden("glossy_sphere");
}

TEST_CASE("golden image: cornell_radiosity (radiosity, PNG)") {
  check_golden("cornell_radiosity");
}

TEST_CASE("golden image: haar_sun (Haar sun shadow, linear EXR)") {
  check_golden("haar_sun");
}

TEST_CASE("golden image: textured_wall (per-pixel texture, PNG)") {
  check_golden("textured_wall");
}

TEST_CASE("golden comparison: per-pixel metrics and tolerances and the outlier allowance") {
  SECTION("PNG: a difference of 2 levels is within tolerance, 3 levels beyond") {
    const FloatImage a = constant_image(100, 10, 3, 100 / 255.f);
    FloatImage b = a;
    b.pixels[0] = 102 / 255.f;  // pixel 0: 2 levels
    b.pixels[5] = 103 / 255.f;  // pixel 1: 3 levels
    const Comparison c = compare_images(a, b, tolerance_for("x.png"));
    CHECK(c.pixels == 1000);
    CHECK(c.differing == 2);
    CHECK(c.beyond == 1);
    CHECK(c.allowed == 1);  // 0.1% of 1000
    CHECK(c.max_difference == Approx(3).epsilon(1e-4));
    CHECK(c.passed());
    b.pixels[8] = 0.f;  // a second pixel beyond: more than the allowance
    CHECK_FALSE(compare_images(a, b, tolerance_for("x.png")).passed());
  }
  SECTION("PNG: the whole picture one level off is within the per-pixel tolerance, not the mean") {
    const FloatImage a = constant_image(100, 10, 3, 100 / 255.f);
    const FloatImage b = constant_image(100, 10, 3, 101 / 255.f);
    const Comparison c = compare_images(a, b, tolerance_for("x.png"));
    CHECK(c.beyond == 0);
    CHECK(c.mean_difference == 1);
    CHECK_FALSE(c.passed());
  }
  SECTION("EXR: relative to the reference, with a floor of 5% of its mean") {
    FloatImage a = constant_image(1000, 1, 3, 1.f);
    a.pixels[0] = a.pixels[1] = a.pixels[2] = 0.f;  // a black pixel
    FloatImage b = a;
    b.pixels[3] = 1.004f;   // 0.4%: within 0.5%
    b.pixels[0] = 0.0002f;  // against the floor 0.05 × mean ≈ 0.05: 0.4%
    Comparison c = compare_images(a, b, tolerance_for("x.exr"));
    CHECK(c.differing == 2);
    CHECK(c.beyond == 0);
    CHECK(c.max_difference == Approx(0.004).epsilon(0.01));
    b.pixels[6] = 0.99f;  // 1%: beyond
    b.pixels[9] = 1.02f;  // 2%: beyond, more than the one allowed
    c = compare_images(a, b, tolerance_for("x.exr"));
    CHECK(c.beyond == 2);
    CHECK_FALSE(c.passed());
  }
  SECTION("a NaN where the reference has a number, or another size, fails") {
    const FloatImage a = constant_image(10, 10, 3, 0.5f);
    FloatImage b = a;
    b.pixels[4] = std::nanf("");
    b.pixels[40] = std::nanf("");
    b.pixels[80] = std::nanf("");
    CHECK(compare_images(a, b, tolerance_for("x.exr")).beyond == 3);
    const Comparison c = compare_images(a, constant_image(10, 9, 3, 0.5f), tolerance_for("x.png"));
    CHECK_FALSE(c.passed());
    CHECK(c.describe().find("render 10x9x3, reference 10x10x3") != std::string::npos);
  }
  SECTION("the difference image marks the pixels beyond tolerance in red to yellow") {
    const FloatImage a = constant_image(4, 1, 3, 100 / 255.f);
    FloatImage b = a;
    b.pixels[3] = 101 / 255.f;  // pixel 1: 1 level, half the tolerance
    b.pixels[6] = 110 / 255.f;  // pixel 2: 10 levels, 5 × the tolerance
    const fs::path out = prt::test::output_path("golden") / "difference_unit.png";
    fs::create_directories(out.parent_path());
    write_difference_image(out, a, b, tolerance_for("x.png"));
    const FloatImage d = prt::relight::read_image(out.string());
    CHECK(d.pixels[0] == 0.f);                                   // identical: black
    CHECK(d.pixels[3] == Approx(64 / 255.f).margin(0.5 / 255));  // within: grey
    CHECK(d.pixels[4] == d.pixels[3]);
    CHECK(d.pixels[6] == 1.f);  // 2 × the tolerance or more: yellow
    CHECK(d.pixels[7] == 1.f);
    CHECK(d.pixels[8] == 0.f);
  }
}

TEST_CASE("golden comparison: a perturbed render fails and an identical one passes") {
  const GoldenImage& demo = golden_image("demo");
  const fs::path demo_reference = references_dir() / demo.file;
  REQUIRE(fs::exists(demo_reference));
  const FloatImage ref = prt::relight::read_image(demo_reference.string());
  const Tolerance png = tolerance_for(demo_reference);

  SECTION("the reference against itself: nothing differs") {
    const Comparison c = compare_images(ref, ref, png);
    CHECK(c.passed());
    CHECK(c.differing == 0);
    CHECK(c.max_difference == 0);
  }
  SECTION("the demo rendered 1/4 EV brighter than its automatic exposure fails") {
    // The automatic exposure of the set's commands, read from their output, then the same
    // relight at that exposure (identical) and at 0.25 EV more (must fail).
    const fs::path work = work_dir("perturbed_exposure");
    const Render auto_render = render_golden(demo, PRT_CLI_PATH, work);
    const double ev = reported_exposure(auto_render.log);
    const Render same =
        relight_demo_again(work, "same", ".png", {"--exposure", std::to_string(ev)});
    const Comparison unchanged =
        compare_images(ref, prt::relight::read_image(same.image.string()), png);
    INFO("explicit --exposure " << ev << ": " << unchanged.describe());
    CHECK(unchanged.passed());
    const Render brighter =
        relight_demo_again(work, "brighter", ".png", {"--exposure", std::to_string(ev + 0.25)});
    const Comparison c =
        compare_images(ref, prt::relight::read_image(brighter.image.string()), png);
    INFO("+0.25 EV: " << c.describe());
    CHECK_FALSE(c.passed());
    CHECK(c.beyond > c.pixels / 2);  // most of the picture, not a few pixels
  }
  SECTION("the demo's linear render through another tone curve fails, through its own passes") {
    const fs::path work = work_dir("perturbed_curve");
    const float ev =
        static_cast<float>(reported_exposure(render_golden(demo, PRT_CLI_PATH, work).log));
    const Render linear = relight_demo_again(work, "linear", ".exr", {});
    const FloatImage hdr = prt::relight::read_image(linear.image.string());
    const Comparison own =
        compare_images(ref, tone_mapped(hdr, ev, prt::relight::ToneCurve::AcesFilmic), png);
    INFO("ACES filmic at " << ev << " EV: " << own.describe());
    CHECK(own.passed());
    const Comparison clamp =
        compare_images(ref, tone_mapped(hdr, ev, prt::relight::ToneCurve::Clamp), png);
    INFO("no curve (clamp): " << clamp.describe());
    CHECK_FALSE(clamp.passed());
  }
  SECTION("a linear reference scaled by 2^0.25, a swapped channel or a one-pixel shift fails") {
    const fs::path exr = references_dir() / golden_image("glossy_sphere").file;
    REQUIRE(fs::exists(exr));
    const FloatImage g = prt::relight::read_image(exr.string());
    const Tolerance relative = tolerance_for(exr);
    FloatImage scaled = g, swapped = g, shifted = g, slightly = g;
    for (float& v : scaled.pixels) v *= std::pow(2.f, 0.25f);
    for (float& v : slightly.pixels) v *= 1.0005f;  // 0.05%: within tolerance
    for (std::size_t p = 0; p + 2 < swapped.pixels.size(); p += 3)
      std::swap(swapped.pixels[p], swapped.pixels[p + 2]);
    std::copy(g.pixels.begin(), g.pixels.end() - 3, shifted.pixels.begin() + 3);
    CHECK(compare_images(g, slightly, relative).passed());
    const Comparison s = compare_images(g, scaled, relative);
    INFO("x 2^0.25: " << s.describe());
    CHECK_FALSE(s.passed());
    CHECK(s.beyond > s.pixels / 2);
    CHECK_FALSE(compare_images(g, swapped, relative).passed());
    CHECK_FALSE(compare_images(g, shifted, relative).passed());
  }
}
