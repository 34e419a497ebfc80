// cli/ssao_browser.h — headless Chromium over the ambient-occlusion page of `prt view`
// (web/ssao.html), for `prt report --ssao`: finds Debian's chromium, node and puppeteer-core
// (tests/viewer/node_modules, installed by scripts/install-deps.sh --for test), runs
// scripts/ssao-capture.cjs for a list of cameras and reads its float32 read-backs
// (report/ssao_comparison.h's AoCapture: G-buffer, classic SSAO, GTAO, baked AO).
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "report/ssao_comparison.h"

namespace prt::cli {

struct BrowserTools {
  std::string node, chromium, modules, script;
};

// The tools, or CommandError with one line naming what is missing: Chromium is looked up as
// $PRT_CHROMIUM, else chromium or chromium-browser on the PATH.
BrowserTools find_browser_tools();

struct CaptureCamera {
  std::string name;
  glm::vec3 eye{0.f}, target{0.f}, up{0.f, 1.f, 0.f};
  double yfov_degrees = 45;
};

struct CaptureJob {
  int width = 480, height = 270;
  double radius = 1;
  int samples = 32, slices = 4, steps = 8;
  std::vector<CaptureCamera> cameras;
};

// Renders every camera of `job` from the page at `url` (http://127.0.0.1:PORT) and returns the
// read-backs, estimates named "ssao", "gtao", "baked". Throws CommandError (one line) when the
// browser or the page fails.
std::vector<report::AoCapture> capture_ao(const BrowserTools& tools, const std::string& url,
                                          const CaptureJob& job);

}  // namespace prt::cli
