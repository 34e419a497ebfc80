// fuzz/fuzz_env_map_exr.cpp — libFuzzer target: the OpenImageIO part of the environment-map path,
// EXR bytes → scratch file "….exr" → relight::read_image (OpenImageIO's OpenEXR reader only, no
// probing of other plugins) → relight::to_environment (layout guessed or forced) →
// prt::sh::validate_layout → prt::sh::project.
//
// Input: byte 0 picks the layout ((b % 5): guessed, latlong, angular, cross, faces); the rest is
// the file. A hostile file must be refused with a one-line std::runtime_error "PATH: ..." or give
// a map whose projection is finite over the texels it used. Images over kMaxFuzzTexels are
// refused by read_image's size cap. read_image checks EXR headers itself first
// (relight/exr_header_check.h), because OpenEXR 3.1 allocates what a header claims (a 1.9 GB
// string attribute in a 94-byte file, line buffers for a 7.6-million-pixel-wide window: both
// found by this target, the second a 10 s timeout under ASan). scripts/fuzz.sh still gives this
// target a larger RSS limit for whatever the check does not foresee. Its third finding, a bad
// line-offset table that made OpenImageIO 2.4's IOMemReader read before its buffer, is why
// read_image lets OpenEXR read EXR files from disk. fuzz/corpus/fuzz_env_map_exr/regression_*
// are the three findings, replayed by every run and by tests/relight/test_hdr_decoders.cpp.
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

#include <OpenImageIO/imageio.h>

#include "fuzz_input_file.h"
#include "relight/image_io.h"
#include "sh/env_map.h"
#include "sh/projection.h"

namespace {

constexpr std::size_t kMaxFuzzTexels = std::size_t{1} << 16;

void check_error(const char* message, const std::string& path) {
  if (message == nullptr || std::strncmp(message, path.c_str(), path.size()) != 0 ||
      std::strncmp(message + path.size(), ": ", 2) != 0 || message[path.size() + 2] == '\0' ||
      std::strchr(message, '\n') != nullptr)
    std::abort();
}

}  // namespace

// One thread for OpenImageIO and OpenEXR: their pools would otherwise start and stop worker
// threads around every tiny file, which is most of a run's time (prt's own reads are unchanged).
extern "C" int LLVMFuzzerInitialize(int*, char***) {
  OIIO::attribute("threads", 1);
  OIIO::attribute("exr_threads", 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t selector = data[0];
  std::optional<prt::sh::EnvLayout> layout;
  switch (selector % 5) {
    case 1:
      layout = prt::sh::EnvLayout::LatLong;
      break;
    case 2:
      layout = prt::sh::EnvLayout::Angular;
      break;
    case 3:
      layout = prt::sh::EnvLayout::Cross;
      break;
    case 4:
      layout = prt::sh::EnvLayout::Faces;
      break;
    default:
      break;  // guessed from the aspect ratio
  }
  const std::string path = prt::fuzz::write_scratch_file(".exr", data + 1, size - 1);
  prt::sh::EnvMap env;
  try {
    env =
        prt::relight::to_environment(prt::relight::read_image(path, kMaxFuzzTexels), path, layout);
  } catch (const std::runtime_error& e) {
    check_error(e.what(), path);
    return 0;
  }
  std::string why;
  if (!prt::sh::validate_layout(env.layout, env.width, env.height, &why)) std::abort();
  if (env.rgb.size() != static_cast<std::size_t>(env.width) * env.height * 3) std::abort();
  prt::sh::ProjectionStats stats;
  const std::vector<double> c = prt::sh::project(env, 3, &stats);
  if (c.size() != 27) std::abort();
  for (double v : c)
    if (!std::isfinite(v)) std::abort();
  return 0;
}
