// cli/input_files.h — every file a command reads for one input argument, so that an output can
// be refused when it is any of them (output_safety.h).
//
//   scene_files        the scene itself, plus what it refers to: a glTF's (.gltf, .glb)
//                      external buffers and images (buffers[].uri, images[].uri; data: URIs
//                      are embedded; %XX escapes decoded), an OBJ's `mtllib` files and the
//                      texture maps those name (map_*, bump, disp, decal, norm, refl: the last
//                      token of the line). Paths are relative to the referring file's folder.
//   environment_files  the map, or the six faces of a pattern with %s (px, nx, py, ny, pz, nz;
//                      relight/image_io.h).
//
// Discovery is best effort and never fails: a file that cannot be read or parsed contributes
// only itself (its loader reports the problem later, with its own message).
#pragma once

#include <string>
#include <vector>

namespace prt::cli {

std::vector<std::string> scene_files(const std::string& scene_path);

std::vector<std::string> environment_files(const std::string& environment_path);

}  // namespace prt::cli
