// cli/view/view_server.h — the HTTP server of `prt view`: a fixed table of routes, nothing else.
//
// Routes (all GET; request_target.h refuses every other request before the table is read):
//   /                      the page, web/index.html of the build tree's web assets
//   /NAME                  each other file of the web assets (the page's modules and the
//                          three.js files copied there at build time), by its relative path
//   /api/manifest.json     the manifest of view_payload.h
//   /api/mesh.bin, /api/transfer.bin, /api/environment.bin   the payloads of view_payload.h
//   /api/glossy.bin        glossy files only: frames, CPCA weights, b nodes (glossy_payload.h)
//   (and /api/preview.bin, /api/emitters.bin when the payload has them)
//   /api/also0.bin, /api/also1.bin, ...   prt view --also: the transfer payload of each further
//                          file, in the order given (a number, never a name, picks one)
// The table is built once, at start-up, from the payload and the asset files read into memory;
// no request reaches the file system. Bodies are streamed from memory (binary payloads are sent
// as they are, never turned into JSON). Requests whose Host header names neither the bound
// address nor localhost are refused with 400 when the server listens on loopback (a web page
// elsewhere cannot reach the viewer through DNS rebinding).
// The server binds `host` (127.0.0.1 unless the user says otherwise) and `port` (0: a free port
// chosen by the system; port() tells which).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "view_payload.h"

namespace prt::cli::view {

struct Route {
  std::string content_type;
  std::shared_ptr<const std::vector<std::uint8_t>> body;
};

// The routes of the web assets under `web_dir` ("/" for index.html). Throws std::runtime_error
// "prt view: ..." when index.html is missing (the assets were not built).
std::map<std::string, Route> asset_routes(const std::string& web_dir);

// Adds the /api/ routes of `payload`.
void add_payload_routes(ViewPayload payload, std::map<std::string, Route>* routes);

class ViewServer {
 public:
  explicit ViewServer(std::map<std::string, Route> routes);
  ~ViewServer();
  ViewServer(const ViewServer&) = delete;
  ViewServer& operator=(const ViewServer&) = delete;

  // Binds host:port; throws std::runtime_error (one line) when it cannot. Returns the port.
  int bind(const std::string& host, int port);
  int port() const { return port_; }
  // Serves until stop() (from another thread or a signal handler's thread). `log` (optional)
  // receives one line per refused request.
  void serve(std::function<void(const std::string&)> log = {});
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::map<std::string, Route> routes_;
  std::string host_;
  int port_ = 0;
};

}  // namespace prt::cli::view
