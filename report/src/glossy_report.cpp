// report/src/glossy_report.cpp — the sweep of `prt report --glossy` (report/glossy_report.h):
// ground truth per eye, bakes, CPCA, relighting and the error of each setting.
#include "report/glossy_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <utility>

#include "bake/cpca/compressor.h"
#include "bake/cpca/relit_metric.h"
#include "bake/glossy_transfer_baker.h"
#include "glossy_report_outputs.h"
#include "prt/glossy/relighter.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/auto_camera.h"
#include "relight/environment_input.h"
#include "report/glossy_ground_truth.h"
#include "scene/ray_caster.h"
#include "scene/scene_loader.h"

namespace prt::report {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

struct Setting {
  std::string axis;
  int order, samples, bounces;
};

struct CpcaSize {
  uint32_t clusters, vectors;
};

Setting base_glossy_setting(bool quick) {
  return {"", 6, quick ? 256 : 1024, 1};
}

// One axis at a time around the base; a setting on several axes is one row (axes joined).
std::vector<Setting> glossy_sweep(bool quick) {
  const Setting base = base_glossy_setting(quick);
  const std::vector<int> orders =
      quick ? std::vector<int>{3, 4, 6, 8} : std::vector<int>{2, 3, 4, 5, 6, 8, 10};
  const std::vector<int> samples =
      quick ? std::vector<int>{64, 256, 1024} : std::vector<int>{64, 256, 1024, 4096};
  const std::vector<int> bounces = quick ? std::vector<int>{0, 1, 3} : std::vector<int>{0, 1, 2, 4};
  std::vector<Setting> out;
  auto add = [&out](Setting s) {
    for (Setting& o : out)
      if (o.order == s.order && o.samples == s.samples && o.bounces == s.bounces) {
        o.axis += "+" + s.axis;
        return;
      }
    out.push_back(std::move(s));
  };
  for (int n : orders) add({"order", n, base.samples, base.bounces});
  for (int s : samples) add({"samples", base.order, s, base.bounces});
  for (int b : bounces) add({"bounces", base.order, base.samples, b});
  return out;
}

std::vector<CpcaSize> glossy_cpca_sizes(bool quick) {
  if (quick) return {{16, 4}, {16, 8}, {64, 8}};
  return {{16, 4}, {16, 8}, {32, 16}, {64, 8}, {64, 16}, {128, 32}};
}

// The camera's eye, and in full mode that eye turned by ±90° about the vertical through the
// camera's target.
std::vector<std::array<double, 3>> report_eyes(const scene::Scene& scene, bool quick) {
  const scene::RayCaster caster(scene);
  const relight::Camera cam = relight::choose_camera("auto", scene, caster, 16.f / 9.f).camera;
  std::vector<std::array<double, 3>> eyes{{cam.eye.x, cam.eye.y, cam.eye.z}};
  if (quick) return eyes;
  const glm::dvec3 d = glm::dvec3(cam.eye) - glm::dvec3(cam.target);
  for (double s : {1.0, -1.0})  // Ry(±90°): (x, z) → (s·z, −s·x)
    eyes.push_back({cam.target.x + s * d.z, cam.eye.y, cam.target.z - s * d.x});
  return eyes;
}

// An equal share of `count` from each primitive, among its vertices facing the eye, evenly
// spaced in index order (primitives with fewer facing vertices give all of theirs).
std::vector<uint32_t> pick_vertices(const scene::Scene& scene, const std::array<double, 3>& e,
                                    std::size_t count) {
  const glm::dvec3 eye(e[0], e[1], e[2]);
  std::vector<std::vector<uint32_t>> facing;
  auto add_range = [&](std::size_t first, std::size_t end) {
    std::vector<uint32_t> f;
    for (std::size_t v = first; v < end; ++v)
      if (glm::dot(glm::dvec3(scene.normals[v]), eye - glm::dvec3(scene.positions[v])) > 0)
        f.push_back(static_cast<uint32_t>(v));
    if (!f.empty()) facing.push_back(std::move(f));
  };
  if (scene.primitives.empty()) add_range(0, scene.vertex_count());
  for (const scene::ScenePrimitive& p : scene.primitives)
    add_range(p.first_vertex, std::min<std::size_t>(scene.vertex_count(),
                                                    std::size_t(p.first_vertex) + p.vertex_count));
  std::vector<uint32_t> out;
  if (facing.empty()) return out;
  const std::size_t share = std::max<std::size_t>(1, count / facing.size());
  for (const std::vector<uint32_t>& f : facing) {
    const std::size_t take = std::min(share, f.size());
    for (std::size_t k = 0; k < take; ++k) out.push_back(f[k * f.size() / take]);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

struct EyeTruth {
  std::array<double, 3> eye;
  std::vector<uint32_t> vertices;
  GroundTruthResult truth;
  std::vector<char> grazing;  // per entry of `vertices`: n·ω_o < kGrazingCosine
};

// Views within ~6° of the tangent plane, reported apart (the relighter's b table is least
// accurate there: docs/GLOSSY.md).
constexpr double kGrazingCosine = 0.1;

std::vector<char> grazing_flags(const scene::Scene& scene, const std::array<double, 3>& e,
                                const std::vector<uint32_t>& vertices) {
  std::vector<char> out;
  for (uint32_t v : vertices) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(scene.normals[v]));
    const glm::dvec3 d =
        glm::normalize(glm::dvec3(e[0], e[1], e[2]) - glm::dvec3(scene.positions[v]));
    out.push_back(glm::dot(n, d) < kGrazingCosine ? 1 : 0);
  }
  return out;
}

// Relights transfer data toward every eye and measures it against the ground truth.
class Measurer {
 public:
  Measurer(const GlossyReportOptions& o, const scene::Scene& scene, const sh::EnvMap& env,
           const std::vector<EyeTruth>& eyes)
      : opt_(o), env_(env), V_(scene.vertex_count()), eyes_(eyes) {
    primitive_of_vertex_.assign(V_, 0);
    for (std::size_t p = 0; p < scene.primitives.size(); ++p) {
      const scene::ScenePrimitive& prim = scene.primitives[p];
      for (std::size_t v = prim.first_vertex;
           v < std::min<std::size_t>(V_, std::size_t(prim.first_vertex) + prim.vertex_count); ++v)
        primitive_of_vertex_[v] = static_cast<uint32_t>(p);
    }
    primitives_ = std::max<std::size_t>(1, scene.primitives.size());
  }

  void measure(GlossyTransferData&& data, GlossyReportRow& row) {
    const int order = static_cast<int>(data.order);
    const Clock::time_point t0 = Clock::now();
    Result<GlossyRelighter> made = GlossyRelighter::create(std::move(data));
    if (!made.ok()) throw std::runtime_error(opt_.scene_path + ": " + made.status().message());
    row.relighter_seconds = seconds_since(t0);
    const ShLighting& light = lighting(order);
    std::vector<float> out(3 * V_);
    double num = 0, den = 0, shade = 0;
    std::vector<double> pnum(primitives_, 0.0), pden(primitives_, 0.0);
    double fnum = 0, fden = 0;
    for (const EyeTruth& e : eyes_) {
      const float eye[3] = {float(e.eye[0]), float(e.eye[1]), float(e.eye[2])};
      const Clock::time_point t1 = Clock::now();
      const Status s = made.value().shade(light, eye, 0, V_, out.data());
      shade += seconds_since(t1);
      if (!s) throw std::runtime_error(opt_.scene_path + ": " + s.message());
      for (std::size_t k = 0; k < e.vertices.size(); ++k)
        for (int c = 0; c < 3; ++c) {
          const uint32_t v = e.vertices[k];
          const double t = e.truth.radiance[3 * v + c], d = double(out[3 * v + c]) - t;
          num += d * d, den += t * t;
          pnum[primitive_of_vertex_[v]] += d * d, pden[primitive_of_vertex_[v]] += t * t;
          if (!e.grazing[k]) fnum += d * d, fden += t * t;
        }
    }
    row.shade_seconds = shade / static_cast<double>(eyes_.size());
    row.relative_rms = den > 0 ? std::sqrt(num / den) : 0.0;
    row.relative_rms_non_grazing = fden > 0 ? std::sqrt(fnum / fden) : 0.0;
    row.primitive_rms.clear();
    for (std::size_t p = 0; p < primitives_; ++p)
      row.primitive_rms.push_back(pden[p] > 0 ? std::sqrt(pnum[p] / pden[p]) : 0.0);
  }

 private:
  const ShLighting& lighting(int order) {
    auto it = lights_.find(order);
    if (it != lights_.end()) return it->second;
    Result<ShLighting> l = ShLighting::from_env_map(env_, order);
    if (!l.ok()) throw std::runtime_error(opt_.environment_path + ": " + l.status().message());
    return lights_.emplace(order, std::move(l.value())).first->second;
  }

  const GlossyReportOptions& opt_;
  const sh::EnvMap& env_;
  std::size_t V_;
  const std::vector<EyeTruth>& eyes_;
  std::map<int, ShLighting> lights_;
  std::vector<uint32_t> primitive_of_vertex_;
  std::size_t primitives_ = 1;
};

std::string describe_row(const GlossyReportRow& r) {
  char buf[256];
  if (r.clusters > 0)
    std::snprintf(
        buf, sizeof buf, "CPCA %u clusters x %u vectors: %.3g MB, compress %.1f s, error %.2f%%",
        r.clusters, r.vectors, double(r.bytes) / 1e6, r.compress_seconds, 100 * r.relative_rms);
  else
    std::snprintf(
        buf, sizeof buf, "order %d, %d samples, %d bounce(s): bake %.1f s, %.3g MB, error %.2f%%",
        r.order, r.samples, r.bounces, r.bake_seconds, double(r.bytes) / 1e6, 100 * r.relative_rms);
  std::string line = buf;
  std::snprintf(buf, sizeof buf, " (non-grazing %.2f%%); per primitive",
                100 * r.relative_rms_non_grazing);
  line += buf;
  for (double e : r.primitive_rms) {
    std::snprintf(buf, sizeof buf, " %.1f%%", 100 * e);
    line += buf;
  }
  return line;
}

// Pareto fronts: a row is on a front when no other row has cost ≤ and error ≤, one strictly.
void mark_fronts(std::vector<GlossyReportRow>& rows) {
  auto front = [&rows](auto cost, bool GlossyReportRow::*flag) {
    for (GlossyReportRow& r : rows) {
      r.*flag = true;
      for (const GlossyReportRow& o : rows)
        if (&o != &r && cost(o) <= cost(r) && o.relative_rms <= r.relative_rms &&
            (cost(o) < cost(r) || o.relative_rms < r.relative_rms))
          r.*flag = false;
    }
  };
  front([](const GlossyReportRow& r) { return double(r.bytes); }, &GlossyReportRow::front_storage);
  front([](const GlossyReportRow& r) { return r.bake_seconds + r.compress_seconds; },
        &GlossyReportRow::front_bake_time);
}

std::vector<EyeTruth> ground_truths(const GlossyReportOptions& o, const scene::Scene& scene,
                                    const sh::EnvMap& env, const detail::GlossyLog& log) {
  std::vector<EyeTruth> out;
  for (const std::array<double, 3>& eye : report_eyes(scene, o.quick)) {
    EyeTruth e{eye, pick_vertices(scene, eye, o.quick ? 192 : 768), {}, {}};
    e.grazing = grazing_flags(scene, eye, e.vertices);
    if (e.vertices.empty()) continue;
    GlossyGroundTruthOptions g;
    g.eye = eye;
    g.seed = o.seed + 1000;
    g.max_samples = o.quick ? 8192 : 1 << 16;
    g.target_relative_se = o.quick ? 0.02 : 0.01;
    g.vertices = e.vertices;
    e.truth = compute_glossy_ground_truth(scene, env, g, o.progress);
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "ground truth toward (%.2f, %.2f, %.2f): %zu vertices, %d samples, relative SE "
                  "%.3g%%, %.1f s",
                  eye[0], eye[1], eye[2], e.vertices.size(), e.truth.samples_per_vertex,
                  100 * e.truth.relative_rms_se, e.truth.seconds);
    log(buf);
    out.push_back(std::move(e));
  }
  if (out.empty()) throw std::runtime_error(o.scene_path + ": no vertex faces the report's eye");
  return out;
}

// The ground truth's relative RMS SE over all eyes together (the noise floor of the errors).
double combined_relative_se(const std::vector<EyeTruth>& eyes) {
  double se2 = 0, b2 = 0;
  for (const EyeTruth& e : eyes)
    for (uint32_t v : e.vertices)
      for (int c = 0; c < 3; ++c) {
        se2 += e.truth.standard_error[3 * v + c] * e.truth.standard_error[3 * v + c];
        b2 += e.truth.radiance[3 * v + c] * e.truth.radiance[3 * v + c];
      }
  return b2 > 0 ? std::sqrt(se2 / b2) : 0.0;
}

void sweep_cpca(const GlossyReportOptions& o, const GlossyTransferData& base,
                const GlossyReportRow& base_row, Measurer& measurer,
                std::vector<GlossyReportRow>& rows, const detail::GlossyLog& log) {
  for (const CpcaSize& size : glossy_cpca_sizes(o.quick)) {
    CpcaOptions co;
    co.clusters = size.clusters, co.vectors = size.vectors, co.seed = o.seed;
    co.memory_limit = o.memory_limit;
    co.threads = std::max(1u, std::thread::hardware_concurrency());
    const Clock::time_point t0 = Clock::now();
    // As prt compress does by default: minimise the expected relit error
    // (bake/cpca/relit_metric.h).
    Result<std::vector<double>> metric = cpca_relit_metric(base);
    if (!metric.ok())
      throw std::runtime_error(o.scene_path + ": CPCA: " + metric.status().message());
    co.row_metric = std::move(metric).value();
    Result<CpcaTransfer> c = cpca_compress(base, co);
    if (!c.ok()) throw std::runtime_error(o.scene_path + ": CPCA: " + c.status().message());
    GlossyReportRow row = base_row;
    row.axis = "cpca";
    row.clusters = size.clusters, row.vectors = size.vectors;
    row.compress_seconds = seconds_since(t0);
    row.bytes = c.value().payload_bytes();
    row.cpca_matrix_error = cpca_relative_rms_error(c.value(), base.matrices.data());
    GlossyTransferData copy = base;
    const std::size_t D = c.value().dimension();
    std::vector<double> x(D);
    for (std::size_t v = 0; v < copy.vertex_count; ++v) {
      cpca_reconstruct(c.value(), v, x.data());
      for (std::size_t d = 0; d < D; ++d) copy.matrices[v * D + d] = static_cast<float>(x[d]);
    }
    measurer.measure(std::move(copy), row);
    log(describe_row(row));
    rows.push_back(row);
  }
}

}  // namespace

std::vector<std::string> glossy_report_file_names() {
  return {
      "results.csv", "pareto.svg", "pareto.png", "error_vs_bake_time.svg", "error_vs_bake_time.png",
      "summary.md"};
}

GlossyReportResult run_glossy_report(const GlossyReportOptions& o) {
  const Clock::time_point start = Clock::now();
  const detail::GlossyLog log{o.log, start};
  scene::LoadOptions load;
  load.material_overrides = o.material_overrides;
  const scene::Scene scene = scene::load_scene(o.scene_path, load);
  relight::EnvironmentUse use;
  use.sh_order = o.quick ? 8 : 10;
  relight::EnvironmentInput in = relight::read_checked_environment(o.environment_path, {}, use);
  const sh::EnvMap& env = in.env;
  log(o.scene_path + ": " + std::to_string(scene.vertex_count()) + " vertices; " +
      o.environment_path + ": " + in.layout_note);
  std::error_code ec;  // only once the inputs have been read
  std::filesystem::create_directories(o.output_dir, ec);
  if (ec) throw std::runtime_error(o.output_dir + ": cannot create directory: " + ec.message());

  GlossyReportResult result;
  result.materials = scene::describe_materials(scene);
  if (!o.material_overrides.empty())
    for (const std::string& m : result.materials) log("material " + m);
  const std::vector<EyeTruth> eyes = ground_truths(o, scene, env, log);
  for (const EyeTruth& e : eyes) {
    result.eyes.push_back(e.eye);
    result.vertices_per_eye = std::max(result.vertices_per_eye, e.vertices.size());
    result.ground_truth_samples = std::max(result.ground_truth_samples, e.truth.samples_per_vertex);
    result.ground_truth_seconds += e.truth.seconds;
  }
  result.ground_truth_relative_se = combined_relative_se(eyes);

  Measurer measurer(o, scene, env, eyes);
  for (const scene::ScenePrimitive& p : scene.primitives)
    result.primitive_names.push_back(p.material.empty() ? p.name : p.material);
  if (scene.primitives.empty()) result.primitive_names.push_back("scene");
  const Setting base = base_glossy_setting(o.quick);
  for (const Setting& s : glossy_sweep(o.quick)) {
    bake::GlossyBakeOptions bo;
    bo.order = s.order, bo.samples = s.samples, bo.bounces = s.bounces, bo.seed = o.seed;
    bo.memory_limit = o.memory_limit;
    bake::GlossyBakeResult baked = bake::bake_glossy_transfer(scene, bo);
    GlossyReportRow row;
    row.axis = s.axis, row.order = s.order, row.samples = s.samples, row.bounces = s.bounces;
    row.channels = baked.data.channels;
    row.bytes = baked.data.matrices.size() * sizeof(float);
    row.bake_seconds = baked.stats.seconds_total;
    const bool is_base =
        s.order == base.order && s.samples == base.samples && s.bounces == base.bounces;
    GlossyTransferData kept;
    if (is_base) kept = baked.data;
    measurer.measure(std::move(baked.data), row);
    log(describe_row(row));
    result.rows.push_back(row);
    if (is_base) sweep_cpca(o, kept, row, measurer, result.rows, log);
  }
  mark_fronts(result.rows);
  detail::write_glossy_outputs(o, result, &result.files_written);
  log("done in " + std::to_string(static_cast<int>(seconds_since(start))) + " s");
  return result;
}

}  // namespace prt::report
