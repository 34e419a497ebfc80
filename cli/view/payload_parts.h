// cli/view/payload_parts.h — the parts of `prt view`'s payload that every basis shares (the mesh,
// the environment and background, the camera, the automatic exposure, the manifest's common
// fields, the memory charged; view_payload.cpp builds them), for the payloads of the other bases
// (haar_payload.h, glossy_payload.h). Layouts are those of view_payload.h.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/formats/transfer_data.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/auto_camera.h"
#include "relight/shown_window.h"
#include "scene/scene.h"
#include "sh/env_map.h"
#include "view_payload.h"

namespace prt::cli::view {

// Charges `bytes` for the payload part `what` to inputs.budget (none: nothing) before the part is
// built; throws prt::MemoryBudgetExceeded (one line naming the transfer file, the part, the total
// and the limit) when they do not fit. The payloads are held for as long as `prt view` serves.
void charge_payload(const ViewInputs& inputs, std::uint64_t bytes, const std::string& what);
// mesh.bin (positions, normals, albedo, AO and bent normals when `data` has them, indices),
// charged; records the sections in *sections.
std::vector<std::uint8_t> payload_mesh_bytes(const ViewInputs& inputs, const scene::Scene& scene,
                                             const prt::TransferData& data,
                                             nlohmann::json* sections);
// The map the scene is lit with: inputs.environment_path read and checked (for SH order
// `sh_order`; 0: not projected to SH), or uniform radiance 1 without one.
sh::EnvMap payload_environment(const ViewInputs& inputs, int sh_order);
// The automatic exposure of `prt relight`'s first frame for this vertex radiance.
float payload_automatic_exposure(std::vector<float> radiance, const scene::Scene& scene,
                                 bool albedo_folded);
// The manifest's fields of every basis: format, scene, transfer_file, environment, kind, order,
// channels, albedo_folded, vertex_count, triangle_count.
nlohmann::json payload_manifest_head(const ViewInputs& inputs, const scene::Scene& scene,
                                     const std::string& kind, int order, int channels,
                                     bool albedo_folded);
// The manifest's "lighting" (the unwindowed SH coefficients) and "window" (the choice of
// `prt relight --window auto`, its note).
void add_payload_lighting(const prt::ShLighting& unwindowed,
                          const relight::ShownWindowChoice& choice, const std::string& note,
                          nlohmann::json* manifest);
// The manifest's "exposure_ev", "camera" and "background", and payload->environment (charged).
void add_payload_view(const ViewInputs& inputs, const sh::EnvMap& env, float exposure,
                      const relight::CameraChoice& camera, nlohmann::json* manifest,
                      ViewPayload* payload);
// "+1.50 EV": an exposure as the terminal's summary and the page show it.
std::string payload_exposure_text(float ev);

}  // namespace prt::cli::view
