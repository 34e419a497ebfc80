// cli/view/request_target.cpp — the refusals of request_target.h.
#include "request_target.h"

namespace prt::cli::view {
namespace {

bool is_path_byte(char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
         c == '_' || c == '/' || c == '-';
}

TargetDecision refuse(int status, std::string reason) {
  TargetDecision d;
  d.status = status;
  d.reason = std::move(reason);
  return d;
}

}  // namespace

TargetDecision check_request(const std::string& method, const std::string& raw_target) {
  if (method != "GET") return refuse(405, "method " + method + " is not allowed (GET only)");
  if (raw_target.empty() || raw_target[0] != '/')
    return refuse(400, "the request target is not a path starting with '/'");
  const std::size_t question = raw_target.find('?');
  const std::string path = raw_target.substr(0, question);
  if (question != std::string::npos) {
    for (std::size_t i = question + 1; i < raw_target.size(); ++i) {
      const unsigned char c = static_cast<unsigned char>(raw_target[i]);
      if (c <= 0x20 || c >= 0x7f) return refuse(400, "the query holds a space or a control byte");
    }
  }
  if (path.find('%') != std::string::npos)
    return refuse(400, "percent-encoded paths are refused (no route needs one)");
  if (path.find('\\') != std::string::npos) return refuse(400, "backslashes are refused");
  if (path.find("..") != std::string::npos) return refuse(400, "'..' in a path is refused");
  if (path.find("//") != std::string::npos) return refuse(400, "empty path segments are refused");
  for (char c : path)
    if (!is_path_byte(c)) return refuse(400, "the path holds a byte outside [A-Za-z0-9._/-]");
  TargetDecision ok;
  ok.path = path;
  return ok;
}

}  // namespace prt::cli::view
