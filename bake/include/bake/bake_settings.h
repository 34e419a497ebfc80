// bake/bake_settings.h — the canonical settings of a bake: every option of BakeOptions,
// HaarBakeOptions and GlossyBakeOptions that changes the bytes of the output, as one JSON
// object (UTF-8 text, keys in a fixed order), and the options rebuilt from it.
//
// One table per options struct lists every member either as carried (a JSON key) or as not
// carried, with the reason (run settings: threads, memory limit; the seed, which part files keep
// apart; what a sharded bake refuses). A static_assert compares the table's length with the
// struct's member count (bake/src/aggregate_fields.h), so a member added to an options struct
// without a line in its table does not compile: a farm merge cannot silently drop an option.
// The part files (bake/transfer_part_file.h) store these settings and compare them between
// parts; `prt merge` bakes with the options rebuilt from them.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bake/glossy_transfer_baker.h"
#include "bake/haar_baker.h"
#include "bake/subsurface/subsurface_baker.h"
#include "bake/transfer_baker.h"

namespace prt::bake {

// {"basis": "sh", "transfer", "order", …}: the carried members of `o`.
std::string sh_bake_settings(const BakeOptions& o);
// The options `settings` describes, with `seed`; members not carried keep their defaults.
// Throws BakeError "what: problem" when a key is missing or of the wrong type.
BakeOptions sh_options_from_settings(const std::string& settings, uint64_t seed,
                                     const std::string& what);

std::string haar_bake_settings(const HaarBakeOptions& o);  // "basis": "haar"
HaarBakeOptions haar_options_from_settings(const std::string& settings, uint64_t seed,
                                           const std::string& what);

std::string glossy_bake_settings(const GlossyBakeOptions& o);  // "basis": "glossy"
GlossyBakeOptions glossy_options_from_settings(const std::string& settings, uint64_t seed,
                                               const std::string& what);

// {"materials": [{"sigma_a", "sigma_s_prime", "eta"}, …], "mm_per_unit", "gather": {…}}: the
// carried members of a subsurface bake's options (SH parts of `--subsurface` hold it under the
// key "subsurface" of their settings). vertex_material is not carried here: one value per
// vertex, shard 0 stores it and every part hashes it (bake/transfer_part_file.h).
std::string subsurface_bake_settings(const SubsurfaceBakeOptions& o);
SubsurfaceBakeOptions subsurface_options_from_settings(const std::string& settings,
                                                       const std::string& what);

// The names of the members the tables do not carry, "member: why", for the tests and docs.
std::vector<std::string> settings_not_carried();

}  // namespace prt::bake
