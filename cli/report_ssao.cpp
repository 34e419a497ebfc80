// cli/report_ssao.cpp — `prt report --ssao` (report_ssao.h).
#include "report_ssao.h"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <limits>
#include <thread>

#include <nlohmann/json.hpp>

#include "bake/obscurance_falloff.h"
#include "bake/transfer_baker.h"
#include "cli_parsing.h"
#include "command_registry.h"
#include "option_rules.h"
#include "prt/formats/transfer_file.h"
#include "report/ssao_comparison.h"
#include "report/ssao_report_outputs.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "ssao_browser.h"
#ifdef PRT_VIEW_WEB_DIR
#include "view/view_payload.h"
#include "view/view_server.h"
#endif

namespace prt::cli {
namespace {

namespace fs = std::filesystem;

const char* const kSsaoOptions[] = {"--ao-distance",  "--ao-falloff",  "--ssao-radius",
                                    "--ssao-samples", "--ssao-slices", "--ssao-steps",
                                    "--ssao-rays",    "--ssao-size"};
constexpr int kDistanceBins = 6;

// "WxH" → {W, H}, each in [16, 4096].
std::pair<int, int> parse_size(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w < 16 ||
      h < 16 || w > 4096 || h > 4096)
    throw UsageError("--ssao-size " + text + ": expected WxH, each in [16, 4096]");
  return {w, h};
}

// The cameras: the scene's automatic camera (prt relight's, from the manifest), then views
// turned by ±30° about the vertical through its target and pulled back along the view (× 1.6,
// × 2.5): the automatic camera looks in from the open side, and these stay there.
std::vector<CaptureCamera> cameras(const std::string& manifest_json, bool quick) {
  const nlohmann::json c = nlohmann::json::parse(manifest_json)["camera"];
  const auto vec = [](const nlohmann::json& j) {
    return glm::vec3(j[0].get<float>(), j[1].get<float>(), j[2].get<float>());
  };
  CaptureCamera first{"cam0", vec(c["eye"]), vec(c["target"]), vec(c["up"]),
                      c["yfov_degrees"].get<double>()};
  struct Turn {
    double degrees, scale;
  };
  const std::vector<Turn> turns =
      quick ? std::vector<Turn>{{-30, 1.6}} : std::vector<Turn>{{30, 1}, {-30, 1.6}, {0, 2.5}};
  std::vector<CaptureCamera> out = {first};
  const glm::vec3 offset = first.eye - first.target;
  for (const Turn& t : turns) {
    const double a = t.degrees * 3.14159265358979323846 / 180.0;
    const float ca = static_cast<float>(std::cos(a)), sa = static_cast<float>(std::sin(a));
    const glm::vec3 turned(ca * offset.x + sa * offset.z, offset.y, -sa * offset.x + ca * offset.z);
    CaptureCamera cam = first;
    cam.name = "cam" + std::to_string(out.size());
    cam.eye = first.target + static_cast<float>(t.scale) * turned;
    cam.up = glm::vec3(0.f, 1.f, 0.f);
    out.push_back(cam);
  }
  return out;
}

int camera_count(bool quick) {
  return quick ? 2 : 4;
}

// Bakes AO (or obscurance) with the fixed recipe.
prt::TransferData bake_ao(const scene::Scene& scene, int samples,
                          const bake::ObscuranceOptions& obscurance) {
  bake::BakeOptions o;
  o.kind = prt::TransferKind::Shadowed;
  o.order = 1;
  o.samples = samples;
  o.ao = true;
  o.obscurance = obscurance;
  o.memory_limit = memory_limit_or_default(0);
  return bake::bake_transfer(scene, o).data;
}

void write_transfer(const std::string& path, const prt::TransferData& data) {
  const prt::Status written = prt::write_transfer_file(path, data);
  if (!written.ok()) throw CommandError(written.message());
}

// The baked AO file the server reads while the browser renders: a scratch copy, so that
// nothing is in the output folder until the measurement has succeeded.
struct ScratchFile {
  fs::path path =
      fs::temp_directory_path() / ("prt-ssao-ao-" + std::to_string(::getpid()) + ".prt");
  ~ScratchFile() {
    std::error_code ec;
    fs::remove(path, ec);
  }
};

#ifdef PRT_VIEW_WEB_DIR
// `prt view`'s server on a free loopback port while the browser renders.
std::vector<report::AoCapture> render_in_browser(const BrowserTools& tools,
                                                 const std::string& scene_path,
                                                 const std::string& ao_file, CaptureJob job,
                                                 bool quick) {
  // The build tree's page, unless PRT_VIEW_WEB_DIR names another copy (as for prt view).
  const char* web_dir = std::getenv("PRT_VIEW_WEB_DIR");
  std::map<std::string, view::Route> routes =
      view::asset_routes(web_dir && *web_dir ? web_dir : PRT_VIEW_WEB_DIR);
  view::ViewInputs inputs;
  inputs.scene_path = scene_path;
  inputs.transfer_path = ao_file;
  inputs.aspect = static_cast<float>(job.width) / static_cast<float>(job.height);
  view::ViewPayload payload = view::build_view_payload(inputs);
  job.cameras = cameras(payload.manifest_json, quick);
  view::add_payload_routes(std::move(payload), &routes);
  view::ViewServer server(std::move(routes));
  const int port = server.bind("127.0.0.1", 0);
  std::thread serving([&server] { server.serve(); });
  struct Stop {
    view::ViewServer& s;
    std::thread& t;
    ~Stop() {
      s.stop();
      t.join();
    }
  } stop{server, serving};
  return capture_ao(tools, "http://127.0.0.1:" + std::to_string(port), job);
}
#endif

struct Measured {
  std::vector<report::SsaoResult> results;
  double lo = 0, hi = 0;
};

// Traces the truth of every capture, writes its picture, and measures every estimate.
Measured measure(const scene::Scene& scene, const std::vector<report::AoCapture>& captures,
                 const report::PixelTruthOptions& truth_options, const report::RegionRule& rule,
                 const std::string& output) {
  Measured m;
  m.lo = std::numeric_limits<double>::infinity();
  for (const report::AoCapture& c : captures) {
    double lo = 0, hi = 0;
    report::eye_distance_range(c, lo, hi);
    m.lo = std::min(m.lo, lo);
    m.hi = std::max(m.hi, hi);
  }
  if (!(m.hi > 0)) throw CommandError(output + ": no camera sees the scene");
  const scene::RayCaster caster(scene);
  std::vector<report::SsaoResult> totals;
  for (const report::AoCapture& c : captures) {
    const report::PixelTruth truth = report::trace_pixel_truth(scene, caster, c, truth_options);
    report::write_ssao_picture((fs::path(output) / ("ssao_" + c.name + ".png")).string(), c, truth);
    for (int k = 0; k < static_cast<int>(c.estimates.size()); ++k)
      for (const bool obscurance : {false, true}) {
        if (obscurance && (truth.obscurance.empty() || c.estimate_names[k] == "baked")) continue;
        report::SsaoResult r{c.name, c.estimate_names[k], obscurance ? "obscurance" : "ao", {}};
        r.errors.distance.resize(kDistanceBins);
        report::accumulate_errors(c, k, obscurance ? truth.obscurance : truth.ao, truth, rule, m.lo,
                                  m.hi, r.errors);
        auto total = std::find_if(totals.begin(), totals.end(), [&](const auto& t) {
          return t.estimate == r.estimate && t.truth == r.truth;
        });
        if (total == totals.end())
          totals.push_back({"all", r.estimate, r.truth, r.errors});
        else
          total->errors.merge(r.errors);
        m.results.push_back(std::move(r));
      }
  }
  m.results.insert(m.results.begin(), totals.begin(), totals.end());
  return m;
}

bake::ObscuranceOptions obscurance_of(const SsaoReportArguments& a) {
  bake::ObscuranceOptions o;
  if (a.ao_distance) {
    o.distance = *a.ao_distance;
    o.falloff = *bake::parse_obscurance_falloff(a.ao_falloff);
  }
  return o;
}

}  // namespace

void add_ssao_report_options(CLI::App* cmd, SsaoReportArguments* a) {
  cmd->add_flag("--ssao", a->enabled,
                "Screen-space AO (classic, GTAO) against ray-traced AO per pixel, in headless "
                "Chromium: prt report --ssao SCENE -o DIR");
  cmd->add_option("--ao-distance", a->ao_distance,
                  "--ssao: also measure against obscurance of this distance (scene units; the "
                  "default SSAO radius)");
  cmd->add_option("--ao-falloff", a->ao_falloff,
                  "--ssao --ao-distance: linear | exponential | smoothstep | constant")
      ->capture_default_str();
  cmd->add_option("--ssao-radius", a->radius,
                  "--ssao: screen-space radius in scene units (default: --ao-distance, else 1/10 "
                  "of the scene's diagonal)");
  cmd->add_option("--ssao-samples", a->samples, "--ssao: classic SSAO samples, 1..64")
      ->capture_default_str();
  cmd->add_option("--ssao-slices", a->slices, "--ssao: GTAO slices, 1..16")->capture_default_str();
  cmd->add_option("--ssao-steps", a->steps, "--ssao: GTAO horizon steps per side, 1..32")
      ->capture_default_str();
  cmd->add_option("--ssao-rays", a->rays, "--ssao: truth rays per pixel (--quick: 64)")
      ->capture_default_str();
  cmd->add_option("--ssao-size", a->size, "--ssao: image size WxH")->capture_default_str();
}

void refuse_ssao_options(const CLI::App& cmd) {
  for (const char* option : kSsaoOptions)
    if (cmd.count(option) > 0) throw UsageError(std::string(option) + " applies only to --ssao");
}

void check_ssao_mode(const SsaoReportArguments& a, const std::string& scene,
                     const std::string& other) {
  if (scene.empty()) throw UsageError("--ssao needs SCENE: prt report --ssao SCENE -o DIR");
  if (!other.empty()) throw UsageError(other + " does not apply to --ssao");
  if (a.ao_distance && !(*a.ao_distance > 0 && std::isfinite(*a.ao_distance)))
    throw UsageError("--ao-distance: must be a finite length > 0 (scene units)");
  if (!bake::parse_obscurance_falloff(a.ao_falloff))
    throw UsageError("--ao-falloff " + a.ao_falloff +
                     ": expected linear, exponential, smoothstep or constant");
  if (a.radius && !(*a.radius > 0 && std::isfinite(*a.radius)))
    throw UsageError("--ssao-radius: must be a finite length > 0 (scene units)");
  if (a.samples < 1 || a.samples > 64) throw UsageError("--ssao-samples: must be in [1, 64]");
  if (a.slices < 1 || a.slices > 16) throw UsageError("--ssao-slices: must be in [1, 16]");
  if (a.steps < 1 || a.steps > 32) throw UsageError("--ssao-steps: must be in [1, 32]");
  if (a.rays < 16 || a.rays > 65536) throw UsageError("--ssao-rays: must be in [16, 65536]");
  parse_size(a.size);
}

CommandFiles ssao_report_files(const SsaoReportArguments& a, const std::string& scene,
                               const std::string& output, bool quick) {
  CommandFiles files;
  files.add_scene(scene);
  files.add_output_directory("-o", output);
  std::vector<std::string> names = report::ssao_table_names();
  names.push_back("ao.prt");
  if (a.ao_distance) names.push_back("obscurance.prt");
  for (int i = 0; i < camera_count(quick); ++i)
    names.push_back("ssao_cam" + std::to_string(i) + ".png");
  for (const std::string& name : names) files.add_output("-o", (fs::path(output) / name).string());
  return files;
}

void run_ssao_mode(const SsaoReportArguments& a, const std::string& scene_path,
                   const std::string& output, bool quick, bool quiet) {
#ifndef PRT_VIEW_WEB_DIR
  (void)a, (void)scene_path, (void)output, (void)quick, (void)quiet;
  throw CommandError("prt report --ssao: this prt was built without the viewer (cpp-httplib)");
#else
  const BrowserTools tools = find_browser_tools();  // before anything is written
  const scene::Scene scene = scene::load_scene(scene_path);
  const bake::ObscuranceOptions obscurance = obscurance_of(a);
  const int bake_samples = quick ? 64 : 256;
  const prt::TransferData ao = bake_ao(scene, bake_samples, {});
  const ScratchFile ao_file;
  write_transfer(ao_file.path.string(), ao);
  CaptureJob job;
  std::tie(job.width, job.height) = parse_size(quick && a.size == "480x270" ? "320x180" : a.size);
  job.radius = a.radius ? *a.radius : a.ao_distance ? *a.ao_distance : 0.1 * scene.extent();
  job.samples = a.samples;
  job.slices = a.slices;
  job.steps = a.steps;
  if (!quiet) std::fprintf(stderr, "prt report --ssao: rendering in headless Chromium\n");
  const std::vector<report::AoCapture> captures =
      render_in_browser(tools, scene_path, ao_file.path.string(), job, quick);
  report::PixelTruthOptions truth;
  truth.rays = quick && a.rays == 256 ? 64 : a.rays;
  // Without --ao-distance, "obscurance" is AO within the radius (constant falloff at D = R):
  // what a screen-space method with radius R can see at best.
  truth.obscurance = obscurance;
  if (!obscurance.enabled()) truth.obscurance = {job.radius, bake::ObscuranceFalloff::Constant};
  report::RegionRule rule;
  rule.radius = job.radius;
  if (!quiet) std::fprintf(stderr, "prt report --ssao: tracing the truth per pixel\n");
  fs::create_directories(output);
  const Measured m = measure(scene, captures, truth, rule, output);
  write_transfer((fs::path(output) / "ao.prt").string(), ao);
  if (obscurance.enabled())
    write_transfer((fs::path(output) / "obscurance.prt").string(),
                   bake_ao(scene, bake_samples, obscurance));
  report::SsaoReportSettings s;
  s.scene = scene_path;
  s.radius = job.radius;
  s.samples = job.samples;
  s.slices = job.slices;
  s.steps = job.steps;
  s.truth_rays = (truth.rays + 15) / 16 * 16;
  s.bake_samples = bake_samples;
  s.obscurance = truth.obscurance;
  s.rule = rule;
  s.distance_lo = m.lo;
  s.distance_hi = m.hi;
  for (const std::string& f : report::write_ssao_tables(output, m.results, s))
    std::printf("wrote %s\n", f.c_str());
  for (const report::SsaoResult& r : m.results)
    if (r.camera == "all")
      std::printf("%s vs ray-traced %s: relative RMS %.3f over %llu pixels\n", r.estimate.c_str(),
                  r.truth.c_str(), r.errors.all.stats().relative_rms,
                  static_cast<unsigned long long>(r.errors.all.n));
#endif
}

}  // namespace prt::cli
