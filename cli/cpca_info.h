// cli/cpca_info.h — CPCA files (.prtq, prt/formats/cpca_file.h) in `prt info`, and the
// compression record `prt compress` stores in them.
//   prt info FILE.prtq          the header, the compression (the relative RMS error it reached,
//                               in the metric it minimised and in the plain matrix metric, and
//                               its settings) and the source bake's settings, as text;
//   prt info FILE.prtq --json   the same as one JSON object ("compression": the record, null for
//                               a version-1 file, which has none; "source_bake": the bake's
//                               metadata, from the record or else from the source section);
//   prt info FILE.prtq --csv    one row per vertex as for .prtg files (index, x, y, z, nx, ny,
//                               nz, tx, ty, tz, tw, material, then m<c>_<i>_<j>), the matrices
//                               reconstructed from the CPCA (μ + Σ_k w_k U_k), with the vertex's
//                               cluster after its material; without a source section only
//                               index, cluster and the matrices.
#pragma once

#include <string>

#include "glossy_cli.h"
#include "prt/glossy/cpca_transfer.h"
#include "prt/glossy/transfer.h"

namespace prt::cli {

// The compression record (JSON text) of a `prt compress` run: its settings, the relative RMS
// errors reached (plain matrix, and in the metric it minimised), the input's name and bytes,
// and the source bake's metadata (the .prtg's metadata object).
std::string make_cpca_record(const GlossyCompressRequest& request,
                             const prt::GlossyTransferData& source, const prt::CpcaTransfer& cpca,
                             double matrix_error, double metric_error);

// `prt info` of a .prtq. Throws CommandError for an unreadable or corrupt file.
void describe_cpca_file(const std::string& path, bool json, bool csv);

}  // namespace prt::cli
