// fuzz/fuzz_env_map.cpp — libFuzzer target: the environment-map path from memory, image bytes →
// the project's Radiance / PFM decoders (relight/radiance_hdr.h, relight/pfm_image.h) →
// relight::to_environment (layout guessed or forced) → prt::sh::validate_layout → prt::sh::project.
// (EXR goes through OpenImageIO: fuzz_env_map_exr.cpp.)
//
// Input: byte 0 picks the decoder (even: Radiance RGBE, odd: PFM) and the layout
// ((b / 2) % 5: guessed, latlong, angular, cross, faces); the rest is the file. A hostile file
// must be refused with a one-line std::runtime_error "fuzz.hdr: ..." / "fuzz.pfm: ...", or give
// an image of the announced size (RGBE: finite, non-negative samples) and then a map whose
// projection is finite over the texels it used (NaN/Inf/negative texels are skipped and
// counted). Images over kMaxFuzzTexels are refused by the decoders' own size cap, before they
// allocate, which keeps each execution short (the cap is the parameter real reads set to 2^28).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "relight/image_io.h"
#include "relight/pfm_image.h"
#include "relight/radiance_hdr.h"
#include "sh/env_map.h"
#include "sh/projection.h"

namespace {

// 2^16 texels: wide enough for a 32768-pixel scanline (flat, too long for RLE) and beyond.
constexpr std::size_t kMaxFuzzTexels = std::size_t{1} << 16;

// Errors are one line, "NAME: problem".
void check_error(const char* message, const std::string& name) {
  if (message == nullptr || std::strncmp(message, name.c_str(), name.size()) != 0 ||
      std::strncmp(message + name.size(), ": ", 2) != 0 || message[name.size() + 2] == '\0' ||
      std::strchr(message, '\n') != nullptr || std::strchr(message, '\r') != nullptr)
    std::abort();
}

std::optional<prt::sh::EnvLayout> layout_of(uint8_t selector) {
  switch ((selector / 2) % 5) {
    case 1:
      return prt::sh::EnvLayout::LatLong;
    case 2:
      return prt::sh::EnvLayout::Angular;
    case 3:
      return prt::sh::EnvLayout::Cross;
    case 4:
      return prt::sh::EnvLayout::Faces;
    default:
      return std::nullopt;  // guessed from the aspect ratio
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  const bool radiance = selector % 2 == 0;
  const std::string name = radiance ? "fuzz.hdr" : "fuzz.pfm";
  prt::relight::FloatImage image;
  try {
    image = radiance ? prt::relight::decode_radiance_hdr(data + 1, size - 1, name, kMaxFuzzTexels)
                     : prt::relight::decode_pfm(data + 1, size - 1, name, kMaxFuzzTexels);
  } catch (const std::runtime_error& e) {
    check_error(e.what(), name);
    return 0;
  }
  if (image.width <= 0 || image.height <= 0) std::abort();
  const std::size_t texels = static_cast<std::size_t>(image.width) * image.height;
  if (texels > kMaxFuzzTexels) std::abort();
  const bool channels_ok =
      radiance ? image.channels == 3 : image.channels == 1 || image.channels == 3;
  if (!channels_ok) std::abort();
  if (image.pixels.size() != texels * static_cast<std::size_t>(image.channels)) std::abort();
  if (radiance)
    for (float v : image.pixels)
      if (!std::isfinite(v) || v < 0.0f) std::abort();  // m · 2^(e − 136) is never NaN or < 0

  prt::sh::EnvMap env;
  try {
    env = prt::relight::to_environment(std::move(image), name, layout_of(selector));
  } catch (const std::runtime_error& e) {
    check_error(e.what(), name);
    return 0;
  }
  std::string why;
  if (!prt::sh::validate_layout(env.layout, env.width, env.height, &why)) std::abort();
  if (env.rgb.size() != texels * 3) std::abort();
  prt::sh::ProjectionStats stats;
  const std::vector<double> c = prt::sh::project(env, 3, &stats);
  if (c.size() != 27) std::abort();
  for (double v : c)
    if (!std::isfinite(v)) {
      // Only finite texels are summed; finite floats can still overflow a double sum only
      // beyond ~1e308, impossible for float inputs times solid angles ≤ 4π.
      std::abort();
    }
  return 0;
}
