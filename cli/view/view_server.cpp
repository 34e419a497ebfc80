// cli/view/view_server.cpp — view_server.h on cpp-httplib (its pre-routing hook answers every
// request, so httplib's own routing, file mounts and methods are never used).
#include "view_server.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include <httplib.h>

#include "request_target.h"

namespace prt::cli::view {
namespace {

std::string content_type_for(const std::filesystem::path& path) {
  const std::string ext = path.extension().string();
  if (ext == ".html") return "text/html; charset=utf-8";
  if (ext == ".js" || ext == ".mjs") return "text/javascript; charset=utf-8";
  if (ext == ".json") return "application/json";
  if (ext == ".css") return "text/css; charset=utf-8";
  if (ext == ".png") return "image/png";
  if (ext == ".md" || ext == ".txt") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

std::shared_ptr<const std::vector<std::uint8_t>> read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot be read");
  auto bytes = std::make_shared<std::vector<std::uint8_t>>(std::istreambuf_iterator<char>(in),
                                                           std::istreambuf_iterator<char>());
  return bytes;
}

std::shared_ptr<const std::vector<std::uint8_t>> share(std::vector<std::uint8_t> bytes) {
  return std::make_shared<const std::vector<std::uint8_t>>(std::move(bytes));
}

// Host header check for a loopback server: "127.0.0.1:PORT", "localhost:PORT", "[::1]:PORT".
bool host_allowed(const std::string& bound, int port, const std::string& host_header) {
  if (bound != "127.0.0.1" && bound != "localhost" && bound != "::1") return true;
  const std::string p = std::to_string(port);
  for (const char* name : {"127.0.0.1", "localhost", "[::1]"})
    if (host_header == std::string(name).append(":").append(p)) return true;
  return false;
}

}  // namespace

std::map<std::string, Route> asset_routes(const std::string& web_dir) {
  namespace fs = std::filesystem;
  const fs::path root(web_dir);
  std::error_code ec;
  if (!fs::is_regular_file(root / "index.html", ec))
    throw std::runtime_error("the web assets were not built (" + (root / "index.html").string() +
                             " is missing): install node and three.js with "
                             "scripts/install-deps.sh, then configure and build again");
  std::map<std::string, Route> routes;
  for (const fs::directory_entry& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = fs::relative(entry.path(), root).generic_string();
    const std::string url = relative == "index.html" ? "/" : "/" + relative;
    if (check_request("GET", url).status != 200) continue;  // a name no request may use
    routes[url] = {content_type_for(entry.path()), read_bytes(entry.path())};
  }
  return routes;
}

void add_payload_routes(ViewPayload payload, std::map<std::string, Route>* routes) {
  const std::string manifest = payload.manifest_json;
  (*routes)["/api/manifest.json"] = {"application/json", share({manifest.begin(), manifest.end()})};
  (*routes)["/api/mesh.bin"] = {"application/octet-stream", share(std::move(payload.mesh))};
  (*routes)["/api/transfer.bin"] = {"application/octet-stream", share(std::move(payload.transfer))};
  (*routes)["/api/environment.bin"] = {"application/octet-stream",
                                       share(std::move(payload.environment))};
  for (std::size_t i = 0; i < payload.also.size(); ++i)
    (*routes)["/api/also" + std::to_string(i) + ".bin"] = {"application/octet-stream",
                                                           share(std::move(payload.also[i]))};
  if (!payload.glossy.empty())
    (*routes)["/api/glossy.bin"] = {"application/octet-stream", share(std::move(payload.glossy))};
  if (!payload.preview.empty())
    (*routes)["/api/preview.bin"] = {"application/octet-stream", share(std::move(payload.preview))};
  if (!payload.emitters.empty())
    (*routes)["/api/emitters.bin"] = {"application/octet-stream",
                                      share(std::move(payload.emitters))};
}

struct ViewServer::Impl {
  httplib::Server server;
};

ViewServer::ViewServer(std::map<std::string, Route> routes)
    : impl_(std::make_unique<Impl>()), routes_(std::move(routes)) {}

ViewServer::~ViewServer() = default;

int ViewServer::bind(const std::string& host, int port) {
  host_ = host;
  port_ = port == 0 ? impl_->server.bind_to_any_port(host) : port;
  if (port != 0 && !impl_->server.bind_to_port(host, port)) port_ = -1;
  if (port_ < 0)
    throw std::runtime_error("cannot listen on " + host + ":" + std::to_string(port) +
                             " (in use, or not an address of this machine)");
  return port_;
}

void ViewServer::serve(std::function<void(const std::string&)> log) {
  const auto refuse = [log](httplib::Response& res, int status, const std::string& why,
                            const httplib::Request& req) {
    res.status = status;
    if (status == 405) res.set_header("Allow", "GET");
    res.set_content(why + "\n", "text/plain; charset=utf-8");
    if (log) log(std::to_string(status) + " " + req.method + " " + req.target + ": " + why);
  };
  impl_->server.set_pre_routing_handler(
      [this, refuse](const httplib::Request& req, httplib::Response& res) {
        const TargetDecision d =
            decide_request(req.method, req.target,
                           [this](const std::string& path) { return routes_.count(path) > 0; });
        if (d.status != 200) {
          refuse(res, d.status, d.reason, req);
        } else if (!host_allowed(host_, port_, req.get_header_value("Host"))) {
          refuse(res, 400, "the Host header names another server", req);
        } else {
          const Route& route = routes_.at(d.path);
          res.status = 200;
          res.set_header("Cache-Control", "no-store");
          res.set_header("X-Content-Type-Options", "nosniff");
          const auto body = route.body;
          res.set_content_provider(
              body->size(), route.content_type,
              [body](std::size_t offset, std::size_t length, httplib::DataSink& sink) {
                const std::size_t n = std::min<std::size_t>(length, 1 << 20);
                sink.write(reinterpret_cast<const char*>(body->data()) + offset, n);
                return true;
              });
        }
        return httplib::Server::HandlerResponse::Handled;
      });
  impl_->server.listen_after_bind();
}

void ViewServer::stop() {
  impl_->server.stop();
}

}  // namespace prt::cli::view
