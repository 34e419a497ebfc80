// Tests of relight/image_io.h and relight/sky_model.h: round trips, atomic writes, one-line
// errors, layout detection on real probes, a cross-layout consistency check on the same capture,
// and the procedural sky's sun.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "relight/image_io.h"
#include "relight/sky_model.h"
#include "sh/constants.h"
#include "sh/projection.h"
#include "support/error_message.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using prt::relight::read_environment;
using prt::relight::write_image;
using prt::test::error_of;

namespace {

using prt::sh::kPi;

std::string scratch(const std::string& name) {
  fs::create_directories(prt::test::output_path("image_io"));
  return prt::test::output_path("image_io/" + name).string();
}

std::vector<float> random_pixels(std::size_t count, float low, float high, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<float> uniform(low, high);
  std::vector<float> pixels(count);
  for (float& p : pixels) p = uniform(random);
  return pixels;
}

// No temporaries of `path` (PATH.tmp-<pid>) are left in its directory. Only this path's: ctest
// runs the other cases as parallel processes writing into the same directory, and their
// temporaries may exist at any moment.
bool no_temporaries_beside(const std::string& path) {
  const std::string prefix = fs::path(path).filename().string() + ".tmp-";
  for (const auto& entry : fs::directory_iterator(fs::path(path).parent_path()))
    if (entry.path().filename().string().rfind(prefix, 0) == 0) return false;
  return true;
}

void check_one_line_error(const std::string& message, const std::string& path) {
  INFO(message);
  CHECK(message.rfind(path + ": ", 0) == 0);  // starts with "PATH: "
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.size() > path.size() + 2);
}

// Band-1 direction (L_1,1, L_1,−1, L_1,0) of channel `channel` of a channel-major expansion.
std::array<double, 3> band1_direction(const std::vector<double>& L, int order, int channel) {
  const double* c = &L[static_cast<std::size_t>(channel) * order * order];
  std::array<double, 3> d = {c[3], c[1], c[2]};
  const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
  for (double& x : d) x /= n;
  return d;
}

double angle_deg(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  const double dot = a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  return std::acos(std::clamp(dot, -1.0, 1.0)) * 180.0 / kPi;
}

}  // namespace

TEST_CASE("EXR round trips exactly in float and within half precision in half") {
  const int w = 7, h = 5;
  std::vector<float> pixels = random_pixels(w * h * 3, 0.0f, 50.0f, 1);
  pixels[5] = 1.0e5f;  // above the half range
  const std::string path = scratch("roundtrip.exr");
  write_image(path, w, h, 3, pixels.data());
  CHECK(no_temporaries_beside(path));
  const prt::relight::FloatImage image = prt::relight::read_image(path);
  REQUIRE(image.width == w);
  REQUIRE(image.height == h);
  REQUIRE(image.channels == 3);
  CHECK(image.pixels == pixels);  // 32-bit float EXR is lossless

  const std::string half_path = scratch("roundtrip_half.exr");
  prt::relight::ImageWriteOptions options;
  options.exr_half = true;
  write_image(half_path, w, h, 3, pixels.data(), options);
  const prt::relight::FloatImage half = prt::relight::read_image(half_path);
  REQUIRE(half.pixels.size() == pixels.size());
  for (std::size_t i = 0; i < pixels.size(); ++i) {
    if (i == 5) continue;
    // Half has an 11-bit significand: relative rounding error ≤ 2^-11.
    CHECK(half.pixels[i] == Approx(pixels[i]).epsilon(1.0 / 2048));
  }
  CHECK(half.pixels[5] == 65504.0f);  // clamped to the largest half, not turned into infinity
}

TEST_CASE("HDR (RGBE) round trips within its shared-exponent precision") {
  const int w = 16, h = 8;
  std::vector<float> pixels = random_pixels(w * h * 3, 0.001f, 2000.0f, 2);
  const std::string path = scratch("roundtrip.hdr");
  write_image(path, w, h, 3, pixels.data());
  CHECK(no_temporaries_beside(path));
  std::string note;
  const prt::sh::EnvMap env = read_environment(path, std::nullopt, &note);
  CHECK(env.layout == prt::sh::EnvLayout::LatLong);
  CHECK(note.find("latlong") != std::string::npos);
  REQUIRE(env.width == w);
  REQUIRE(env.height == h);
  for (int i = 0; i < w * h; ++i) {
    const float* in = &pixels[i * 3];
    const float* out = &env.rgb[i * 3];
    const float largest = std::max({in[0], in[1], in[2]});
    // RGBE stores 8-bit mantissas under the largest channel's exponent: each channel is within
    // one step, 2^-8 of the largest channel's power of two (≤ 2^-7 of the largest channel).
    for (int c = 0; c < 3; ++c) CHECK(std::abs(out[c] - in[c]) <= largest / 128.0f);
  }
}

TEST_CASE("PNG quantises encoded values to 8 bits, and grey images are replicated on reading") {
  const int w = 4, h = 3;
  std::vector<float> pixels = random_pixels(w * h, -0.2f, 1.2f, 3);
  pixels[0] = std::nanf("");
  const std::string path = scratch("grey.png");
  write_image(path, w, h, 1, pixels.data());
  const prt::relight::FloatImage image = prt::relight::read_image(path);
  REQUIRE(image.channels == 1);
  for (int i = 0; i < w * h; ++i) {
    const float v = std::isnan(pixels[i]) ? 0.0f : std::clamp(pixels[i], 0.0f, 1.0f);
    // OpenImageIO returns 8-bit values as byte/255.
    CHECK(image.pixels[i] == Approx(std::round(v * 255.0f) / 255.0f).margin(1e-6));
  }
  // A grey image read as an environment: channel 0 replicated into RGB.
  const std::string grey_hdr = scratch("grey_env.png");
  std::vector<float> square(8 * 8, 0.25f);
  write_image(grey_hdr, 8, 8, 1, square.data());
  const prt::sh::EnvMap env = read_environment(grey_hdr, prt::sh::EnvLayout::Angular);
  REQUIRE(env.rgb.size() == 8u * 8u * 3u);
  CHECK(env.rgb[0] == env.rgb[1]);
  CHECK(env.rgb[1] == env.rgb[2]);
  CHECK(env.rgb[0] == Approx(64.0f / 255.0f));
}

TEST_CASE("PFM files are read with row 0 at the top") {
  // PFM stores rows bottom to top; write one by hand: 2x2, little-endian (scale −1).
  const std::string path = scratch("orientation.pfm");
  {
    std::ofstream out(path, std::ios::binary);
    out << "PF\n2 2\n-1.0\n";
    // Bottom row first: bottom-left (1,1,1), bottom-right (2,2,2); top row (3,3,3), (4,4,4).
    const float data[12] = {1, 1, 1, 2, 2, 2, 3, 3, 3, 4, 4, 4};
    out.write(reinterpret_cast<const char*>(data), sizeof data);
  }
  const prt::sh::EnvMap env = read_environment(path, prt::sh::EnvLayout::Angular);
  REQUIRE(env.rgb.size() == 12u);
  CHECK(env.rgb[0] == 3.0f);  // top-left
  CHECK(env.rgb[3] == 4.0f);
  CHECK(env.rgb[6] == 1.0f);  // bottom-left
  CHECK(env.rgb[9] == 2.0f);
}

TEST_CASE("reading fails with one-line PATH: problem errors") {
  const std::string missing = scratch("does_not_exist.hdr");
  const std::string missing_error = error_of([&] { read_environment(missing, std::nullopt); });
  check_one_line_error(missing_error, missing);
  CHECK(missing_error.find("no such file") != std::string::npos);

  // Not an image at all.
  const std::string garbage = scratch("garbage.exr");
  std::ofstream(garbage) << "this is not an image\n";
  check_one_line_error(error_of([&] { read_environment(garbage, std::nullopt); }), garbage);

  // Zero size: a PFM header announcing 0x0 pixels.
  const std::string empty = scratch("empty.pfm");
  std::ofstream(empty, std::ios::binary) << "PF\n0 0\n-1.0\n";
  const std::string empty_error = error_of([&] { read_environment(empty, std::nullopt); });
  check_one_line_error(empty_error, empty);
  CHECK(empty_error.find("zero size") != std::string::npos);

  // Aspect ratios that fit no layout (auto) or not the requested one.
  const std::string odd = scratch("odd_aspect.exr");
  std::vector<float> pixels(10 * 7 * 3, 1.0f);
  write_image(odd, 10, 7, 3, pixels.data());
  const std::string guess_error = error_of([&] { read_environment(odd, std::nullopt); });
  check_one_line_error(guess_error, odd);
  CHECK(guess_error.find("10x7") != std::string::npos);
  const std::string wide = scratch("wide.exr");
  std::vector<float> wide_pixels(8 * 4 * 3, 1.0f);
  write_image(wide, 8, 4, 3, wide_pixels.data());
  const std::string layout_error =
      error_of([&] { read_environment(wide, prt::sh::EnvLayout::Angular); });
  check_one_line_error(layout_error, wide);
  CHECK(layout_error.find("angular") != std::string::npos);
  CHECK_NOTHROW(read_environment(wide, prt::sh::EnvLayout::LatLong));
}

TEST_CASE("writes are atomic and failures leave nothing behind") {
  const std::string bad_dir = scratch("no_such_dir/out.exr");
  std::vector<float> pixels(4 * 2 * 3, 1.0f);
  check_one_line_error(error_of([&] { write_image(bad_dir, 4, 2, 3, pixels.data()); }), bad_dir);
  CHECK_FALSE(fs::exists(bad_dir));
  const std::string bad_extension = scratch("image.xyz");
  check_one_line_error(error_of([&] { write_image(bad_extension, 4, 2, 3, pixels.data()); }),
                       bad_extension);
  CHECK_FALSE(fs::exists(bad_extension));
  // Overwriting an existing file replaces it whole.
  const std::string path = scratch("overwrite.exr");
  write_image(path, 4, 2, 3, pixels.data());
  std::vector<float> other(6 * 3 * 3, 2.0f);
  write_image(path, 6, 3, 3, other.data());
  const prt::relight::FloatImage image = prt::relight::read_image(path);
  CHECK(image.width == 6);
  CHECK(image.pixels == other);
  CHECK(no_temporaries_beside(path));
}

TEST_CASE("six face files stack into a Faces map in the order px, nx, py, ny, pz, nz") {
  const int s = 4;
  const std::string pattern = scratch("cube_%s.exr");
  for (int face = 0; face < 6; ++face) {
    std::vector<float> pixels(s * s * 3, static_cast<float>(face + 1));
    std::string path = pattern;
    path.replace(path.find("%s"), 2, prt::relight::kFaceSuffixes[face]);
    write_image(path, s, s, 3, pixels.data());
  }
  std::string note;
  const prt::sh::EnvMap env = read_environment(pattern, prt::sh::EnvLayout::Faces, &note);
  CHECK(env.layout == prt::sh::EnvLayout::Faces);
  REQUIRE(env.width == s);
  REQUIRE(env.height == 6 * s);
  for (int face = 0; face < 6; ++face)
    CHECK(env.rgb[(face * s * s) * 3] == static_cast<float>(face + 1));
  // The +Z face (5th, value 5) is where direction +Z samples.
  const double plus_z[3] = {0, 0, 1};
  float rgb[3];
  prt::sh::sample_bilinear(env, plus_z, rgb);
  CHECK(rgb[0] == 5.0f);
  // A missing face names its file.
  std::vector<std::string> paths(6, scratch("cube_px.exr"));
  paths[3] = scratch("cube_missing.exr");
  check_one_line_error(error_of([&] { prt::relight::read_environment_faces(paths); }), paths[3]);
}

TEST_CASE("real probes: the layout is guessed from the aspect ratio") {
  struct Case {
    const char* file;
    prt::sh::EnvLayout layout;
  };
  const Case cases[] = {{"probes/grace_probe.hdr", prt::sh::EnvLayout::Angular},
                        {"probes/grace_cross.hdr", prt::sh::EnvLayout::Cross},
                        {"probes/small/grace.hdr", prt::sh::EnvLayout::LatLong}};
  for (const Case& c : cases) {
    const fs::path path = prt::test::shared_data(c.file);
    PRT_REQUIRE_SHARED_DATA(path);
    std::string note;
    const prt::sh::EnvMap env = read_environment(path.string(), std::nullopt, &note);
    INFO(c.file << ": " << note);
    CHECK(env.layout == c.layout);
    CHECK(note.find(prt::sh::layout_name(c.layout)) != std::string::npos);
    CHECK(note.find("auto") != std::string::npos);
    CHECK(env.rgb.size() == static_cast<std::size_t>(env.width) * env.height * 3);
  }
}

TEST_CASE("the same capture as angular probe and as vertical cross projects alike") {
  const fs::path probe_path = prt::test::shared_data("probes/grace_probe.hdr");
  const fs::path cross_path = prt::test::shared_data("probes/grace_cross.hdr");
  PRT_REQUIRE_SHARED_DATA(probe_path);
  PRT_REQUIRE_SHARED_DATA(cross_path);
  const prt::sh::EnvMap probe = read_environment(probe_path.string(), prt::sh::EnvLayout::Angular);
  const prt::sh::EnvMap cross = read_environment(cross_path.string(), prt::sh::EnvLayout::Cross);
  const int order = 3;
  prt::sh::ProjectionStats probe_stats, cross_stats;
  const std::vector<double> a = prt::sh::project(probe, order, &probe_stats);
  const std::vector<double> b = prt::sh::project(cross, order, &cross_stats);
  REQUIRE(a.size() == 27u);
  REQUIRE(b.size() == 27u);
  // Both files are Debevec's 1999 Grace Cathedral, resampled by HDR Shop into the two layouts,
  // but saved at different exposures: the cross is brighter by a constant factor (measured
  // 4.00 in every channel, two stops). So compare shapes: the colour balance (the per-channel
  // exposure ratio must be the same for r, g, b) and the coefficients divided by the channel's
  // L_00. Resampling (and the cross's watermark) change the integrals only a little: measured,
  // the three ratios agree to 6e-5, the largest |a_k/a_00 − b_k/b_00| is 1.1e-4 and the band-1
  // directions agree within 0.003°. Tolerances (1e-3, 1e-3, 0.05°) leave 10–20x margin, and a
  // mirrored or rotated face would move band-1 and band-2 coefficients by tens of percent.
  double ratio[3];
  double worst = 0.0;
  for (int channel = 0; channel < 3; ++channel) {
    const double a00 = a[channel * 9], b00 = b[channel * 9];
    ratio[channel] = b00 / a00;
    for (int k = 1; k < 9; ++k)
      worst = std::max(worst, std::abs(a[channel * 9 + k] / a00 - b[channel * 9 + k] / b00));
    const double angle =
        angle_deg(band1_direction(a, order, channel), band1_direction(b, order, channel));
    INFO("channel " << channel << " exposure ratio " << ratio[channel] << ", band-1 angle " << angle
                    << " deg");
    CHECK(angle < 0.05);
  }
  INFO("ratios " << ratio[0] << " " << ratio[1] << " " << ratio[2]);
  CHECK(ratio[1] == Approx(ratio[0]).epsilon(1e-3));
  CHECK(ratio[2] == Approx(ratio[0]).epsilon(1e-3));
  INFO("worst |a_k/a_00 - b_k/b_00| = " << worst);
  CHECK(worst < 1e-3);
}

TEST_CASE("procedural sky: no NaN, the sun where configured, the sun dominates band 1") {
  prt::relight::SkyParams params;
  params.sun_elevation_deg = 30.0;
  params.sun_azimuth_deg = -70.0;
  const std::array<double, 3> sun = prt::relight::sun_direction(params);
  const prt::sh::EnvMap sky = prt::relight::make_procedural_sky(256, 128, params);
  REQUIRE(sky.rgb.size() == 256u * 128u * 3u);
  bool finite_positive = true;
  std::size_t brightest = 0;
  for (std::size_t i = 0; i < sky.rgb.size(); ++i) {
    finite_positive = finite_positive && std::isfinite(sky.rgb[i]) && sky.rgb[i] > 0.0f;
    if (sky.rgb[i] > sky.rgb[brightest]) brightest = i;
  }
  CHECK(finite_positive);
  // The brightest texel is the sun's: the texel containing the sun direction (±1 texel).
  double col, row;
  REQUIRE(prt::sh::direction_to_texel(prt::sh::EnvLayout::LatLong, 256, 128, sun.data(), &col, &row));
  const int texel = static_cast<int>(brightest / 3);
  CHECK(std::abs(texel % 256 - col) < 1.5);
  CHECK(std::abs(texel / 256 - row) < 1.5);
  // Above the horizon is brighter than below: zenith vs nadir texels.
  CHECK(sky.rgb[2] > 2 * sky.rgb[(127 * 256) * 3 + 2]);

  const int order = 3;
  const std::vector<double> with_sun = prt::sh::project(sky, order);
  // Sun + glow alone: their band-1 vector points at the sun up to the lat-long quadrature of a
  // 1°-radius disc on 1.4° texels (measured 0.05°; tolerance 0.5°).
  prt::relight::SkyParams no_sun = params;
  no_sun.sun_radiance = 0.0;
  no_sun.glow_radiance = 0.0;
  const std::vector<double> without_sun =
      prt::sh::project(prt::relight::make_procedural_sky(256, 128, no_sun), order);
  std::vector<double> sun_only(with_sun.size());
  for (std::size_t i = 0; i < sun_only.size(); ++i) sun_only[i] = with_sun[i] - without_sun[i];
  const std::array<double, 3> zenith = {0.0, 1.0, 0.0};
  for (int channel = 0; channel < 3; ++channel) {
    const double sun_only_angle = angle_deg(band1_direction(sun_only, order, channel), sun);
    const std::array<double, 3> all = band1_direction(with_sun, order, channel);
    INFO("channel " << channel << ": sun-only band 1 is " << sun_only_angle
                    << " deg from the sun; the full sky's " << angle_deg(all, sun) << " deg");
    CHECK(sun_only_angle < 0.5);
    // The whole sky's band 1 leans toward the sun rather than the zenith (the sun dominates):
    // measured 4°, 10° and 22° from the sun for r, g, b (the blue sky pulls blue up; the sun is
    // 60° from the zenith). Tolerance 30°, and nearer the sun than the zenith.
    CHECK(angle_deg(all, sun) < 30.0);
    CHECK(angle_deg(all, sun) < angle_deg(all, zenith));
  }
  // Deterministic: the same parameters give the same bits.
  CHECK(prt::relight::make_procedural_sky(64, 32, params).rgb ==
        prt::relight::make_procedural_sky(64, 32, params).rgb);
}
