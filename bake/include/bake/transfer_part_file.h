// bake/transfer_part_file.h — a sharded SH bake's part (bake/transfer_part.h) as a part file
// (prt/formats/part_file.h, kind ShTransfer), and the checks that parts belong together.
//
// Sections (tags; docs/FORMAT.md, "Part files"):
//   1 settings   JSON: {"generator", "prt_version", "seed", "settings": {the bake's canonical
//                settings, bake/bake_settings.h: every option that changes the output},
//                "scene_inputs": hex hash of normals, albedo, triangles and primitives}. Parts
//                of one bake have equal settings sections.
//   2 scene      JSON (shard 0 only): source path, skipped triangles, primitives (name, first
//                vertex, vertex count); with sections 3–6 the scene as the bake saw it (after
//                --albedo, --material and --max-edge), so that the merge needs no scene file.
//   3 positions  f32 × 3V   4 normals f32 × 3V   5 albedo f32 × 3V   6 triangles u32 × 3T
//   7 direct     f64 × rows·K (shadowed, interreflected): S_v of bake/transfer_baker.h
//   8 ao         f32 × rows (--ao)            9 bent normals f32 × 3·rows (--bent-normals)
//  10 gather rows u32 × rows (interreflected): hits per row
//  11 gather hits 8 bytes each: u32 triangle (renumbered), u16 u, u16 v (bake/compact_gather.h)
//  12 counters   u64 rays, u64 back-face hits, f64 largest ray offset
// Haar parts (kind HaarTransfer, bake/haar_part.h) have sections 1–6 and 12 as above, and
//  13 sparse lengths u32 × rows, 14 sparse indices u32, 15 sparse values f32 × C per index
//     (unshadowed, shadowed); 16 wavelets f32 × rows·6N²·C, 17 gather lengths u32 × rows,
//  18 gather columns u32, 19 gather weights f32 (interreflected).
// Glossy parts (kind GlossyTransfer, bake/glossy_part.h) have sections 1–6 and 12 as above, and
//  21 direct matrices f32 × rows·K² (K = n²), 22 hit counts u32 × rows and 23 hits, 16 bytes
//     each: u32 sample, u32 triangle, f32 u, f32 v (interreflected); shard 0 also
//  24 tangent frames f32 × 4V, 25 material of each vertex u32 × V, 26 materials JSON (every
//     field of brdf::Material); their hash joins scene_inputs in every part.
// Subsurface parts (`prt bake --subsurface --shard`, bake/subsurface/subsurface_part.h) are SH
// parts whose settings also hold "subsurface" (bake_settings.h: materials, scale, gather), and
//  27 subsurface material of each vertex i32 × V (shard 0; −1 opaque); its hash joins
//     scene_inputs in every part.
// Form-factor parts (kind FormFactorRows, `prt radiosity --shard`) carry no scene: the header's
// fingerprint is the form-factor cache key (radiosity/form_factor_cache.h), its rows the
// senders, section 1's settings the form-factor options, and
//  20 form factors f32 × rows·N (N = total rows, the patch count).
// Rows are those of bake/transfer_part.h (Morton order); the header's fingerprint is
// geometry_fingerprint of the positions, its rows [first_row, first_row + row_count) of V.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bake/glossy_part.h"
#include "bake/haar_part.h"
#include "bake/subsurface/subsurface_baker.h"
#include "bake/transfer_part.h"
#include "prt/formats/part_file.h"
#include "scene/scene.h"

namespace prt::bake {

// A part file's contents, decoded.
struct TransferPartFile {
  std::string name;         // the file, for messages
  std::string prt_version;  // of the prt that wrote it
  uint64_t seed = 0;
  uint64_t fingerprint = 0;  // of the positions
  std::string settings;      // the settings object, canonical JSON (compared between parts)
  std::string scene_inputs;  // hex hash of the scene's normals, albedo, triangles, primitives
  BakeOptions options;       // rebuilt from the settings (threads and memory limit not set)
  // A subsurface bake's part: its options (vertex_material: shard 0 only, else empty).
  std::optional<SubsurfaceBakeOptions> subsurface;
  std::optional<scene::Scene> scene;    // shard 0
  TransferPart part;                    // SH parts; for Haar parts only shard, vertices and rows
  std::shared_ptr<const void> mapping;  // the mapping the parts' views point into
  bool haar = false;                    // a Haar part: the two fields below
  HaarBakeOptions haar_options;
  HaarPart haar_part;
  bool glossy = false;  // a glossy part: the three fields below
  GlossyBakeOptions glossy_options;
  GlossyPart glossy_part;
  std::optional<GlossyInputs> glossy_inputs;  // shard 0
  bool form_factors = false;                  // a form-factor part: `settings` holds the options
  uint64_t key = 0;                           // its cache key (= fingerprint)
  std::vector<float> form_factor_rows;        // rows × N
};

// The part file of `part`, baked from `scene` with `options` by prt `prt_version`. Its large
// sections refer to the arrays of `part` and `scene` (no copy): keep them until it is written.
// With `subsurface`: the part of a subsurface bake (its settings, and the vertices' materials).
prt::PartFile encode_transfer_part(const TransferPart& part, const scene::Scene& scene,
                                   const BakeOptions& options, const std::string& prt_version,
                                   const SubsurfaceBakeOptions* subsurface = nullptr);

// The part file of a Haar bake's part (referring to its arrays, as above).
prt::PartFile encode_haar_part(const HaarPart& part, const scene::Scene& scene,
                               const HaarBakeOptions& options, const std::string& prt_version);

// The part file of a glossy bake's part; `inputs` are glossy_inputs(scene) (every shard hashes
// them into scene_inputs; shard 0 stores them). Refers to the arrays of `part`, `scene` and
// `inputs`, as above.
prt::PartFile encode_glossy_part(const GlossyPart& part, const scene::Scene& scene,
                                 const GlossyInputs& inputs, const GlossyBakeOptions& options,
                                 const std::string& prt_version);

// A form-factor part: rows [first, first + rows.size()/patches) of the `patches` × `patches`
// matrix whose cache key is `key`, computed with the options `settings` (a JSON object).
prt::PartFile encode_form_factor_part(ShardSpec shard, uint64_t key, uint64_t patches,
                                      uint64_t first, const std::vector<float>& rows,
                                      const std::string& settings, uint64_t seed,
                                      const std::string& prt_version);

// The layout id every part this prt writes carries in its header (prt::PartFile::layout): a hash
// of the container's format version, the section tags and the shape (keys, nesting, JSON types)
// of the three settings tables' JSON. A part from a prt whose part layout or settings tables
// differ is refused by decode_transfer_part as "written by another prt version", before its
// settings are compared.
uint64_t part_layout_id();

// Decodes a part file read by prt::read_part_file (first: its layout id, above); throws BakeError
// "NAME: problem" when its sections do not hold what its header and settings say.
TransferPartFile decode_transfer_part(const prt::PartFile& file, const std::string& name);

// Checks that `parts` (any order) are the whole of one bake: the same prt version, scene
// (fingerprint and inputs), seed, settings and shard count, every shard exactly once. Returns
// them in shard order; throws BakeError with one line naming the part that does not fit (the
// parts most of them agree with are taken as the reference) or the shard that is missing.
std::vector<const TransferPartFile*> check_parts_fit(const std::vector<TransferPartFile>& parts);

}  // namespace prt::bake
