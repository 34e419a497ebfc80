// prt/formats/coefficient_file.h — one way to open any coefficient file the prt tools write,
// whatever its kind: SH transfer (unshadowed, shadowed, interreflected;
// prt/formats/transfer_file.h) or all-frequency Haar-wavelet transfer
// (prt/formats/haar_transfer_file.h). The container is the same (docs/FORMAT.md); the header's kind
// says which payload follows.
//
//   prt::Result<prt::CoefficientFile> file = prt::read_coefficient_file("scene.prt");
//   if (!file.ok()) { /* file.status().message(): "scene.prt: problem" */ }
//   else if (file.value().haar) { /* Haar: prt::HaarRelighter(std::move(*file.value().haar)) */ }
//   else { /* SH: prt::Relighter over file.value().data */ }
//
// Nothing here throws: errors are one-line "PATH: problem" Statuses. Compiles as C++17.
#pragma once

#include <optional>
#include <string>

#include "prt/core/status.h"
#include "prt/formats/transfer_data.h"
#include "prt/haar/transfer.h"

namespace prt {

struct CoefficientFile {
  // Every kind: the header, geometry, primitives, AO, bent normals and metadata. SH kinds hold
  // their coefficients here too; for kind Haar `order` is the cube size N and `coefficients`
  // is empty.
  TransferData data;
  // Kind Haar only: the sparse wavelet transfer.
  std::optional<HaarTransfer> haar;
};

// Reads and fully validates a coefficient file of any kind (all the checks of
// read_transfer_file or read_haar_transfer_file).
Result<CoefficientFile> read_coefficient_file(const std::string& path);

}  // namespace prt
