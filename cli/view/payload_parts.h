// cli/view/payload_parts.h — the parts of `prt view`'s payload that every basis shares (the mesh,
// the background, the camera, the automatic exposure; view_payload.cpp builds them), for the
// payload of another basis (haar_payload.h). Layouts are those of view_payload.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/formats/transfer_data.h"
#include "relight/auto_camera.h"
#include "scene/scene.h"
#include "sh/env_map.h"

namespace prt::cli::view {

// mesh.bin (positions, normals, albedo, AO and bent normals when `data` has them, indices);
// records the sections in *sections.
std::vector<std::uint8_t> payload_mesh_bytes(const scene::Scene& scene,
                                             const prt::TransferData& data,
                                             nlohmann::json* sections);
// environment.bin: the float16 RGBA lat-long background, `width` × width/2.
std::vector<std::uint8_t> payload_environment_bytes(const sh::EnvMap& env, int width);
// The map `prt view` lights with when it is given none: uniform radiance 1.
sh::EnvMap payload_uniform_environment();
// The automatic exposure of `prt relight`'s first frame for this vertex radiance.
float payload_automatic_exposure(std::vector<float> radiance, const scene::Scene& scene,
                                 bool albedo_folded);
// The manifest's "camera".
nlohmann::json payload_camera_json(const relight::CameraChoice& choice, float aspect);

}  // namespace prt::cli::view
