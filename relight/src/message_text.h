// relight/src/message_text.h (private) — file content quoted safely inside a one-line error
// message: the decoders (radiance_hdr.cpp, pfm_image.cpp, exr_header_check.cpp) name the header
// text they refuse, which may be binary.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace prt::relight::detail {

// `text` in double quotes, printable ASCII only (others become '?'), cut to max_chars with "...".
inline std::string quoted(std::string_view text, std::size_t max_chars) {
  std::string out = "\"";
  for (std::size_t i = 0; i < text.size() && i < max_chars; ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    out += (c >= 0x20 && c < 0x7f) ? static_cast<char>(c) : '?';
  }
  if (text.size() > max_chars) out += "...";
  return out + "\"";
}

}  // namespace prt::relight::detail
