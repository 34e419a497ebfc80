// cli/ssao_browser.cpp — running scripts/ssao-capture.cjs in headless Chromium (ssao_browser.h).
#include "ssao_browser.h"

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include <nlohmann/json.hpp>

#include "command_registry.h"

namespace prt::cli {
namespace {

namespace fs = std::filesystem;

bool executable(const fs::path& p) {
  return ::access(p.c_str(), X_OK) == 0 && fs::is_regular_file(p);
}

// `name` on the PATH, or "".
std::string on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  for (std::string dir; std::getline(dirs, dir, ':');)
    if (!dir.empty() && executable(fs::path(dir) / name)) return (fs::path(dir) / name).string();
  return "";
}

std::string quoted(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::vector<float> read_floats(const fs::path& p, std::size_t count) {
  std::ifstream in(p, std::ios::binary);
  std::vector<float> v(count);
  in.read(reinterpret_cast<char*>(v.data()), static_cast<std::streamsize>(count * sizeof(float)));
  if (!in || in.gcount() != static_cast<std::streamsize>(count * sizeof(float)))
    throw CommandError("prt report --ssao: the browser's read-back " + p.filename().string() +
                       " is missing or short");
  return v;
}

// A scratch folder for the job and the read-backs, removed when the capture is done.
struct ScratchDir {
  fs::path path;
  ScratchDir() {
    path = fs::temp_directory_path() / ("prt-ssao-" + std::to_string(::getpid()));
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~ScratchDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
};

nlohmann::json job_json(const CaptureJob& job) {
  nlohmann::json cams = nlohmann::json::array();
  for (const CaptureCamera& c : job.cameras)
    cams.push_back({{"name", c.name},
                    {"eye", {c.eye.x, c.eye.y, c.eye.z}},
                    {"target", {c.target.x, c.target.y, c.target.z}},
                    {"up", {c.up.x, c.up.y, c.up.z}},
                    {"fov", c.yfov_degrees}});
  return {{"width", job.width},     {"height", job.height}, {"radius", job.radius},
          {"samples", job.samples}, {"slices", job.slices}, {"steps", job.steps},
          {"cameras", cams}};
}

}  // namespace

BrowserTools find_browser_tools() {
  BrowserTools t;
  const char* chosen = std::getenv("PRT_CHROMIUM");
  if (chosen != nullptr && *chosen != '\0') {
    if (!executable(chosen))
      throw CommandError(std::string("prt report --ssao: PRT_CHROMIUM=") + chosen +
                         " is not an executable file");
    t.chromium = chosen;
  } else {
    t.chromium = on_path("chromium");
    if (t.chromium.empty()) t.chromium = on_path("chromium-browser");
  }
  if (t.chromium.empty())
    throw CommandError(
        "prt report --ssao: Chromium was not found (install Debian's chromium with "
        "the test dependencies of scripts/install-deps.sh, or set PRT_CHROMIUM)");
  t.node = on_path("node");
  if (t.node.empty())
    throw CommandError(
        "prt report --ssao: node was not found (the test dependencies of scripts/install-deps.sh)");
  t.modules = PRT_SSAO_NODE_MODULES;
  if (!fs::exists(fs::path(t.modules) / "puppeteer-core" / "package.json"))
    throw CommandError("prt report --ssao: puppeteer-core is not installed in " + t.modules +
                       " (the test dependencies of scripts/install-deps.sh)");
  t.script = PRT_SSAO_CAPTURE_SCRIPT;
  if (!fs::exists(t.script)) throw CommandError("prt report --ssao: " + t.script + " is missing");
  return t;
}

std::vector<report::AoCapture> capture_ao(const BrowserTools& tools, const std::string& url,
                                          const CaptureJob& job) {
  const ScratchDir scratch;
  const fs::path job_file = scratch.path / "job.json", errors = scratch.path / "stderr.txt";
  std::ofstream(job_file) << job_json(job).dump();
  const std::string command =
      quoted(tools.node) + " " + quoted(tools.script) + " " + quoted(tools.modules) + " " +
      quoted(tools.chromium) + " " + quoted(url) + " " + quoted(job_file.string()) + " " +
      quoted(scratch.path.string()) + " >/dev/null 2>" + quoted(errors.string());
  if (std::system(command.c_str()) != 0) {
    std::ifstream in(errors);
    std::string line;
    std::getline(in, line);
    throw CommandError("prt report --ssao: headless Chromium failed: " +
                       (line.empty() ? std::string("no message") : line));
  }
  const std::size_t floats = std::size_t(4) * job.width * job.height;
  std::vector<report::AoCapture> out;
  for (const CaptureCamera& c : job.cameras) {
    report::AoCapture a;
    a.name = c.name;
    a.width = job.width;
    a.height = job.height;
    a.eye = c.eye;
    const auto file = [&](const char* which) {
      return scratch.path / (c.name + "_" + which + ".f32");
    };
    a.position = read_floats(file("position"), floats);
    a.normal = read_floats(file("normal"), floats);
    for (const char* which : {"ssao", "gtao", "baked"}) {
      a.estimates.push_back(read_floats(file(which), floats));
      a.estimate_names.emplace_back(which);
    }
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace prt::cli
