// tests/support/error_message.h — the message a call throws, for tests of one-line errors.
#pragma once

#include <stdexcept>
#include <string>

namespace prt::test {

// The message of the std::runtime_error thrown by `call` ("" if nothing was thrown).
template <typename Call>
std::string error_of(Call call) {
  try {
    call();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

}  // namespace prt::test
