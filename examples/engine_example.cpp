// engine_example.cpp — the minimal engine integration quoted in docs/ENGINE.md.
//
// Usage: engine_example [coefficients.prt]
// Without an argument it first writes a small file of its own (unshadowed diffuse transfer of
// a few vertices, albedo 0.8), so it always runs. It exits with status 1 if any step fails,
// or, for its own file, if the result breaks the analytic check: under a sky of constant
// radiance c, a diffuse surface of albedo ρ has exit radiance ρ·c.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <prt/diffuse/relighter.h>
#include <prt/formats/geometry_check.h>
#include <prt/formats/transfer_file.h>
#include <prt/lighting/sh_lighting.h>
#include <sh/basis.h>
#include <sh/constants.h>
#include <sh/rotation.h>

namespace {

using prt::sh::kPi;

int fail(const std::string& message) {
  std::fprintf(stderr, "engine_example: %s\n", message.c_str());
  return 1;
}

// Writes unshadowed diffuse transfer: T_lm = ρ/π · A_l · Y_lm(n), A = (π, 2π/3, π/4).
prt::Status write_demo_file(const std::string& path, double albedo) {
  prt::TransferData data;
  data.kind = prt::TransferKind::Unshadowed;
  data.order = 3;
  data.channels = 1;
  data.storage = prt::Precision::F16;
  data.vertex_count = 40;
  const double band_factor[3] = {kPi, 2 * kPi / 3, kPi / 4};
  for (int v = 0; v < 40; ++v) {
    // Points on a unit sphere (spherical Fibonacci); the normal is the position.
    const double z = 1 - (2 * v + 1) / 40.0, r = std::sqrt(1 - z * z), phi = v * 2.39996323;
    const double n[3] = {r * std::cos(phi), r * std::sin(phi), z};
    double y[9];
    prt::sh::evaluate(3, n[0], n[1], n[2], y);
    for (int k = 0; k < 9; ++k) {
      const int l = k < 1 ? 0 : (k < 4 ? 1 : 2);
      data.coefficients.push_back(static_cast<float>(albedo / kPi * band_factor[l] * y[k]));
    }
    for (int a = 0; a < 3; ++a) {
      data.positions.push_back(static_cast<float>(n[a]));
      data.normals.push_back(static_cast<float>(n[a]));
    }
  }
  data.primitives.push_back({0, 40, "sphere"});
  data.metadata_json = "{\"generator\": \"engine_example\"}";
  return prt::write_transfer_file(path, data);
}

}  // namespace

int main(int argc, char** argv) {
  const bool own_file = argc < 2;
  const std::string path = own_file ? "engine_example.prt" : argv[1];
  const double albedo = 0.8;
  if (own_file) {
    if (prt::Status s = write_demo_file(path, albedo); !s) return fail(s.message());
  }

  // 1. Load the coefficient file (read_transfer_data() does the same from memory).
  prt::Result<prt::TransferData> data = prt::read_transfer_file(path);
  if (!data) return fail(data.status().message());

  // 2. Check that the engine's vertex buffer is the mesh that was baked. An engine passes its
  //    own positions (scene frame, +Y up); here they are the stored ones.
  const std::vector<float>& engine_positions = data->positions;
  const std::size_t vertex_count = static_cast<std::size_t>(data->vertex_count);
  if (prt::Status s = prt::check_geometry(*data, engine_positions.data(), vertex_count, 1e-5f);
      !s) {
    return fail(s.message());
  }

  // 3. Build the kernel (blocked coefficients, f32 or f16 as stored).
  prt::Result<prt::Relighter> relighter = prt::Relighter::create(*data);
  if (!relighter) return fail(relighter.status().message());

  // 4. Lighting: project an environment map (here a 64×32 lat-long sky of constant radiance),
  //    turn it (yaw 30°) and window it against ringing.
  const float sky[3] = {0.5f, 0.7f, 1.0f};
  const int width = 64, height = 32;
  std::vector<float> pixels(3 * width * height);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = sky[i % 3];
  prt::Result<prt::ShLighting> light =
      prt::ShLighting::from_pixels(prt::sh::EnvLayout::LatLong, width, height, pixels.data(), 3);
  if (!light) return fail(light.status().message());
  if (prt::Status s = light->rotate(prt::sh::rotation_from_yaw_pitch_roll(30, 0, 0)); !s) {
    return fail(s.message());
  }
  if (prt::Status s = light->apply_window(prt::sh::Window::Auto, 0); !s) return fail(s.message());

  // 5. Shade in chunks, as jobs of an engine's job system would (each call is const and
  //    thread-safe; chunks that are multiples of 16 vertices are fastest).
  std::vector<float> radiance(3 * vertex_count);
  const std::size_t chunk = 1024;
  for (std::size_t first = 0; first < vertex_count; first += chunk) {
    const std::size_t count = std::min(chunk, vertex_count - first);
    if (prt::Status s = relighter->shade(*light, first, count, radiance.data() + 3 * first); !s) {
      return fail(s.message());
    }
  }
  // Or straight to display colours: exposure in EV, sRGB, alpha 255.
  std::vector<uint8_t> rgba(4 * vertex_count);
  if (prt::Status s = relighter->shade_rgba8(*light, 0, vertex_count, 0.0f, rgba.data()); !s) {
    return fail(s.message());
  }

  std::printf("%zu vertices, order %d, %d channel(s); vertex 0: RGB %.4f %.4f %.4f\n", vertex_count,
              relighter->order(), relighter->channels(), radiance[0], radiance[1], radiance[2]);
  if (own_file) {
    // ρ·c, with the float16 storage's relative error (2^-11 per coefficient) as tolerance.
    for (std::size_t v = 0; v < vertex_count; ++v) {
      for (int c = 0; c < 3; ++c) {
        const double want = albedo * sky[c];
        if (std::abs(radiance[3 * v + c] - want) > 2e-3 * want) {
          return fail("vertex " + std::to_string(v) + ": radiance " +
                      std::to_string(radiance[3 * v + c]) + ", expected " + std::to_string(want));
        }
      }
    }
  }
  return 0;
}
