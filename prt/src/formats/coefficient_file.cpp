// prt/src/formats/coefficient_file.cpp — the reader of every coefficient-file kind
// (prt/formats/coefficient_file.h).
#include "prt/formats/coefficient_file.h"

#include <utility>

#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/transfer_file.h"

namespace prt {

Result<CoefficientFile> read_coefficient_file(const std::string& path) {
  CoefficientFile file;
  if (is_haar_transfer_file(path)) {
    Result<HaarTransferFile> haar = read_haar_transfer_file(path);
    if (!haar.ok()) return haar.status();
    file.data = std::move(haar.value().info);
    file.haar = std::move(haar.value().transfer);
    return file;
  }
  Result<TransferData> sh = read_transfer_file(path);
  if (!sh.ok()) return sh.status();
  file.data = std::move(sh.value());
  return file;
}

}  // namespace prt
