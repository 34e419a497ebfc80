// fuzz/one_line_error.h — the error rule every reader follows (docs/STABILITY.md): one line that
// starts with NAME (the file's path or the name given for a memory buffer) and says the problem:
// "NAME: problem" or, for a part of the file, "NAME (part): problem". A violation aborts (a
// finding for the fuzzer).
#pragma once

#include <cstdlib>
#include <string>

namespace prt::fuzz {

// Whether `message` follows the rule for `name`.
inline bool is_one_line_error(const std::string& message, const std::string& name) {
  return message.compare(0, name.size(), name) == 0 && message.size() > name.size() + 2 &&
         (message.compare(name.size(), 2, ": ") == 0 ||
          message.compare(name.size(), 2, " (") == 0) &&
         message.find('\n') == std::string::npos && message.find('\r') == std::string::npos;
}

inline void check_one_line_error(const std::string& message, const std::string& name) {
  if (!is_one_line_error(message, name)) std::abort();
}

}  // namespace prt::fuzz
