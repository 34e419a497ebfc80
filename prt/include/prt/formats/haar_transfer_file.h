// prt/formats/haar_transfer_file.h — reading and writing all-frequency (Haar-wavelet) transfer in
// the coefficient-file container (docs/FORMAT.md, "Haar-wavelet transfer", kind 3).
//
// The file is the same container as SH transfer (magic "PRTC", version 1, CRC-32C, 16-byte
// aligned sections, positions/normals/primitives/AO/metadata as for SH); for kind Haar the
// header's `order` field holds the cube size N, the `storage` field the quantisation bits
// (32 f32, 16 i16, 8 i8), and the coefficient section holds the sparse transport matrix of
// prt/haar/transfer.h ("for each lighting coefficient, the list of vertices that have it",
// Ng, Ramamoorthi & Hanrahan, SIGGRAPH 2003, Sec. 5) with per-vertex dequantisation steps.
// Wavelet indices i = face·N² + q (prt/haar/transform.h); cube conventions of
// prt/haar/cube_map.h (glTF frame, +Y up). Exit radiance B_v,c = Σ_i T̂_v,i,c · L̂_i,c with
// L̂ the Haar coefficients of the lighting's radiance; T includes albedo/π when
// info.albedo_folded.
//
// The whole path file → HaarRelighter needs nothing but prt::prt:
//   auto file = prt::read_haar_transfer_file("scene.prt");
//   prt::HaarRelighter relighter(std::move(file.value().transfer));
// Nothing here throws: errors are one-line "NAME: problem" Statuses. Compiles as C++17.
// References: [4] of docs/REFERENCES.md.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "prt/core/status.h"
#include "prt/formats/transfer_data.h"
#include "prt/haar/transfer.h"

namespace prt {

// A Haar coefficient file in memory: `info` carries everything but the transfer (kind Haar,
// order = cube size, channels, positions, normals, primitives, AO, bent normals, metadata;
// info.coefficients is empty), `transfer` the sparse matrix.
struct HaarTransferFile {
  TransferData info;
  HaarTransfer transfer;
};

// Checks info (as validate_transfer_data does for the shared fields; kind must be Haar,
// order == transfer.size, channels == transfer.channels, vertex_count equal) and the transfer
// (offsets, ascending vertex lists, quantised values within ±Q, finite values and steps).
Status validate_haar_transfer_file(const HaarTransferFile& file, const std::string& name);

// Encodes / writes (atomically: PATH.tmp-<pid> then rename) a Haar coefficient file.
Result<std::vector<unsigned char>> encode_haar_transfer_file(const HaarTransferFile& file,
                                                             const std::string& name);
Status write_haar_transfer_file(const std::string& path, const HaarTransferFile& file);

// Reads and fully validates a Haar coefficient file (container checks of docs/FORMAT.md, then
// the payload). A file of another kind is refused with a message naming read_transfer_file.
Result<HaarTransferFile> read_haar_transfer_data(const void* bytes, std::size_t size,
                                                 const std::string& name);
Result<HaarTransferFile> read_haar_transfer_file(const std::string& path);

// True when the file at `path` is a coefficient file of kind Haar (reads the header only; no
// validation: false for unreadable or foreign files).
bool is_haar_transfer_file(const std::string& path) noexcept;

}  // namespace prt
