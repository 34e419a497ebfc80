// cli/view/request_target.h — which HTTP requests `prt view` answers, decided from the raw
// request line alone, before any route is looked up.
//
// The server serves a fixed table of routes (view_server.h): the page's own files and the
// payloads built from the files the command was given. No request names a file on disk, so
// path traversal cannot reach one; still, every form of it is refused explicitly (and tested),
// so that a later change to the table cannot open one:
//   * any method but GET: 405 (HEAD included; methods that HTTP does not define are refused
//     with 400 by the HTTP library's request-line parser before they reach this check);
//   * a target that is not origin-form ("/path[?query]"), or whose path holds "..", "//", a
//     backslash, a percent sign (every encoded form: %2e%2e, %2f, %5c, double-encoded %252e),
//     or any byte outside [A-Za-z0-9._/-]: 400;
//   * a path that is not a route: 404.
// The query string is not interpreted by the server (the page reads it in the browser) but must
// hold printable ASCII only (no spaces or control bytes).
#pragma once

#include <string>

namespace prt::cli::view {

struct TargetDecision {
  int status = 200;    // 200, 400, 404 or 405
  std::string path;    // the route's path when status is 200 (query removed)
  std::string reason;  // one line for the log and the response body when status != 200
};

// `is_route(path)` tells whether a clean path is in the route table.
template <class IsRoute>
TargetDecision decide_request(const std::string& method, const std::string& raw_target,
                              IsRoute is_route);

// The checks above without the route lookup: status 200 (clean), 400 or 405.
TargetDecision check_request(const std::string& method, const std::string& raw_target);

template <class IsRoute>
TargetDecision decide_request(const std::string& method, const std::string& raw_target,
                              IsRoute is_route) {
  TargetDecision decision = check_request(method, raw_target);
  if (decision.status == 200 && !is_route(decision.path)) {
    decision.status = 404;
    decision.reason = "no such route: " + decision.path;
  }
  return decision;
}

}  // namespace prt::cli::view
