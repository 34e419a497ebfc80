// scene/src/scene_file_errors.h (private) — error messages shared by the scene-file readers and
// writer (gltf_loader.cpp, obj_loader.cpp, glb_writer.cpp).
//
// Every error is thrown as SceneError with one line "PATH: problem"; messages that come from a
// parser library (which may span several lines) are condensed to one line first.
#pragma once

#include <sstream>
#include <string>

#include "scene/scene.h"

namespace prt::scene::detail {

// Throws SceneError("PATH: problem").
[[noreturn]] inline void fail(const std::string& path, const std::string& problem) {
  throw SceneError(path + ": " + problem);
}

// Joins the non-empty lines of a multi-line message with "; " (messages must be one line);
// trailing spaces and carriage returns of each line are dropped.
inline std::string condense(const std::string& text) {
  std::string out, line;
  std::istringstream in(text);
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (line.empty()) continue;
    if (!out.empty()) out += "; ";
    out += line;
  }
  return out;
}

}  // namespace prt::scene::detail
