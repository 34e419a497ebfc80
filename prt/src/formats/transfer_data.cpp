// Names of the transfer kinds of a coefficient file (see prt/formats/transfer_data.h).
#include "prt/formats/transfer_data.h"

namespace prt {

const char* transfer_kind_name(TransferKind kind) {
  switch (kind) {
    case TransferKind::Unshadowed:
      return "unshadowed";
    case TransferKind::Shadowed:
      return "shadowed";
    case TransferKind::Interreflected:
      return "interreflected";
    case TransferKind::Haar:
      return "haar";
  }
  return "unknown";
}

}  // namespace prt
