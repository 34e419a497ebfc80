// `prt view SCENE FILE.prt|.prtg|.prtq [ENV] [--also OTHER.prt]... [--port N] [--listen ADDR]
// [--memory-limit SIZE]`:
// serve a browser page that relights the scene on the GPU (web/, docs/VIEWER.md). The page, the
// payloads and the server's refusals are cli/view/ (view_payload.h, view_server.h,
// request_target.h); this file maps the arguments.
#include <pthread.h>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "command_registry.h"
#include "option_rules.h"
#include "output_safety.h"
#include "prt/core/memory_budget.h"
#include "view/view_payload.h"
#include "view/view_server.h"

namespace prt::cli {
namespace {

struct ViewArguments {
  std::string scene, transfer, environment;
  int port = 8765;
  std::string listen = "127.0.0.1";
  std::string emitters;            // --emitters R.prte
  std::optional<double> max_edge;  // --max-edge L
  std::vector<std::string> also;   // --also OTHER.prt (repeatable)
  uint64_t memory_limit = 0;       // --memory-limit (option_rules.h); 0: not given
  bool quiet = false;
};

#ifdef PRT_VIEW_WEB_DIR
// Blocks SIGINT and SIGTERM in this thread and in every thread started after it (the payload
// builders' worker threads too, so that none of them takes the default action) and waits for
// them in a thread of its own: before *server is set (the payloads being built), a signal ends
// prt view at once with status 128 + signal (nothing was written); after, it stops the server,
// and Ctrl-C ends `prt view` with status 0 once the socket is closed. Their dispositions are
// reset first: a shell starts a background job (`prt view … &` in a script) with SIGINT ignored,
// and an ignored signal is discarded, never delivered to sigwait.
std::thread stop_on_signal(const std::atomic<view::ViewServer*>* server) {
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  sigset_t set;
  sigemptyset(&set);
  sigaddset(&set, SIGINT);
  sigaddset(&set, SIGTERM);
  pthread_sigmask(SIG_BLOCK, &set, nullptr);
  return std::thread([server, set] {
    int signal = 0;
    sigwait(&set, &signal);
    view::ViewServer* serving = server->load();
    if (serving == nullptr) std::_Exit(128 + signal);
    serving->stop();
  });
}
#endif

void run(const ViewArguments& args) {
#ifndef PRT_VIEW_WEB_DIR
  throw CommandError("this prt was built without the viewer (cpp-httplib was not found)");
#else
  // The assets first: without them there is nothing to serve, whatever the inputs. The build
  // tree's copy, unless PRT_VIEW_WEB_DIR names another (an installed or a test copy).
  const char* web_dir = std::getenv("PRT_VIEW_WEB_DIR");
  std::map<std::string, view::Route> routes =
      view::asset_routes(web_dir && *web_dir ? web_dir : PRT_VIEW_WEB_DIR);
  std::atomic<view::ViewServer*> serving{nullptr};
  std::thread waiter = stop_on_signal(&serving);
  struct Join {  // the waiter outlives every exit of this function, thrown or returned
    std::thread* thread;
    ~Join() {
      if (thread->joinable()) thread->detach();
    }
  } join{&waiter};
  view::ViewInputs inputs;
  inputs.scene_path = args.scene;
  inputs.transfer_path = args.transfer;
  inputs.environment_path = args.environment;
  inputs.emitters_path = args.emitters;
  inputs.max_edge = args.max_edge;
  inputs.also_paths = args.also;
  // The payloads are held for as long as the server runs: charged as they are built, so that a
  // scene too large for the limit is refused in one line before the port is opened.
  prt::MemoryBudget budget(memory_limit_or_default(args.memory_limit), args.transfer);
  inputs.budget = &budget;
  if (args.max_edge && !(*args.max_edge > 0))
    throw UsageError("--max-edge: must be a positive length");
  view::ViewPayload payload = view::build_view_payload(inputs);
  const std::string summary =
      payload.summary + "; payloads " + prt::format_memory_size(budget.used()) + " held";
  view::add_payload_routes(std::move(payload), &routes);
  view::ViewServer server(std::move(routes));
  const int port = server.bind(args.listen, args.port);
  std::string host = args.listen;  // an IPv6 address goes in brackets in a URL
  if (host.find(':') != std::string::npos) host = std::string("[").append(host).append("]");
  if (!args.quiet) std::printf("%s\n", summary.c_str());
  std::printf("serving http://%s:%d/ (Ctrl-C stops)\n", host.c_str(), port);
  std::fflush(stdout);
  serving = &server;
  server.serve([&args](const std::string& line) {
    if (!args.quiet) std::fprintf(stderr, "prt view: refused %s\n", line.c_str());
  });
  waiter.join();
#endif
}

Command register_view(CLI::App& app) {
  auto args = std::make_shared<ViewArguments>();
  CLI::App* cmd = app.add_subcommand(
      "view", "Serve a browser page that relights the scene on the GPU (drag to turn the light)");
  cmd->add_option("scene", args->scene, "Scene (.glb, .gltf, .obj) the file was baked from")
      ->required();
  cmd->add_option("transfer", args->transfer,
                  "Coefficient file (.prt: SH or Haar wavelets) or glossy transfer (.prtg, .prtq)")
      ->required();
  cmd->add_option("environment", args->environment,
                  "Environment map (.hdr, .exr, .pfm; default: uniform radiance 1)");
  cmd->add_option("--port", args->port, "TCP port (0: any free port; the URL printed says which)")
      ->check(CLI::Range(0, 65535))
      ->capture_default_str();
  cmd->add_option("--listen", args->listen,
                  "Address to listen on (default loopback only; another address exposes the "
                  "scene to the network)")
      ->capture_default_str();
  cmd->add_option("--emitters", args->emitters,
                  "Per-emitter radiosity responses (.prte) added to the environment light, with "
                  "a colour and intensity slider per emitter (as prt relight --emitters)");
  cmd->add_option("--max-edge", args->max_edge,
                  "Subdivide the scene as prt bake --max-edge did (the vertices of --emitters)");
  cmd->add_option("--also", args->also,
                  "Another SH file of the scene (repeatable; e.g. interreflected beside a "
                  "shadowed FILE), of FILE's order, channels and albedo folding: one more "
                  "display each, at FILE's camera, exposure and window")
      ->allow_extra_args(false);
  add_memory_limit_option(*cmd, &args->memory_limit);
  cmd->add_flag("--quiet", args->quiet, "Print the URL only");
  const auto files = [args] {
    CommandFiles f;
    f.add_scene(args->scene);
    f.add_input("coefficient file", args->transfer);
    if (!args->environment.empty()) f.add_environment(args->environment);
    if (!args->emitters.empty()) f.add_input("emitter responses", args->emitters);
    for (const std::string& other : args->also) f.add_input("coefficient file", other);
    return f;
  };
  return {cmd, {}, files, [args] { run(*args); }};
}

}  // namespace

PRT_REGISTER_COMMAND(32, register_view);

}  // namespace prt::cli
