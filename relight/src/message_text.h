// relight/src/message_text.h (private) — text made fit for a one-line error message: file
// content quoted safely (the decoders radiance_hdr.cpp, pfm_image.cpp, exr_header_check.cpp name
// the header text they refuse, which may be binary), and other libraries' messages on one line.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace prt::relight::detail {

// `text` on one line: newlines become spaces and trailing blanks go (library messages, such as
// OpenImageIO's, may span several lines).
inline std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n') c = ' ';
  while (!text.empty() && (text.back() == ' ' || text.back() == '\r')) text.pop_back();
  return text;
}

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
