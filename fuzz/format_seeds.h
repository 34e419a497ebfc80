// fuzz/format_seeds.h — seed corpora of the fuzz targets of prt's binary formats and textures,
// written with the project's own writers (make_fuzz_corpus calls it). Each seed is a small valid
// file (a few hundred bytes to a few KB) that the target's reader accepts.
#pragma once

#include <filesystem>

namespace prt::fuzz {

// Writes OUT/fuzz_glossy_file, fuzz_cpca_file, fuzz_emitter_responses, fuzz_haar_file,
// fuzz_form_factor_cache, fuzz_merl_brdf, fuzz_texture, fuzz_link_cache and fuzz_part_file
// (creating the folders). Throws
// std::runtime_error when a writer fails.
void write_format_seeds(const std::filesystem::path& out);

}  // namespace prt::fuzz
