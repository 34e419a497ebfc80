// report/src/report.cpp — `prt report` (see report.h).
#include "report/report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>

#include <nlohmann/json.hpp>

#include "bake/adaptive/adaptive_baker.h"
#include "bake/ground_truth.h"
#include "bake/haar_baker.h"
#include "bake/progress.h"
#include "bake/transfer_baker.h"
#include "prt/haar/cube_map.h"
#include "prt/haar/relighter.h"
#include "prt/haar/transfer_file.h"
#include "prt/lighting.h"
#include "prt/relighter.h"
#include "prt/transfer_file.h"
#include "relight/camera.h"
#include "relight/haar_relight.h"
#include "relight/image_io.h"
#include "relight/relight_pipeline.h"
#include "relight/renderer.h"
#include "report/plot_svg.h"
#include "report/report_metrics.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"
#include "sh/basis.h"
#include "sh/projection.h"

namespace prt::report {
namespace {

using Clock = std::chrono::steady_clock;
const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};
// Haar series (one per cube size), apart from the SH grid's first five palette colours.
const char* const kHaarPalette[] = {"#8c564b", "#e377c2", "#17becf", "#bcbd22"};
// Haar compression of the report's bakes: the defaults of `prt bake --basis haar`.
constexpr double kHaarThreshold = 1e-3;
constexpr prt::HaarQuantization kHaarQuantization = prt::HaarQuantization::Bits16;

double since(Clock::time_point t) {
  return std::chrono::duration<double>(Clock::now() - t).count();
}

std::string precision_name(prt::Precision p) {
  return p == prt::Precision::F16 ? "f16" : "f32";
}

std::string bounces_name(int b) {
  return b < 0 ? std::string("converged") : std::to_string(b);
}

bool is_haar(const ReportSetting& s) {
  return s.basis == ReportBasis::Haar;
}

std::string basis_name(const ReportSetting& s) {
  return is_haar(s) ? "haar" : "sh";
}

// Storage of the coefficients: f32/f16 for SH, the quantisation for Haar.
std::string storage_name(const ReportSetting& s) {
  return is_haar(s) ? std::string("i") + std::to_string(static_cast<int>(kHaarQuantization))
                    : precision_name(s.precision);
}

int64_t haar_coefficient_count(int cube) {
  return int64_t{6} * cube * cube;
}

// The number of lighting terms a Haar setting uses (all = 6N²).
int64_t haar_terms_used(const ReportSetting& s) {
  return s.terms > 0 ? std::min(s.terms, haar_coefficient_count(s.cube))
                     : haar_coefficient_count(s.cube);
}

std::string terms_text(const ReportSetting& s) {
  const std::string n = std::to_string(haar_terms_used(s));
  return s.terms > 0 ? n : "all " + n;
}

std::string describe(const ReportSetting& s) {
  if (is_haar(s))
    return "Haar cube " + std::to_string(s.cube) + ", " + terms_text(s) +
           " lighting terms (non-linear), bounces " + bounces_name(s.bounces) + ", " +
           storage_name(s);
  return "SH order " + std::to_string(s.order) + ", " + std::to_string(s.samples) +
         " spp, bounces " + bounces_name(s.bounces) + ", " + precision_name(s.precision);
}

std::string short_label(const ReportSetting& s) {
  if (is_haar(s))
    return "H" + std::to_string(s.cube) + " K" +
           (s.terms > 0 ? std::to_string(s.terms) : std::string("all"));
  std::string t = "n" + std::to_string(s.order) + " " + std::to_string(s.samples);
  if (s.bounces >= 0) t += " b" + std::to_string(s.bounces);
  if (s.precision == prt::Precision::F16) t += " f16";
  return t;
}

bool same(const ReportSetting& a, const ReportSetting& b) {
  return a.basis == b.basis && a.order == b.order && a.samples == b.samples &&
         a.bounces == b.bounces && a.precision == b.precision && a.cube == b.cube &&
         a.terms == b.terms;
}

std::string percent(double x) {
  char buf[32];
  if (!std::isfinite(x)) return "inf";
  std::snprintf(buf, sizeof buf, x < 0.01 ? "%.3f%%" : "%.2f%%", 100.0 * x);
  return buf;
}

std::string seconds_text(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, s < 0.01 ? "%.2f ms" : "%.2f s", s < 0.01 ? s * 1e3 : s);
  return buf;
}

// Relights a transfer with SH lighting: 3 floats per vertex; *seconds = best of `repeats` runs.
// A transfer that keeps the albedo apart (a textured scene) is multiplied by each vertex's own
// albedo afterwards (not timed): the exit radiance the ground truth computes at the vertex.
std::vector<float> relight(const prt::TransferData& data, prt::Precision precision,
                           const prt::ShLighting& lighting, int repeats, double* seconds,
                           std::string* failure, const scene::Scene& scene) {
  auto relighter = prt::Relighter::create(data, precision);
  if (!relighter.ok()) {
    *failure = relighter.status().message();
    return {};
  }
  std::vector<float> b;
  *seconds = INFINITY;
  for (int i = 0; i < repeats; ++i) {
    const auto t0 = Clock::now();
    b = relight::shade_all_vertices(*relighter, lighting,
                                    static_cast<std::size_t>(data.vertex_count));
    *seconds = std::min(*seconds, since(t0));
  }
  if (!data.albedo_folded && b.size() == 3 * scene.albedo.size())
    for (std::size_t v = 0; v < scene.albedo.size(); ++v)
      for (int c = 0; c < 3; ++c) b[3 * v + c] *= scene.albedo[v][c];
  return b;
}

// The first n² coefficients of every channel (the order-n transfer of the same samples: the
// interreflection solve acts on each coefficient column independently).
prt::TransferData truncate_order(const prt::TransferData& d, int n) {
  prt::TransferData t = d;
  const std::size_t K = d.coefficients_per_channel(), k = static_cast<std::size_t>(n) * n;
  t.order = static_cast<uint32_t>(n);
  t.coefficients.assign(d.vertex_count * d.channels * k, 0.f);
  for (std::size_t r = 0; r < d.vertex_count * d.channels; ++r)
    std::copy_n(&d.coefficients[r * K], k, &t.coefficients[r * k]);
  return t;
}

std::vector<double> to_double(const std::vector<float>& v) {
  return std::vector<double>(v.begin(), v.end());
}

}  // namespace

ReportSetting base_setting(bool quick) {
  ReportSetting s;
  s.order = 6;
  s.samples = quick ? 256 : 1024;
  s.bounces = -1;
  s.precision = prt::Precision::F32;
  return s;
}

std::vector<ReportAxis> report_axes(bool quick, const std::optional<std::vector<int>>& haar_cubes) {
  const ReportSetting base = base_setting(quick);
  std::vector<ReportAxis> axes;
  auto vary = [&](const std::string& name, auto values, auto apply) {
    ReportAxis axis{name, {}};
    for (auto v : values) {
      ReportSetting s = base;
      apply(s, v);
      axis.settings.push_back(s);
    }
    axes.push_back(axis);
  };
  const std::vector<int> orders =
      quick ? std::vector<int>{2, 3, 4, 5, 6} : std::vector<int>{2, 3, 4, 5, 6, 8, 10, 12, 16};
  const std::vector<int> samples =
      quick ? std::vector<int>{64, 256, 1024} : std::vector<int>{64, 256, 1024, 4096, 16384};
  const std::vector<int> bounces =
      quick ? std::vector<int>{0, 1, -1} : std::vector<int>{0, 1, 2, 4, 8, -1};
  vary("order", orders, [](ReportSetting& s, int v) { s.order = v; });
  vary("samples", samples, [](ReportSetting& s, int v) { s.samples = v; });
  vary("bounces", bounces, [](ReportSetting& s, int v) { s.bounces = v; });
  vary("precision", std::vector<prt::Precision>{prt::Precision::F32, prt::Precision::F16},
       [](ReportSetting& s, prt::Precision v) { s.precision = v; });
  ReportAxis grid{"grid", {}};
  const std::vector<int> grid_orders =
      quick ? std::vector<int>{2, 4, 6} : std::vector<int>{2, 4, 6, 8, 10};
  const std::vector<int> grid_samples =
      quick ? std::vector<int>{64, 256} : std::vector<int>{64, 256, 1024, 4096};
  for (int n : grid_orders)
    for (int N : grid_samples) {
      ReportSetting s = base;
      s.order = n, s.samples = N;
      grid.settings.push_back(s);
    }
  axes.push_back(grid);
  ReportAxis haar{"haar", {}};
  for (int cube : haar_cubes ? *haar_cubes : default_haar_cubes(quick))
    for (int64_t k : haar_terms(quick)) {
      if (k >= haar_coefficient_count(cube)) continue;  // the same as all terms
      ReportSetting s;
      s.basis = ReportBasis::Haar;
      s.order = 0, s.samples = 0;
      s.bounces = base.bounces;
      s.precision = prt::Precision::F32;
      s.cube = cube;
      s.terms = k;
      haar.settings.push_back(s);
    }
  if (!haar.settings.empty()) axes.push_back(haar);
  return axes;
}

std::vector<double> default_auto_tolerances(bool quick) {
  return quick ? std::vector<double>{0.05} : std::vector<double>{0.01, 0.05, 0.1};
}

std::vector<int> default_haar_cubes(bool quick) {
  return quick ? std::vector<int>{8} : std::vector<int>{8, 16};
}

std::vector<int64_t> haar_terms(bool quick) {
  return quick ? std::vector<int64_t>{10, 30, 100, 0}
               : std::vector<int64_t>{10, 30, 100, 300, 1000, 0};
}

namespace {

// ---- run_report, phase by phase ----
//
// run_report loads the inputs and a first ground truth (ReportState), measures every setting of
// the sweep, splits the error into projection and sampling, refines the ground truth if the
// smallest error needs it (and scores everything again), bakes `prt bake --auto` at each
// tolerance, and writes the outputs. The phases share one ReportState.

// Throws for a --haar-cubes size that is not a power of two in [8, 128].
void check_haar_cubes(const ReportOptions& opt) {
  if (opt.haar_cubes)
    for (int cube : *opt.haar_cubes)
      if (!prt::is_valid_cube_size(cube))
        throw std::runtime_error("report: Haar cube size " + std::to_string(cube) +
                                 " is not a power of two in [8, 128]");
}

void create_output_dir(const ReportOptions& opt) {
  std::error_code ec;
  std::filesystem::create_directories(opt.output_dir, ec);
  if (ec) throw std::runtime_error(opt.output_dir + ": cannot create directory: " + ec.message());
}

bake::GroundTruthOptions report_ground_truth_options(const ReportOptions& opt) {
  bake::GroundTruthOptions gto;
  gto.seed = opt.seed + 1000;
  gto.initial_samples = 64;
  gto.max_samples = 1 << 16;
  return gto;
}

// Progress lines on stderr (when verbose), stamped with the seconds since the start.
struct ReportLog {
  bool verbose;
  Clock::time_point t_start;
  void operator()(const std::string& line) const {
    if (verbose) std::fprintf(stderr, "[report %6.1fs] %s\n", since(t_start), line.c_str());
  }
};

// The scene, the map and the renderer every phase measures with.
struct ReportInputs {
  // Loads the scene and the map, logs them, and finds the pixels the scene covers.
  ReportInputs(const ReportOptions& opt, const ReportLog& log);

  // Renders per-vertex RGB radiance with the report's camera: RGB floats per pixel.
  std::vector<float> render_radiance(const std::vector<float>& b) const {
    return relight::render(scene, caster, b, nullptr, relight::kIdentityRotation, camera, ropt).rgb;
  }

  scene::Scene scene;
  std::string layout_note;
  const sh::EnvMap env;
  scene::RayCaster caster;
  const std::size_t V;
  relight::RenderOptions ropt;
  relight::Camera camera;
  std::vector<uint8_t> mask;  // pixels fully covered by the scene
};

ReportInputs::ReportInputs(const ReportOptions& opt, const ReportLog& log)
    : scene(scene::load_scene(opt.scene_path)),
      env(relight::read_environment(opt.environment_path, opt.layout, &layout_note)),
      caster(scene),
      V(scene.vertex_count()) {
  log(opt.scene_path + ": " + std::to_string(V) + " vertices; " + opt.environment_path + ": " +
      layout_note);
  ropt.width = opt.image_width, ropt.height = opt.image_height, ropt.samples_per_axis = 2;
  camera = relight::parse_camera("auto", scene,
                                 static_cast<float>(ropt.width) / static_cast<float>(ropt.height));
  // Pixels fully covered by the scene: a rendering of radiance 1 everywhere is 1 there.
  const std::vector<float> ones = render_radiance(std::vector<float>(3 * V, 1.f));
  mask.resize(ones.size() / 3);
  for (std::size_t i = 0; i < mask.size(); ++i) mask[i] = ones[3 * i] > 0.999f ? 1 : 0;
}

// Everything the phases of run_report share: the inputs, the ground truth, the sweep's caches
// and per-measurement results, and the result being filled.
struct ReportState {
  // Loads the inputs and sets up the ground-truth integrator (no samples yet: see
  // estimate_ground_truth).
  ReportState(const ReportOptions& options, Clock::time_point start);

  // Adds ground-truth samples (doubling) until its standard error reaches `target`, the
  // sample cap or the time budget.
  void refine_within_budget(double target) {
    gt.add_samples_up_to(gto.initial_samples, &progress);
    while (gt.result().relative_rms_se > target && gt.samples_per_vertex() * 2 <= gto.max_samples &&
           gt.result().seconds * 2.0 <= budget)  // the next pass costs about all passes so far
      gt.add_samples_up_to(gt.samples_per_vertex() * 2, &progress);
  }
  // The map projected to `order` (projected once per order).
  const prt::ShLighting& lighting_for(int order) {
    auto it = lighting.find(order);
    if (it == lighting.end())
      it = lighting.emplace(order, relight::project_lighting(in.env, order, {})).first;
    return it->second;
  }
  // The interreflected SH bake of a setting; shared between settings that differ only in
  // precision.
  const bake::BakeResult& bake_for(const ReportSetting& s) {
    const auto key = std::make_tuple(s.order, s.samples, s.bounces);
    auto it = bakes.find(key);
    if (it == bakes.end()) {
      bake::BakeOptions bo;
      bo.kind = prt::TransferKind::Interreflected;
      bo.order = s.order, bo.samples = s.samples, bo.bounces = s.bounces, bo.seed = opt.seed;
      it = bakes.emplace(key, bake::bake_transfer(in.scene, bo)).first;
    }
    return it->second;
  }

  const ReportOptions& opt;
  const ReportLog log;
  const ReportSetting base;
  ReportInputs in;

  // Ground truth: a first estimate before the sweep, refined after it if the errors demand it.
  const bake::GroundTruthOptions gto;
  bake::GroundTruthIntegrator gt;
  bake::ConsoleProgress progress;
  const double budget;  // seconds
  bake::GroundTruthResult truth;

  // The sweep.
  std::map<int, prt::ShLighting> lighting;                      // per order
  std::map<std::tuple<int, int, int>, bake::BakeResult> bakes;  // (order, samples, bounces)
  std::vector<std::vector<float>> radiance;                     // per measurement
  std::vector<std::vector<float>> images;                       // per measurement
  // The converged reference of the projection/sampling split: the largest order and sample
  // count (quick: the samples axis' largest bake at the base order, reused).
  const int reference_order;
  const int reference_samples;
  std::vector<std::vector<double>> reference_b;  // per order of the split

  double e_min = INFINITY;             // the smallest error measured
  std::vector<double> cost, error;     // per measurement; failed ones are infinite
  std::vector<std::string> png_notes;  // why a plot has no PNG
  ReportResult result;
};

ReportState::ReportState(const ReportOptions& options, Clock::time_point start)
    : opt(options),
      log{options.verbose, start},
      base(base_setting(options.quick)),
      in(options, log),
      gto(report_ground_truth_options(options)),
      gt(in.scene, in.env, gto),
      progress(!options.verbose),
      budget(options.quick ? std::min(options.ground_truth_budget_seconds, 15.0)
                           : options.ground_truth_budget_seconds),
      reference_order(options.quick ? base_setting(true).order : 16),
      reference_samples(options.quick ? 1024 : 8192) {}

// ---- Phase 1: the sweep ----

// The ground truth's first estimate, before the sweep.
void estimate_ground_truth(ReportState& st) {
  st.refine_within_budget(st.opt.quick ? 0.03 : 0.01);
  st.truth = st.gt.result();
  st.log("ground truth: " + std::to_string(st.truth.samples_per_vertex) +
         " samples/vertex, relative RMS SE " + percent(st.truth.relative_rms_se) + ", " +
         seconds_text(st.truth.seconds));
}

// One measurement per unique setting of the axes, tagged with every axis it belongs to.
std::vector<ReportMeasurement> unique_measurements(const ReportOptions& opt) {
  std::vector<ReportMeasurement> measurements;
  for (const ReportAxis& axis : report_axes(opt.quick, opt.haar_cubes))
    for (const ReportSetting& s : axis.settings) {
      auto it = std::find_if(measurements.begin(), measurements.end(),
                             [&](const ReportMeasurement& m) { return same(m.setting, s); });
      if (it != measurements.end()) {
        if (it->axis.find(axis.name) == std::string::npos) it->axis += "+" + axis.name;
        continue;
      }
      ReportMeasurement m;
      m.axis = axis.name;
      m.setting = s;
      measurements.push_back(m);
    }
  return measurements;
}

// Haar bakes are shared between the settings of one cube size (they differ only in K) and
// dropped after the last of them.
struct HaarBake {
  double seconds = 0;
  uint64_t file_bytes = 0;
  std::unique_ptr<prt::HaarRelighter> relighter;
  bool albedo_folded = true;  // false: multiply by the vertex albedo (a textured scene)
  std::string failure;
  int uses_left = 0;
};

// The Haar bake of a setting's cube size, baked on first use.
HaarBake& haar_bake_for(ReportState& st, std::map<int, HaarBake>& haar_bakes,
                        const ReportSetting& s) {
  HaarBake& hb = haar_bakes[s.cube];
  if (hb.relighter || !hb.failure.empty()) return hb;
  bake::HaarBakeOptions ho;
  ho.transport = prt::TransferKind::Interreflected;
  ho.cube_size = s.cube;
  ho.supersample = 1;
  ho.compression.relative_threshold = kHaarThreshold;
  ho.compression.quantization = kHaarQuantization;
  ho.bounces = s.bounces;
  ho.seed = st.opt.seed;
  st.log("Haar bake, cube " + std::to_string(s.cube) + " (" +
         std::to_string(haar_coefficient_count(s.cube)) + " directions per vertex)");
  try {
    bake::HaarBakeResult r = bake::bake_haar_transfer(st.in.scene, ho);
    hb.seconds = r.stats.seconds_total;
    auto bytes = prt::encode_haar_transfer_file(r.file, "report");
    if (!bytes.ok()) {
      hb.failure = bytes.status().message();
      return hb;
    }
    hb.file_bytes = bytes->size();
    hb.albedo_folded = r.file.info.albedo_folded;
    hb.relighter = std::make_unique<prt::HaarRelighter>(std::move(r.file.transfer));
  } catch (const std::runtime_error& e) {  // e.g. the dense wavelet block is too large
    hb.failure = e.what();
  }
  return hb;
}

// Bakes (or reuses) and relights a Haar setting: its per-vertex radiance, empty on failure.
// Fills the setting's times, file size and failure.
std::vector<float> measure_haar(ReportState& st, std::map<int, HaarBake>& haar_bakes,
                                ReportMeasurement& m) {
  HaarBake& hb = haar_bake_for(st, haar_bakes, m.setting);
  std::vector<float> b;
  m.bake_seconds = hb.seconds;
  m.file_bytes = hb.file_bytes;
  m.failure = hb.failure;
  if (hb.relighter) {
    relight::HaarLightingOptions lo;
    lo.terms = m.setting.terms;
    lo.linear = false;
    const prt::SparseLighting haar_lighting =
        relight::project_haar_lighting(st.in.env, m.setting.cube, relight::kIdentityRotation, lo);
    b.assign(3 * st.in.V, 0.f);
    m.relight_seconds = INFINITY;
    for (int r = 0; r < 5; ++r) {
      const auto t0 = Clock::now();
      const prt::Status shaded = hb.relighter->shade(haar_lighting, b.data());
      m.relight_seconds = std::min(m.relight_seconds, since(t0));
      if (!shaded.ok()) {
        m.failure = shaded.message();
        b.clear();
        break;
      }
    }
    if (!hb.albedo_folded && !b.empty())  // as relight() does for SH
      for (std::size_t v = 0; v < st.in.scene.albedo.size(); ++v)
        for (int c = 0; c < 3; ++c) b[3 * v + c] *= st.in.scene.albedo[v][c];
  }
  if (--hb.uses_left == 0) hb.relighter.reset();
  return b;
}

// Bakes (or reuses) and relights an SH setting: its per-vertex radiance, empty on failure.
// Fills the setting's times, file size and failure.
std::vector<float> measure_sh(ReportState& st, ReportMeasurement& m) {
  const bake::BakeResult& baked = st.bake_for(m.setting);
  m.bake_seconds = baked.stats.seconds_total;
  prt::TransferData data = baked.data;
  data.storage = m.setting.precision;
  auto bytes = prt::encode_transfer_file(data, "report");
  std::vector<float> b;
  if (!bytes.ok()) {
    m.failure = bytes.status().message();
  } else {
    m.file_bytes = bytes->size();
    b = relight(data, m.setting.precision, st.lighting_for(m.setting.order), 5, &m.relight_seconds,
                &m.failure, st.in.scene);
  }
  return b;
}

// Keep only the base bake (the precision axis reuses it) and the reference bake of the
// projection/sampling split: memory stays bounded.
void drop_bake_unless_reused(ReportState& st, const ReportSetting& s) {
  const ReportSetting& b0 = st.base;
  if (!(s.order == b0.order && s.samples == b0.samples && s.bounces == b0.bounces) &&
      !(s.order == st.reference_order && s.samples == st.reference_samples && s.bounces == -1))
    st.bakes.erase(std::make_tuple(s.order, s.samples, s.bounces));
}

void score_against_truth(ReportMeasurement& m, const std::vector<float>& b,
                         const std::vector<double>& truth) {
  const VertexErrorStats e = compute_vertex_errors(b, truth);
  m.relative_rms = e.relative_rms, m.p99 = e.p99, m.max = e.max;
}

// Measures every setting of the sweep: bake, file size, relight time and error against the
// current ground truth; keeps each one's radiance and rendering for the refinement.
void run_sweep(ReportState& st) {
  st.result.measurements = unique_measurements(st.opt);
  std::map<int, HaarBake> haar_bakes;
  for (const ReportMeasurement& m : st.result.measurements)
    if (is_haar(m.setting)) ++haar_bakes[m.setting.cube].uses_left;
  const std::size_t total = st.result.measurements.size();
  for (std::size_t i = 0; i < total; ++i) {
    ReportMeasurement& m = st.result.measurements[i];
    const bool haar = is_haar(m.setting);
    const std::vector<float> b = haar ? measure_haar(st, haar_bakes, m) : measure_sh(st, m);
    st.radiance.push_back(b);
    st.images.push_back(b.empty() ? std::vector<float>() : st.in.render_radiance(b));
    if (m.failure.empty()) score_against_truth(m, b, st.truth.radiance);
    if (!haar) drop_bake_unless_reused(st, m.setting);
    st.log("[" + std::to_string(i + 1) + "/" + std::to_string(total) + "] " + describe(m.setting) +
           ": bake " + seconds_text(m.bake_seconds) + (haar ? " (one per cube)" : "") +
           ", relight " + seconds_text(m.relight_seconds) + ", error " +
           (m.failure.empty() ? percent(m.relative_rms) : "failed: " + m.failure));
  }
}

// ---- Phase 2: projection vs sampling error ----

// The split's orders (the order axis) and sample counts (the grid's, in sweep order).
void list_split_axes(ReportState& st) {
  ReportResult& result = st.result;
  for (const ReportAxis& axis : report_axes(st.opt.quick, st.opt.haar_cubes)) {
    if (axis.name == "order")
      for (const ReportSetting& s : axis.settings) result.orders.push_back(s.order);
    if (axis.name == "grid")
      for (const ReportSetting& s : axis.settings)
        if (std::find(result.split_samples.begin(), result.split_samples.end(), s.samples) ==
            result.split_samples.end())
          result.split_samples.push_back(s.samples);
  }
}

// The reference bake truncated to each order of the split, relit.
void relight_reference(ReportState& st) {
  ReportSetting rs = st.base;
  rs.order = st.reference_order, rs.samples = st.reference_samples, rs.bounces = -1;
  st.log("reference bake (order " + std::to_string(rs.order) + ", " + std::to_string(rs.samples) +
         " spp) for the projection/sampling split");
  const bake::BakeResult ref = st.bake_for(rs);
  for (int n : st.result.orders) {
    double unused;
    std::string failure;
    st.reference_b.push_back(
        to_double(relight(truncate_order(ref.data, n), prt::Precision::F32, st.lighting_for(n), 1,
                          &unused, &failure, st.in.scene)));
  }
}

// Projection error: each order's truncated reference against the ground truth.
void compute_projection_error(ReportState& st) {
  ReportResult& result = st.result;
  result.projection_error.clear();
  for (std::size_t j = 0; j < result.orders.size(); ++j)
    result.projection_error.push_back(
        compute_vertex_errors(st.reference_b[j], st.truth.radiance).relative_rms);
}

// Sampling error: each (order, samples) bake at the base bounces and f32 against the reference
// truncated to its order (NaN where the sweep has no such bake).
void compute_sampling_error(ReportState& st) {
  ReportResult& result = st.result;
  result.sampling_error.assign(result.split_samples.size(),
                               std::vector<double>(result.orders.size(), NAN));
  for (std::size_t i = 0; i < result.measurements.size(); ++i) {
    const ReportMeasurement& m = result.measurements[i];
    if (is_haar(m.setting) || !m.failure.empty() || m.setting.bounces != st.base.bounces ||
        m.setting.samples >= st.reference_samples || m.setting.precision != prt::Precision::F32)
      continue;
    const auto si =
        std::find(result.split_samples.begin(), result.split_samples.end(), m.setting.samples);
    const auto oi = std::find(result.orders.begin(), result.orders.end(), m.setting.order);
    if (si == result.split_samples.end() || oi == result.orders.end()) continue;
    result.sampling_error[static_cast<std::size_t>(si - result.split_samples.begin())]
                         [static_cast<std::size_t>(oi - result.orders.begin())] =
        compute_vertex_errors(st.radiance[i],
                              st.reference_b[static_cast<std::size_t>(oi - result.orders.begin())])
            .relative_rms;
  }
}

void split_projection_and_sampling(ReportState& st) {
  list_split_axes(st);
  relight_reference(st);
  compute_projection_error(st);
  compute_sampling_error(st);
}

// ---- Phase 3: the ground truth's refinement ----

// The smallest error measured (settings and projection errors).
double smallest_error(const ReportResult& result) {
  double e = INFINITY;
  for (const ReportMeasurement& m : result.measurements)
    if (m.failure.empty() && m.relative_rms > 0) e = std::min(e, m.relative_rms);
  for (double p : result.projection_error) e = std::min(e, p);
  return e;
}

// Is the ground truth good enough for the smallest error measured? Refines it if needed and
// scores the settings and the projection error again.
void refine_ground_truth(ReportState& st) {
  ReportResult& result = st.result;
  st.e_min = smallest_error(result);
  if (st.truth.relative_rms_se > st.e_min / 5.0) {
    st.log("refining the ground truth toward SE " + percent(st.e_min / 5.0) +
           " (1/5 of the smallest error)");
    st.refine_within_budget(st.e_min / 5.0);
    st.truth = st.gt.result();
    for (std::size_t i = 0; i < result.measurements.size(); ++i) {
      ReportMeasurement& m = result.measurements[i];
      if (!m.failure.empty()) continue;
      score_against_truth(m, st.radiance[i], st.truth.radiance);
    }
    compute_projection_error(st);
    st.e_min = smallest_error(result);
  }
}

// The image errors against a rendering of the final ground truth, and the ground truth's
// figures in the result.
void record_ground_truth(ReportState& st) {
  ReportResult& result = st.result;
  const bake::GroundTruthResult& truth = st.truth;
  const std::vector<float> truth_f(truth.radiance.begin(), truth.radiance.end());
  const std::vector<float> truth_image = st.in.render_radiance(truth_f);
  for (std::size_t i = 0; i < result.measurements.size(); ++i)
    if (result.measurements[i].failure.empty())
      result.measurements[i].image_relative_rms =
          relative_rms_image_error(st.images[i], truth_image, st.in.mask);
  result.ground_truth_samples = truth.samples_per_vertex;
  result.ground_truth_relative_se = truth.relative_rms_se;
  result.ground_truth_seconds = truth.seconds;
  result.ground_truth_mrays = truth.mrays_per_second();
  result.ground_truth_adequate = truth.relative_rms_se <= st.e_min / 5.0;
  st.log("ground truth: " + std::to_string(truth.samples_per_vertex) + " samples/vertex, SE " +
         percent(truth.relative_rms_se) + " vs smallest error " + percent(st.e_min) +
         (result.ground_truth_adequate ? " (adequate)" : " (NOT below 1/5 of it)"));
}

// Every setting's (bake time, error); failed ones never count.
void collect_costs(ReportState& st) {
  for (const ReportMeasurement& m : st.result.measurements) {
    st.cost.push_back(m.failure.empty() ? m.bake_seconds : INFINITY);
    st.error.push_back(m.failure.empty() ? m.relative_rms : INFINITY);
  }
}

// ---- Phase 4: `prt bake --auto` at each tolerance, against the same ground truth ----

ReportAuto measure_auto_bake(ReportState& st, const bake::AutoBakeOptions& ao) {
  ReportAuto a;
  a.tolerance = ao.tolerance;
  try {
    const auto t0 = Clock::now();
    const bake::AutoBakeResult ab = bake::bake_transfer_auto(st.in.scene, ao);
    a.bake_seconds = since(t0);
    a.order = ab.report.order;
    a.channels = ab.bake.data.channels;
    a.kind = bake::transfer_kind_name(ab.report.stored_kind);
    a.haar_recommended = ab.report.order_choice.haar_recommended;
    a.predicted_error = ab.report.predicted_error;
    auto bytes = prt::encode_transfer_file(ab.bake.data, "report");
    if (!bytes.ok()) throw std::runtime_error(bytes.status().message());
    a.file_bytes = bytes->size();
    double relight_seconds = 0;
    const std::vector<float> b =
        relight(ab.bake.data, ab.bake.data.storage, st.lighting_for(a.order), 1, &relight_seconds,
                &a.failure, st.in.scene);
    if (a.failure.empty()) {
      const VertexErrorStats e = compute_vertex_errors(b, st.truth.radiance);
      a.relative_rms = e.relative_rms, a.p99 = e.p99, a.max = e.max;
      a.cheapest_fixed = cheapest_reaching(st.cost, st.error, a.relative_rms);
    }
  } catch (const std::exception& e) {
    a.failure = e.what();
  }
  return a;
}

void measure_auto_bakes(ReportState& st) {
  const std::vector<double> auto_tolerances =
      st.opt.auto_tolerances ? *st.opt.auto_tolerances : default_auto_tolerances(st.opt.quick);
  if (auto_tolerances.empty()) return;
  bake::AutoBakeOptions ao;
  ao.bake.seed = st.opt.seed;
  ao.lighting_order = bake::kMaxBakeOrder;  // as `prt bake --auto --env`
  ao.lighting = sh::project(st.in.env, ao.lighting_order);
  for (double tolerance : auto_tolerances) {
    ao.tolerance = tolerance;
    const ReportAuto a = measure_auto_bake(st, ao);
    st.log("--auto, tolerance " + percent(tolerance) + ": order " + std::to_string(a.order) +
           ", bake " + seconds_text(a.bake_seconds) + ", predicted " + percent(a.predicted_error) +
           ", measured " + (a.failure.empty() ? percent(a.relative_rms) : "failed: " + a.failure));
    st.result.autos.push_back(a);
  }
}

// Pareto front over (bake time, error).
void mark_pareto_front(ReportState& st) {
  const std::vector<bool> front = pareto_front(st.cost, st.error);
  for (std::size_t i = 0; i < front.size(); ++i)
    st.result.measurements[i].on_pareto_front = front[i];
}

// ---- Phase 5: the outputs ----

std::string output_path(const ReportState& st, const std::string& name) {
  return (std::filesystem::path(st.opt.output_dir) / name).string();
}

// Writes a file of the output directory atomically and lists it in the result.
void write_output(ReportState& st, const std::string& name, const std::string& text) {
  write_text_file(output_path(st, name), text);
  st.result.files_written.push_back(output_path(st, name));
}

// The error levels marked on the plots and tabulated in the summary.
std::vector<std::pair<double, std::string>> error_thresholds() {
  return {{0.01, "1%"}, {0.05, "5%"}, {0.10, "10%"}};
}

// Haar cube sizes measured, in sweep order.
std::vector<int> haar_cubes_swept(const ReportResult& result) {
  std::vector<int> cubes;
  for (const ReportMeasurement& m : result.measurements)
    if (is_haar(m.setting) && std::find(cubes.begin(), cubes.end(), m.setting.cube) == cubes.end())
      cubes.push_back(m.setting.cube);
  return cubes;
}

// A Haar cube's measured (not failed) rows, by ascending K.
std::vector<std::size_t> haar_rows_by_terms(const ReportResult& result, int cube) {
  std::vector<std::size_t> rows;
  for (std::size_t i = 0; i < result.measurements.size(); ++i) {
    const ReportMeasurement& m = result.measurements[i];
    if (is_haar(m.setting) && m.setting.cube == cube && m.failure.empty()) rows.push_back(i);
  }
  std::sort(rows.begin(), rows.end(), [&](std::size_t a, std::size_t b) {
    return haar_terms_used(result.measurements[a].setting) <
           haar_terms_used(result.measurements[b].setting);
  });
  return rows;
}

void write_results_csv(ReportState& st) {
  std::ostringstream csv;
  // basis sh: order and samples set, cube and terms empty; basis haar: the other way round
  // (terms = the lighting terms used, 6N² for all).
  csv << "axis,basis,order,samples,cube,terms,bounces,precision,bake_seconds,relight_seconds,"
         "file_bytes,relative_rms,p99_relative,max_relative,image_relative_rms,pareto,failure\n";
  for (const ReportMeasurement& m : st.result.measurements) {
    std::string failure = m.failure;
    std::replace(failure.begin(), failure.end(), ',', ';');
    const ReportSetting& s = m.setting;
    csv << m.axis << "," << basis_name(s) << ",";
    if (is_haar(s))
      csv << ",," << s.cube << "," << haar_terms_used(s) << ",";
    else
      csv << s.order << "," << s.samples << ",,,";
    csv << bounces_name(s.bounces) << "," << storage_name(s) << "," << m.bake_seconds << ","
        << m.relight_seconds << "," << m.file_bytes << "," << m.relative_rms << "," << m.p99 << ","
        << m.max << "," << m.image_relative_rms << "," << (m.on_pareto_front ? 1 : 0) << ","
        << failure << "\n";
  }
  write_output(st, "results.csv", csv.str());
}

nlohmann::json error_definitions_json(const relight::RenderOptions& ropt) {
  return {{"relative_rms", "sqrt(sum_p |B_p - B_gt,p|^2) / sqrt(sum_p |B_gt,p|^2), |.| RGB norm"},
          {"p99_relative/max_relative",
           "per-vertex |B_p - B_gt,p| / max(|B_gt,p|, 0.05 * RMS_p |B_gt,p|): 99th percentile "
           "(nearest rank) and maximum"},
          {"image_relative_rms",
           "relative RMS over the pixels that show the scene, " + std::to_string(ropt.width) + "x" +
               std::to_string(ropt.height) + " with 2x2 samples, same camera for both"},
          {"bake_seconds",
           "wall time of bake_transfer (SH) or bake_haar_transfer (Haar: one bake per cube size, "
           "shared by its K settings), all threads"},
          {"relight_seconds",
           "best of 5 wall times of shading every vertex (SH: all threads; Haar: "
           "HaarRelighter::shade on one thread, as prt relight)"}};
}

nlohmann::json measurement_json(const ReportMeasurement& m) {
  const ReportSetting& s = m.setting;
  const nlohmann::json none;  // null: the field does not apply to this basis
  return {{"axis", m.axis},
          {"basis", basis_name(s)},
          {"order", is_haar(s) ? none : nlohmann::json(s.order)},
          {"samples", is_haar(s) ? none : nlohmann::json(s.samples)},
          {"cube", is_haar(s) ? nlohmann::json(s.cube) : none},
          {"terms", is_haar(s) ? nlohmann::json(haar_terms_used(s)) : none},
          {"all_terms", is_haar(s) ? nlohmann::json(s.terms <= 0) : none},
          {"bounces", bounces_name(s.bounces)},
          {"precision", storage_name(s)},
          {"bake_seconds", m.bake_seconds},
          {"relight_seconds", m.relight_seconds},
          {"file_bytes", m.file_bytes},
          {"relative_rms", m.relative_rms},
          {"p99_relative", m.p99},
          {"max_relative", m.max},
          {"image_relative_rms", m.image_relative_rms},
          {"pareto", m.on_pareto_front},
          {"failure", m.failure}};
}

nlohmann::json auto_json(const ReportAuto& a) {
  return {{"tolerance", a.tolerance},
          {"order", a.order},
          {"channels", a.channels},
          {"kind", a.kind},
          {"haar_recommended", a.haar_recommended},
          {"predicted_error", a.predicted_error},
          {"predicted_error_scope", "excludes the mesh's interpolation of interreflected light"},
          {"bake_seconds", a.bake_seconds},
          {"file_bytes", a.file_bytes},
          {"relative_rms", a.relative_rms},
          {"p99_relative", a.p99},
          {"max_relative", a.max},
          {"cheapest_fixed_index", a.cheapest_fixed},
          {"failure", a.failure}};
}

void write_results_json(ReportState& st) {
  const ReportOptions& opt = st.opt;
  const ReportResult& result = st.result;
  const bake::GroundTruthResult& truth = st.truth;
  nlohmann::json j;
  j["sh_basis"] = sh::kBasisConvention;
  j["scene"] = opt.scene_path;
  j["environment"] = opt.environment_path;
  j["environment_layout"] = st.in.layout_note;
  j["vertices"] = st.in.V;
  j["quick"] = opt.quick;
  j["base_setting"] = {{"order", st.base.order},
                       {"samples", st.base.samples},
                       {"bounces", bounces_name(st.base.bounces)},
                       {"precision", "f32"}};
  j["error_definitions"] = error_definitions_json(st.in.ropt);
  j["ground_truth"] = {{"samples_per_vertex", truth.samples_per_vertex},
                       {"relative_rms_standard_error", truth.relative_rms_se},
                       {"seconds", truth.seconds},
                       {"rays", truth.rays},
                       {"mrays_per_second", truth.mrays_per_second()},
                       {"max_bounces", st.gto.max_bounces},
                       {"adequate", result.ground_truth_adequate},
                       {"smallest_error_measured", st.e_min}};
  j["haar"] = {{"transfer", "interreflected, bounces as the base setting"},
               {"directions", "one per cube texel (6N^2 per vertex, texel centres)"},
               {"relative_threshold", kHaarThreshold},
               {"quantization_bits", static_cast<int>(kHaarQuantization)},
               {"lighting", "non-linear: the K largest area-weighted wavelet coefficients"},
               {"relight_seconds",
                "best of 5, HaarRelighter::shade on one thread (as prt "
                "relight); lighting selection not included"}};
  nlohmann::json rows = nlohmann::json::array();
  for (const ReportMeasurement& m : result.measurements) rows.push_back(measurement_json(m));
  j["results"] = rows;
  nlohmann::json autos = nlohmann::json::array();
  for (const ReportAuto& a : result.autos) autos.push_back(auto_json(a));
  j["auto"] = autos;
  j["split"] = {{"orders", result.orders},
                {"projection_error", result.projection_error},
                {"reference_samples", st.reference_samples},
                {"sampling_samples", result.split_samples},
                {"sampling_error", result.sampling_error}};
  write_output(st, "results.json", j.dump(2) + "\n");
}

// Writes STEM.svg and, through rsvg-convert, STEM.png (else notes why not).
void write_plot(ReportState& st, const PlotSpec& spec, const std::string& stem) {
  write_output(st, stem + ".svg", render_svg(spec));
  std::string why;
  if (convert_svg_to_png(output_path(st, stem + ".svg"), output_path(st, stem + ".png"), 1.5, &why))
    st.result.files_written.push_back(output_path(st, stem + ".png"));
  else
    st.png_notes.push_back(why);
}

// Pareto plot: the SH grid, one line per order through its sample counts.
std::vector<PlotSeries> grid_series(const ReportResult& result) {
  std::vector<int> grid_orders;
  for (const ReportMeasurement& m : result.measurements)
    if (m.axis.find("grid") != std::string::npos &&
        std::find(grid_orders.begin(), grid_orders.end(), m.setting.order) == grid_orders.end())
      grid_orders.push_back(m.setting.order);
  std::sort(grid_orders.begin(), grid_orders.end());
  std::vector<PlotSeries> series;
  for (std::size_t g = 0; g < grid_orders.size(); ++g) {
    PlotSeries s;
    s.label = "SH order " + std::to_string(grid_orders[g]) + ", samples varied";
    s.color = kPalette[g % 10];
    s.line_width = 1.5;
    std::vector<std::pair<int, std::size_t>> pts;
    for (std::size_t i = 0; i < result.measurements.size(); ++i) {
      const ReportMeasurement& m = result.measurements[i];
      if (m.axis.find("grid") != std::string::npos && m.setting.order == grid_orders[g] &&
          m.failure.empty())
        pts.emplace_back(m.setting.samples, i);
    }
    std::sort(pts.begin(), pts.end());
    for (const auto& [n, i] : pts) {
      s.x.push_back(result.measurements[i].bake_seconds);
      s.y.push_back(result.measurements[i].relative_rms);
    }
    series.push_back(s);
  }
  return series;
}

// Pareto plot: the SH settings off the grid, as markers.
PlotSeries other_axes_series(const ReportResult& result) {
  PlotSeries other;
  other.label = "SH, other axes (bounces, order, samples, f16)";
  other.color = "#555555";
  other.line = false;
  other.marker = Marker::Diamond;
  other.marker_size = 3.5;
  for (const ReportMeasurement& m : result.measurements)
    if (!is_haar(m.setting) && m.axis.find("grid") == std::string::npos && m.failure.empty()) {
      other.x.push_back(m.bake_seconds);
      other.y.push_back(m.relative_rms);
    }
  return other;
}

// Pareto plot: one Haar series per cube size; its K settings share the bake, so they stand in
// a column.
std::vector<PlotSeries> haar_bake_series(const ReportResult& result,
                                         const std::vector<int>& cubes) {
  std::vector<PlotSeries> series;
  for (std::size_t c = 0; c < cubes.size(); ++c) {
    PlotSeries h;
    h.label = "Haar cube " + std::to_string(cubes[c]) + ", K varied (column)";
    h.color = kHaarPalette[c % 4];
    h.marker = Marker::Square;
    h.marker_size = 5;
    h.line_width = 1.5;
    for (std::size_t i : haar_rows_by_terms(result, cubes[c])) {
      h.x.push_back(result.measurements[i].bake_seconds);
      h.y.push_back(result.measurements[i].relative_rms);
    }
    series.push_back(h);
  }
  return series;
}

// Pareto plot: `prt bake --auto` at each tolerance (not part of the front, which is over the
// sweep).
PlotSeries auto_series(const ReportResult& result) {
  PlotSeries au;
  au.label = "prt bake --auto, by tolerance";
  au.color = "#000000";
  au.line = false;
  au.marker = Marker::Triangle;
  au.marker_size = 6;
  for (const ReportAuto& a : result.autos)
    if (a.failure.empty()) {
      char label[32];
      std::snprintf(label, sizeof label, "auto %g%%", 100.0 * a.tolerance);
      au.x.push_back(a.bake_seconds);
      au.y.push_back(a.relative_rms);
      au.point_labels.push_back(label);
    }
  return au;
}

// Pareto plot: the front itself, by bake time, each point labelled with its setting.
PlotSeries pareto_front_series(const ReportResult& result) {
  PlotSeries f;
  f.label = "Pareto front";
  f.color = "#d62728";
  f.dashed = true;
  f.marker = Marker::Circle;
  f.marker_size = 6.5;
  f.line_width = 2.0;
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < result.measurements.size(); ++i)
    if (result.measurements[i].on_pareto_front) idx.push_back(i);
  std::sort(idx.begin(), idx.end(), [&](std::size_t a, std::size_t b) {
    return result.measurements[a].bake_seconds < result.measurements[b].bake_seconds;
  });
  for (std::size_t i : idx) {
    f.x.push_back(result.measurements[i].bake_seconds);
    f.y.push_back(result.measurements[i].relative_rms);
    f.point_labels.push_back(short_label(result.measurements[i].setting));
  }
  return f;
}

void write_pareto_plot(ReportState& st, const std::vector<int>& haar_cubes) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against bake time (" + std::string(st.opt.quick ? "quick" : "full") + " sweep)";
  p.x_label = "bake time, seconds (wall, all threads; log)";
  p.y_label = "relative RMS error of exit radiance vs ground truth (log)";
  p.log_x = p.log_y = true;
  p.y_as_percent = true;
  p.legend = LegendCorner::Auto;  // a free corner, else beside the plot
  for (const auto& t : error_thresholds()) p.reference_lines.push_back(t);
  p.series = grid_series(result);
  p.series.push_back(other_axes_series(result));
  for (const PlotSeries& h : haar_bake_series(result, haar_cubes)) p.series.push_back(h);
  const PlotSeries au = auto_series(result);
  if (!au.x.empty()) p.series.push_back(au);
  // Front drawn first so the other markers stay visible on top of its big circles.
  p.series.insert(p.series.begin(), pareto_front_series(result));
  write_plot(st, p, "pareto");
}

void write_error_vs_order_plot(ReportState& st) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against SH order: projection vs sampling";
  p.legend = LegendCorner::BottomRight;  // the sampling curves rise into the top right
  p.x_label = "SH order n (n^2 coefficients per channel)";
  p.y_label = "relative RMS error (log)";
  p.log_y = true;
  p.y_as_percent = true;
  PlotSeries proj;
  proj.label = "projection: order-n converged transfer (" + std::to_string(st.reference_samples) +
               " spp) vs ground truth";
  proj.color = "#000000";
  proj.line_width = 3;
  proj.marker = Marker::Square;
  for (std::size_t j = 0; j < result.orders.size(); ++j) {
    proj.x.push_back(result.orders[j]);
    proj.y.push_back(result.projection_error[j]);
  }
  p.series.push_back(proj);
  for (std::size_t si = 0; si < result.split_samples.size(); ++si) {
    PlotSeries s;
    s.label =
        "sampling: " + std::to_string(result.split_samples[si]) + " spp vs converged order-n bake";
    s.color = kPalette[si < 3 ? si : si + 1];  // index 3 (red) is the total's
    s.dashed = true;
    s.marker = Marker::Triangle;
    for (std::size_t j = 0; j < result.orders.size(); ++j)
      if (std::isfinite(result.sampling_error[si][j])) {
        s.x.push_back(result.orders[j]);
        s.y.push_back(result.sampling_error[si][j]);
      }
    p.series.push_back(s);
  }
  PlotSeries total_s;
  total_s.label =
      "total: base setting (" + std::to_string(st.base.samples) + " spp) vs ground truth";
  total_s.color = "#d62728";
  total_s.marker = Marker::Circle;
  for (const ReportMeasurement& m : result.measurements)
    if (m.axis.find("order") != std::string::npos && m.failure.empty()) {
      total_s.x.push_back(m.setting.order);
      total_s.y.push_back(m.relative_rms);
    }
  p.series.push_back(total_s);
  p.reference_lines.push_back({st.truth.relative_rms_se, "ground-truth standard error"});
  write_plot(st, p, "error_vs_order");
}

void write_haar_terms_plot(ReportState& st, const std::vector<int>& haar_cubes) {
  const ReportResult& result = st.result;
  PlotSpec p;
  p.title = "Error against lighting terms: Haar (non-linear) and SH";
  p.x_label = "lighting terms per colour channel (Haar: K kept; SH: n^2; log)";
  p.y_label = "relative RMS error of exit radiance vs ground truth (log)";
  p.log_x = p.log_y = true;
  p.y_as_percent = true;
  p.legend = LegendCorner::Auto;  // errors fall to the right: usually bottom left is free
  for (std::size_t c = 0; c < haar_cubes.size(); ++c) {
    PlotSeries h;
    const int cube = haar_cubes[c];
    h.label = "Haar cube " + std::to_string(cube) +
              " (6N^2 = " + std::to_string(haar_coefficient_count(cube)) + "), interreflected";
    h.color = kHaarPalette[c % 4];
    h.marker = Marker::Square;
    for (std::size_t i : haar_rows_by_terms(result, cube)) {
      h.x.push_back(static_cast<double>(haar_terms_used(result.measurements[i].setting)));
      h.y.push_back(result.measurements[i].relative_rms);
    }
    p.series.push_back(h);
  }
  PlotSeries sh_s;
  sh_s.label = "SH order n (order axis, " + std::to_string(st.base.samples) + " spp)";
  sh_s.color = "#1f77b4";
  sh_s.marker = Marker::Circle;
  sh_s.dashed = true;
  for (const ReportMeasurement& m : result.measurements)
    if (!is_haar(m.setting) && m.axis.find("order") != std::string::npos && m.failure.empty()) {
      sh_s.x.push_back(static_cast<double>(m.setting.order) * m.setting.order);
      sh_s.y.push_back(m.relative_rms);
    }
  p.series.push_back(sh_s);
  // The ground truth's SE gets its own line unless it sits on a threshold line (within 25%),
  // where the two labels would print over each other: then the threshold's label says both.
  bool se_shown = false;
  for (const auto& t : error_thresholds()) {
    const double ratio = st.truth.relative_rms_se / t.first;
    if (ratio > 0.8 && ratio < 1.25) {
      p.reference_lines.push_back({t.first, t.second + " ≈ ground-truth SE"});
      se_shown = true;
    } else {
      p.reference_lines.push_back(t);
    }
  }
  if (!se_shown) p.reference_lines.push_back({st.truth.relative_rms_se, "ground-truth SE"});
  write_plot(st, p, "haar_error_vs_terms");
}

// summary.md: the title and the ground truth.
void summarize_ground_truth(std::ostream& md, const ReportState& st) {
  const ReportOptions& opt = st.opt;
  const bake::GroundTruthResult& truth = st.truth;
  md << "# prt report: error against run time\n\n"
     << "Scene `" << opt.scene_path << "` (" << st.in.V << " vertices), environment `"
     << opt.environment_path << "` (" << st.in.layout_note << "), "
     << (opt.quick ? "quick" : "full") << " sweep. Generated by `prt report"
     << (opt.quick ? " --quick" : "") << "`.\n\n"
     << "## Ground truth\n\n"
     << "Per-vertex Monte Carlo integration against the environment map itself "
        "(bake/ground_truth.h: luminance importance sampling of the map and cosine sampling "
        "combined by MIS, Embree visibility, diffuse path tracing with Russian roulette, cap "
     << st.gto.max_bounces << " bounces): " << truth.samples_per_vertex
     << " samples per vertex, relative RMS standard error **" << percent(truth.relative_rms_se)
     << "**, " << seconds_text(truth.seconds) << " (" << truth.rays << " rays, "
     << static_cast<int>(truth.mrays_per_second() * 10) / 10.0 << " Mrays/s).\n\n"
     << "The smallest error measured below is " << percent(st.e_min) << "; the ground truth's "
     << "standard error is " << percent(truth.relative_rms_se) << ", "
     << (st.result.ground_truth_adequate
             ? "at most 1/5 of it, so every error below is resolved."
             : "**more than 1/5 of it**: errors near " + percent(st.e_min) +
                   " are inflated by ground-truth noise (they add in quadrature)" +
                   std::string(opt.quick ? ". Run the full report for more."
                                         : "; raise --ground-truth-budget for more."))
     << "\n\n";
}

// summary.md: the fastest setting reaching each threshold.
void summarize_cheapest_settings(std::ostream& md, const ReportState& st) {
  md << "## Cheapest settings\n\n| target | cheapest setting | bake | relight | file | error "
        "| p99 | image |\n|---|---|---|---|---|---|---|---|\n";
  for (const auto& t : error_thresholds()) {
    const long i = cheapest_reaching(st.cost, st.error, t.first);
    if (i < 0) {
      md << "| " << t.second << " | none of the settings reached it | | | | | | |\n";
      continue;
    }
    const ReportMeasurement& m = st.result.measurements[static_cast<std::size_t>(i)];
    md << "| " << t.second << " | " << describe(m.setting) << " | " << seconds_text(m.bake_seconds)
       << " | " << seconds_text(m.relight_seconds) << " | " << m.file_bytes / 1024 << " KiB | "
       << percent(m.relative_rms) << " | " << percent(m.p99) << " | "
       << percent(m.image_relative_rms) << " |\n";
  }
}

// summary.md: the Pareto and projection/sampling plots, with what they show.
void summarize_plots(std::ostream& md, const ReportState& st, const std::vector<int>& haar_cubes) {
  md << "\nBoth bases compete: SH (spherical harmonics) and Haar (wavelets on a cube map, "
        "non-linear lighting approximation). Cost is the bake's wall time; the relight time "
        "(shading every vertex once) is shown beside it.\n\n## Plots\n\n"
     << "![Error against bake time](pareto.png)\n\n"
     << "Log-log: every measured setting; lines join the SH (order × samples) grid at fixed "
        "order"
     << (haar_cubes.empty()
             ? ""
             : "; squares are Haar settings, one colour per cube size, standing in a column "
               "because the K settings of a cube share its bake")
     << "; the dashed red line is the Pareto front over all settings (no other setting is both "
        "faster and more accurate)"
     << (st.result.autos.empty() ? ""
                                 : "; black triangles are `prt bake --auto` at each tolerance "
                                   "(below), not part of the front")
     << ". Dotted lines mark 1%, 5%, 10%. ([SVG](pareto.svg))\n\n"
     << "![Error against SH order](error_vs_order.png)\n\n"
     << "Projection error: order-n relighting with a converged " << st.reference_samples
     << "-sample transfer against the ground truth (what order n can do at best). Sampling "
        "error: the order-n bake at N samples against that converged order-n transfer (what "
        "finite sampling adds). The total error of the base setting is in red. "
        "([SVG](error_vs_order.svg))\n\n";
}

// The measurement of a Haar (cube, K), or null.
const ReportMeasurement* find_haar_row(const ReportResult& result, int cube, int64_t k) {
  for (const ReportMeasurement& m : result.measurements)
    if (is_haar(m.setting) && m.setting.cube == cube && m.setting.terms == k) return &m;
  return nullptr;
}

// summary.md, Haar section: the error table, K by cube size.
void summarize_haar_errors(std::ostream& md, const ReportResult& result,
                           const std::vector<int>& haar_cubes) {
  md << "| K |";
  for (int cube : haar_cubes) md << " cube " << cube << " |";
  md << "\n|---|";
  for (std::size_t c = 0; c < haar_cubes.size(); ++c) md << "---|";
  md << "\n";
  std::vector<int64_t> ks;  // distinct K values (0 = all), all last
  for (const ReportMeasurement& m : result.measurements)
    if (is_haar(m.setting) && std::find(ks.begin(), ks.end(), m.setting.terms) == ks.end())
      ks.push_back(m.setting.terms);
  std::sort(ks.begin(), ks.end(), [](int64_t a, int64_t b) {
    return (a <= 0 ? INT64_MAX : a) < (b <= 0 ? INT64_MAX : b);
  });
  for (int64_t k : ks) {
    md << "| " << (k > 0 ? std::to_string(k) : std::string("all (6N²)")) << " |";
    for (int cube : haar_cubes) {
      const ReportMeasurement* m = find_haar_row(result, cube, k);
      md << " " << (!m ? "—" : !m->failure.empty() ? "failed" : percent(m->relative_rms)) << " |";
    }
    md << "\n";
  }
}

// summary.md: the Haar section (when the Haar axis was swept).
void summarize_haar(std::ostream& md, const ReportState& st, const std::vector<int>& haar_cubes) {
  const ReportResult& result = st.result;
  md << "## Haar wavelets\n\n"
     << "Interreflected Haar transfer (as `prt bake --basis haar --cube N`: bounces "
     << bounces_name(st.base.bounces) << ", one direction per cube texel, per-vertex threshold "
     << kHaarThreshold << ", " << static_cast<int>(kHaarQuantization)
     << "-bit), relit with the K largest area-weighted lighting coefficients (as `prt "
        "relight --terms K`). Relative RMS error against the same ground truth:\n\n";
  summarize_haar_errors(md, result, haar_cubes);
  md << "| bake |";
  for (int cube : haar_cubes) {
    const ReportMeasurement* m = find_haar_row(result, cube, 0);
    md << " " << (m && m->failure.empty() ? seconds_text(m->bake_seconds) : "—") << " |";
  }
  md << "\n| file |";
  for (int cube : haar_cubes) {
    const ReportMeasurement* m = find_haar_row(result, cube, 0);
    md << " " << (m && m->failure.empty() ? std::to_string(m->file_bytes / 1024) + " KiB" : "—")
       << " |";
  }
  md << "\n\n";
  for (int cube : haar_cubes) {
    const ReportMeasurement* m = find_haar_row(result, cube, 0);
    if (m && !m->failure.empty()) md << "Cube " << cube << " failed: " << m->failure << "\n\n";
  }
  md << "![Error against lighting terms](haar_error_vs_terms.png)\n\n"
     << "Error against the number of lighting terms per colour channel: Haar with K kept "
        "terms per cube size, and SH order n (n² terms, the order axis at the base sample "
        "count) for comparison. The Haar curves level off at the error of their cube "
        "resolution and transfer; the dotted lines mark 1%, 5%, 10% and the ground truth's "
        "standard error. ([SVG](haar_error_vs_terms.svg))\n\n";
}

// summary.md: every setting measured.
void summarize_settings(std::ostream& md, const ReportState& st,
                        const std::vector<int>& haar_cubes) {
  md << "## Settings\n\nBase setting: " << describe(st.base)
     << " (interreflected transfer). Each axis varies one parameter around it; the grid "
        "varies order and samples together"
     << (haar_cubes.empty() ? "" : "; the haar axis varies cube size and lighting terms") << ".\n\n"
     << "| axis | basis | order | spp | cube | terms | bounces | prec. | bake | relight | file "
        "| rel. RMS | p99 | max | image | front |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ReportMeasurement& m : st.result.measurements) {
    const ReportSetting& s = m.setting;
    md << "| " << m.axis << " | " << basis_name(s) << " | ";
    if (is_haar(s))
      md << " | | " << s.cube << " | " << terms_text(s) << " | ";
    else
      md << s.order << " | " << s.samples << " | | | ";
    md << bounces_name(s.bounces) << " | " << storage_name(s) << " | ";
    if (!m.failure.empty()) {
      md << "failed: " << m.failure << " | | | | | | | |\n";
      continue;
    }
    md << seconds_text(m.bake_seconds) << " | " << seconds_text(m.relight_seconds) << " | "
       << m.file_bytes / 1024 << " KiB | " << percent(m.relative_rms) << " | " << percent(m.p99)
       << " | " << percent(m.max) << " | " << percent(m.image_relative_rms) << " | "
       << (m.on_pareto_front ? "yes" : "") << " |\n";
  }
}

// summary.md: the `prt bake --auto` rows (when there are any).
void summarize_auto(std::ostream& md, const ReportResult& result) {
  md << "\n## Scene-adaptive bake (`prt bake --auto`)\n\n"
     << "`prt bake --auto --env` at each tolerance (bake/adaptive/adaptive_baker.h: the lighting "
        "it "
        "adapts to is this map projected at order "
     << bake::kMaxBakeOrder
     << "), measured against the same ground truth. Its prediction leaves out the mesh's "
        "interpolation of interreflected light, which the measured error includes. The last "
        "columns name the fixed setting above that reaches the measured error with the "
        "fastest bake.\n\n| tolerance | chosen | predicted | measured | p99 | bake | file | "
        "fastest fixed setting at that error | its bake | its file | bake speed-up |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const ReportAuto& a : result.autos) {
    md << "| " << percent(a.tolerance) << " | ";
    if (!a.failure.empty()) {
      md << "failed: " << a.failure << " | | | | | | | | | |\n";
      continue;
    }
    md << a.kind << ", SH order " << a.order << ", " << a.channels << " channel"
       << (a.channels == 1 ? "" : "s")
       << (a.haar_recommended ? " (no SH order meets it: Haar recommended)" : "") << " | "
       << percent(a.predicted_error) << " | " << percent(a.relative_rms) << " | " << percent(a.p99)
       << " | " << seconds_text(a.bake_seconds) << " | " << a.file_bytes / 1024 << " KiB | ";
    if (a.cheapest_fixed < 0) {
      md << "none reaches it | | | |\n";
      continue;
    }
    const ReportMeasurement& m = result.measurements[static_cast<std::size_t>(a.cheapest_fixed)];
    char speed[32];
    std::snprintf(speed, sizeof speed, "%.2f×", m.bake_seconds / a.bake_seconds);
    md << describe(m.setting) << " (" << percent(m.relative_rms) << ") | "
       << seconds_text(m.bake_seconds) << " | " << m.file_bytes / 1024 << " KiB | " << speed
       << " |\n";
  }
}

// summary.md: the definitions of the errors, lighting, times and file sizes.
void summarize_definitions(std::ostream& md, const ReportState& st) {
  md << "\n## Definitions\n\n"
     << "- B: per-vertex exit radiance (RGB), |·| its Euclidean norm. **rel. RMS** = "
        "√(Σ|B − B_gt|²)/√(Σ|B_gt|²) over vertices.\n"
     << "- **p99 / max**: 99th percentile (nearest rank) and maximum over vertices of "
        "|B − B_gt| / max(|B_gt|, 0.05·RMS|B_gt|) (the floor keeps near-black vertices from "
        "dividing by ~0).\n"
     << "- **image**: relative RMS over the pixels that show the scene, rendering both with "
        "the relight renderer ("
     << st.in.ropt.width << "×" << st.in.ropt.height << ", 2×2 samples, same camera).\n"
     << "- Lighting: SH: the map projected to order n (no window); " << sh::kBasisConvention
     << ". Haar: the map resampled to the N-cube (exact area weights), wavelet-transformed, the "
        "K largest area-weighted coefficients kept (relight/haar_relight.h).\n"
     << "- Times: wall clock on this machine; bake with all threads; relight = best of 5 (SH "
        "all threads; Haar one thread, as `prt relight`; projecting or selecting the lighting "
        "not included). A Haar bake is shared by the K settings of its cube size.\n"
     << "- File: the coefficient file's size (SH f32/f16; Haar sparse "
     << static_cast<int>(kHaarQuantization) << "-bit with per-vertex threshold " << kHaarThreshold
     << ").\n";
  for (const std::string& n : st.png_notes) md << "- PNG not written: " << n << "\n";
}

void write_summary(ReportState& st, const std::vector<int>& haar_cubes) {
  std::ostringstream md;
  summarize_ground_truth(md, st);
  summarize_cheapest_settings(md, st);
  summarize_plots(md, st, haar_cubes);
  if (!haar_cubes.empty()) summarize_haar(md, st, haar_cubes);
  summarize_settings(md, st, haar_cubes);
  if (!st.result.autos.empty()) summarize_auto(md, st.result);
  summarize_definitions(md, st);
  write_output(st, "summary.md", md.str());
}

// results.csv, results.json, the plots (SVG, and PNG when rsvg-convert is there), summary.md.
void write_outputs(ReportState& st) {
  write_results_csv(st);
  write_results_json(st);
  const std::vector<int> haar_cubes = haar_cubes_swept(st.result);
  write_pareto_plot(st, haar_cubes);
  write_error_vs_order_plot(st);
  if (!haar_cubes.empty()) write_haar_terms_plot(st, haar_cubes);
  write_summary(st, haar_cubes);
}

}  // namespace

ReportResult run_report(const ReportOptions& opt) {
  const auto t_start = Clock::now();
  check_haar_cubes(opt);
  create_output_dir(opt);
  ReportState st(opt, t_start);
  // Phase 1: the sweep, against a first estimate of the ground truth.
  estimate_ground_truth(st);
  run_sweep(st);
  // Phase 2: projection vs sampling error.
  split_projection_and_sampling(st);
  // Phase 3: the ground truth's refinement, then every setting's cost and error.
  refine_ground_truth(st);
  record_ground_truth(st);
  collect_costs(st);
  // Phase 4: `prt bake --auto` at each tolerance, and the Pareto front.
  measure_auto_bakes(st);
  mark_pareto_front(st);
  // Phase 5: the outputs.
  write_outputs(st);
  st.log("done in " + seconds_text(since(t_start)) + "; wrote " +
         std::to_string(st.result.files_written.size()) + " files to " + opt.output_dir);
  return std::move(st.result);
}

}  // namespace prt::report
