// scene/src/gltf_extensions.h (private) — which glTF extensions prt can honour.
//
// A glTF file lists in extensionsRequired the extensions a loader must understand to read it
// correctly (glTF 2.0 §3.12): compressed geometry (KHR_draco_mesh_compression,
// EXT_meshopt_compression), quantized attributes (KHR_mesh_quantization), instancing, texture
// formats and so on. prt reads float geometry, node transforms, perspective cameras and the base
// colour; a required extension outside kIgnorableExtensions would be misread (or fail later with
// a message about accessors that names no cause), so the file is refused up front, naming it.
// kIgnorableExtensions are those prt reads (KHR_materials_anisotropy, _ior, _specular,
// _emissive_strength: scene/src/gltf_materials.h, gltf_emission.h) or that change only what prt
// does not model (other shading layers, lights, metadata), so prt reads such a file correctly
// for what it computes.
// Extensions only in extensionsUsed have a fallback in the file (the spec requires it) and are
// fine; those outside kIgnorableExtensions get a one-line note on stderr.
#pragma once

#include <string>
#include <vector>

namespace prt::scene::detail {

// Extensions prt reads, or that change nothing prt reads.
extern const std::vector<std::string> kIgnorableExtensions;

// Throws SceneError("PATH: requires glTF extension NAME, which prt cannot read") for the first
// required extension outside kIgnorableExtensions (all of them listed when several are).
void check_required_extensions(const std::string& path, const std::vector<std::string>& required);

// Prints "PATH: note: ..." to stderr for used (not required) extensions outside
// kIgnorableExtensions; prints nothing when there are none.
void note_optional_extensions(const std::string& path, const std::vector<std::string>& used,
                              const std::vector<std::string>& required);

}  // namespace prt::scene::detail
