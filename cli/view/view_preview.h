// cli/view/view_preview.h — a coarse copy of the scene for the page's first frame, so that a
// large scene shows at once while its full payloads are still on the way.
//
// Vertex clustering (Rossignac and Borrel, "Multi-resolution 3D approximations for rendering
// complex scenes", 1993): space is cut into cubic cells of one size, and the vertices of a cell
// whose normals point the same way (the same dominant axis and sign: a box's faces stay apart)
// become one preview vertex: the scene vertex nearest to their mean. A preview vertex is thus a
// scene vertex, with its own transfer, so the preview is shaded exactly at its vertices; only the
// triangles in between are coarser. Triangles keep their three clusters' vertices in order and
// are dropped when two fall into one cluster; duplicates are dropped. The cell size is chosen
// from the surface area so that about `target_vertices` cells are occupied.
//
// Deterministic: the same scene gives the same preview (clusters are numbered in vertex order).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <nlohmann/json.hpp>

#include "prt/formats/transfer_data.h"
#include "scene/scene.h"

namespace prt::cli::view {

struct PreviewMesh {
  std::vector<std::uint32_t> source_vertex;  // per preview vertex: the scene vertex it is
  std::vector<std::uint32_t> indices;        // 3 per triangle, into source_vertex
  double cell_size = 0.0;                    // the clustering's cell edge, scene units
};

// Throws std::invalid_argument when target_vertices is 0.
PreviewMesh build_preview_mesh(const scene::Scene& scene, std::size_t target_vertices);

// Scenes above this many vertices get a preview of kPreviewVertices (about) in the manifest.
constexpr std::size_t kPreviewMinVertices = 200000;
constexpr std::size_t kPreviewVertices = 65536;

// preview.bin, laid out as mesh.bin and transfer.bin together (view_payload.h), for the preview
// vertices: float32 sections "positions", "normals", "albedo" (3 per vertex), uint32 "indices",
// then float16 "transfer" texels of an RGBA texture (the layout of transfer.bin, vertex i of the
// preview owning texels i·P .. i·P+P−1). `manifest` receives url, counts, sections and the
// texture's layout.
std::vector<std::uint8_t> preview_bytes(const scene::Scene& scene, const prt::TransferData& data,
                                        const PreviewMesh& preview, nlohmann::json* manifest);

}  // namespace prt::cli::view
