// fuzz/fuzz_env_map.cpp — libFuzzer target: the environment-map path, image bytes →
// OpenImageIO (relight::read_environment) → sh::validate_layout → sh::project.
//
// Input: byte 0 picks the container (.hdr, .exr, .pfm) and whether the layout is guessed or
// forced; the rest is the file. A hostile file must either be refused with a one-line
// std::runtime_error or give a map whose projection is finite over the texels it used
// (NaN/Inf/negative texels are skipped and counted). Images larger than kMaxFuzzTexels are
// refused by the target before decoding pixels would take all memory (the header is read
// by read_environment first, so this still exercises the header parsers).
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>

#include <OpenImageIO/imageio.h>

#include "fuzz_input_file.h"
#include "relight/image_io.h"
#include "scene_invariants.h"
#include "sh/env_map.h"
#include "sh/projection.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  static const char* const kExtensions[] = {".hdr", ".exr", ".pfm"};
  const uint8_t selector = data[0];
  const std::string path =
      prt::fuzz::write_scratch_file(kExtensions[selector % 3], data + 1, size - 1);
  std::optional<sh::EnvLayout> layout;
  switch ((selector / 3) % 5) {
    case 1:
      layout = sh::EnvLayout::LatLong;
      break;
    case 2:
      layout = sh::EnvLayout::Angular;
      break;
    case 3:
      layout = sh::EnvLayout::Cross;
      break;
    case 4:
      layout = sh::EnvLayout::Faces;
      break;
    default:
      break;  // guessed from the aspect ratio
  }
  // Decoding a header that claims a gigantic image would allocate it (read_environment has no
  // size cap: 8192×4096 maps are legitimate); keep the fuzzer inside its memory limit.
  constexpr long long kMaxFuzzTexels = 1 << 20;
  if (auto in = OIIO::ImageInput::open(path)) {
    const OIIO::ImageSpec& spec = in->spec();
    if (static_cast<long long>(spec.width) * spec.height * std::max(spec.nchannels, 1) *
            std::max(spec.depth, 1) >
        3 * kMaxFuzzTexels)
      return 0;
  }
  sh::EnvMap env;
  try {
    env = prt::relight::read_environment(path, layout);
  } catch (const std::runtime_error& e) {
    prt::fuzz::check_one_line_message(e.what());
    return 0;
  }
  std::string why;
  if (!sh::validate_layout(env.layout, env.width, env.height, &why)) std::abort();
  if (env.rgb.size() != static_cast<std::size_t>(env.width) * env.height * 3) std::abort();
  sh::ProjectionStats stats;
  const std::vector<double> c = sh::project(env, 3, &stats);
  if (c.size() != 27) std::abort();
  for (double v : c)
    if (!std::isfinite(v)) {
      // Only finite texels are summed; finite floats can still overflow a double sum only
      // beyond ~1e308, impossible for float inputs times solid angles ≤ 4π.
      std::abort();
    }
  return 0;
}
