// relight/relight_pipeline.h — the steps of `prt relight` (and `prt demo`): load a scene and its
// coefficient file, project an environment map to SH lighting, window and rotate it, shade every
// vertex, render, and write images, a vertex-coloured GLB and a CSV.
//
// Conventions: SH basis of sh/basis.h (real, orthonormal, no Condon–Shortley phase,
// k = l(l+1)+m); glTF frame (+Y up); radiance in the units of the environment map.
// Rotations are row-major 3×3 matrices M acting on column vectors; lighting "rotated by M" is
// g(ω) = f(Mᵀω) (sh/rotation.h), so its SH coefficients are rotated, never re-projected.
// The turntable turns the light about +Y by 360°·i/N on top of --rotate: M_i = Ry(360°·i/N)·M.
// Exit radiance B_p = Σ_k T_p,k L_k (prt/formats/transfer_data.h), linear; a file that keeps the
// albedo apart (albedo_folded = false, e.g. baked from a textured scene) gives radiance per unit
// albedo, and the render multiplies it by the surface's albedo per pixel (relight/renderer.h): the
// texture is applied per pixel, not per vertex. The vertex-coloured GLB holds the exit radiance
// at each vertex (its own albedo × that value), whatever the file.
// Every error throws std::runtime_error (or scene::SceneError) with one line "PATH: problem";
// run_relight() validates all inputs before it writes anything, and each file is written
// atomically (temporary + rename) so nothing partial is left behind.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "prt/diffuse/relighter.h"
#include "prt/emitters/emitter_responses.h"
#include "prt/formats/transfer_data.h"
#include "prt/lighting/sh_lighting.h"
#include "relight/renderer.h"
#include "scene/scene.h"
#include "sh/env_map.h"
#include "sh/window.h"

namespace prt::relight {

// Positions may differ from the baked ones by this fraction of the bounding-box diagonal
// (a re-export with float noise passes; a different mesh does not).
constexpr float kGeometryTolerance = 1e-5f;

// Reads a coefficient file and checks that it was baked for `scene` (prt::check_geometry).
// Throws "PATH: problem" for an unreadable or corrupt file or a geometry mismatch.
prt::TransferData load_transfer_for_scene(const std::string& transfer_path,
                                          const scene::Scene& scene);

// Throws "TRANSFER_PATH: was not baked for SCENE: problem" unless `data` (a coefficient file's
// header and positions, SH or Haar) was baked for `scene` (prt::check_geometry).
void check_transfer_matches_scene(const prt::TransferData& data, const std::string& transfer_path,
                                  const scene::Scene& scene);

struct LightingOptions {
  std::array<double, 3> yaw_pitch_roll_deg{0.0, 0.0, 0.0};  // --rotate
  sh::Window window = sh::Window::None;
  double window_strength = -1.0;  // < 0: the window's documented default for the order
};

// SH lighting of `env` at `order`, windowed (not rotated). `note` (optional) receives a short
// description of the window applied (for auto: what it chose).
prt::ShLighting project_lighting(const sh::EnvMap& env, int order, const LightingOptions& options,
                                 std::string* note = nullptr);

// R = a·b for row-major 3×3 matrices.
std::array<double, 9> multiply_rotations(const std::array<double, 9>& a,
                                         const std::array<double, 9>& b);

// The rotation of frame i of an N-frame turntable: Ry(360°·i/N)·base.
std::array<double, 9> turntable_rotation(const std::array<double, 9>& base, int frame,
                                         int frame_count);

struct RelightRequest;

// The lighting rotation of frame i of the request (its --rotate, turned by the turntable).
std::array<double, 9> frame_rotation(const RelightRequest& request, int frame);

// A copy of `lighting` rotated by M (SH rotation of the coefficients).
prt::ShLighting rotate_lighting(const prt::ShLighting& lighting, const std::array<double, 9>& m);

// Exit radiance of all vertices, 3 floats per vertex, shaded in parallel ranges (TBB).
std::vector<float> shade_all_vertices(const prt::Relighter& relighter,
                                      const prt::ShLighting& lighting, std::size_t vertex_count);

// Writes an image by extension: .exr and .hdr linear, .png tone mapped (tone_map.h with the
// exposure). Negative values (SH ringing: the callers count the vertices that shade below zero
// and say so) are written as 0 in every format, as the PNG's tone curve maps them. Throws for any
// other extension.
void write_rendered_image(const std::string& path, const Image& image, float exposure_ev);

// One row per vertex: index,x,y,z,r,g,b (header row first; r,g,b the exit radiance at the
// vertex), written atomically. With per_unit_albedo (a coefficient file that keeps the albedo
// apart) three more columns, r_per_albedo,g_per_albedo,b_per_albedo: the shaded value before the
// surface's albedo (texture) multiplies it.
void write_vertex_csv(const std::string& path, const scene::Scene& scene,
                      const std::vector<float>& radiance_rgb,
                      const std::vector<float>* per_unit_albedo = nullptr);

// OUT.png → OUT_007.png for frame 7 (three digits at least).
std::string turntable_frame_path(const std::string& path, int frame);

struct RelightRequest {
  std::string scene_path, transfer_path, environment_path;
  std::string output_path;              // .exr, .hdr or .png
  std::optional<sh::EnvLayout> layout;  // nullopt: guess from the aspect ratio
  LightingOptions lighting;
  // PNG exposure in EV (and that of tone-mapped vertex colours); nullopt: automatic, chosen on
  // the first frame by choose_auto_exposure (relight/auto_exposure.h) and kept for every frame.
  std::optional<float> exposure_ev;
  RenderOptions render;
  std::string camera = "auto";     // relight/auto_camera.h resolve_camera()
  std::string vertex_colors_path;  // .glb, optional (unlit, see scene/glb_writer.h)
  // false: COLOR_0 is the linear exit radiance (may exceed 1); true: COLOR_0 is the PNG's
  // exposure and filmic curve before sRGB encoding (tone_map.h), in [0, 1] and still linear, so
  // an LDR viewer's sRGB output shows what the PNG shows.
  bool vertex_colors_tonemapped = false;
  std::string csv_path;      // optional
  int turntable_frames = 0;  // 0: one image at output_path
  // SH files only. max_edge: subdivide the scene as `prt bake --max-edge` did before matching
  // it (scene/subdivide.h). emitters_path: per-emitter radiosity responses computed on the same
  // vertices (relight/emitter_relight.h), recombined with emitter_colors (unnamed emitters keep
  // their stored emission) and added to the exit radiance of every frame; refused for a file
  // that keeps the albedo apart.
  std::optional<double> max_edge;
  std::string emitters_path;
  std::vector<prt::EmitterColor> emitter_colors;
  // Progress (optional): called after each image is written with (images written, images in
  // all) — (i + 1, N) for turntable frame i of N, (1, 1) for a single image.
  std::function<void(int done, int total)> image_written;
};

struct RelightSummary {
  std::size_t vertex_count = 0;
  int order = 0;
  double shade_seconds = 0, render_seconds = 0;
  // Vertices with a negative channel (SH ringing): the most in any frame, and how many frames
  // had any.
  std::size_t negative_vertices = 0;
  int negative_frames = 0;
  float exposure_ev = 0.f;     // the exposure used (given, or chosen)
  bool exposure_auto = false;  // true: chosen by choose_auto_exposure
  std::string window_note, layout_note, camera_note;
  std::vector<std::string> files_written;
};

// Checks the request's outputs before any work is done: the image is .exr, .hdr or .png, the
// vertex colours .glb, every output's directory exists, and 0 ≤ turntable_frames ≤ 3600.
void check_relight_outputs(const RelightRequest& request);

RelightSummary run_relight(const RelightRequest& request);

// For the user: a line on the exposure of PNG images and tone-mapped vertex colours (given or
// automatic, and how the automatic one is chosen), and a line on the camera
// (summary.camera_note, relight/auto_camera.h describe_camera).
std::string describe_view(const RelightRequest& request, const RelightSummary& summary);

}  // namespace prt::relight
