// report/src/report_sweep.cpp — the sweep of `prt report`: every setting baked, relit and scored
// against the ground truth; the projection/sampling split; `prt bake --auto` at each tolerance.

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

#include "bake/adaptive/adaptive_baker.h"
#include "bake/haar_baker.h"
#include "bake/transfer_baker.h"
#include "prt/diffuse/relighter.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/transfer_file.h"
#include "prt/haar/relighter.h"
#include "relight/haar_relight.h"
#include "relight/relight_pipeline.h"
#include "report/report_metrics.h"
#include "report_state.h"
#include "sh/projection.h"

namespace prt::report::detail {

namespace {

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
  ho.memory_limit = st.opt.memory_limit;
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

}  // namespace

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

// Projection error: each order's truncated reference against the ground truth.
void compute_projection_error(ReportState& st) {
  ReportResult& result = st.result;
  result.projection_error.clear();
  for (std::size_t j = 0; j < result.orders.size(); ++j)
    result.projection_error.push_back(
        compute_vertex_errors(st.reference_b[j], st.truth.radiance).relative_rms);
}

void split_projection_and_sampling(ReportState& st) {
  list_split_axes(st);
  relight_reference(st);
  compute_projection_error(st);
  compute_sampling_error(st);
}

void measure_auto_bakes(ReportState& st) {
  const std::vector<double> auto_tolerances =
      st.opt.auto_tolerances ? *st.opt.auto_tolerances : default_auto_tolerances(st.opt.quick);
  if (auto_tolerances.empty()) return;
  bake::AutoBakeOptions ao;
  ao.bake.seed = st.opt.seed;
  ao.bake.memory_limit = st.opt.memory_limit;
  ao.lighting_order = bake::auto_lighting_order(st.in.env);  // as `prt bake --auto --env`
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

}  // namespace prt::report::detail
