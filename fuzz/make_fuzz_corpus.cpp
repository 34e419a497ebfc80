// fuzz/make_fuzz_corpus.cpp — writes the seed corpora of the fuzz targets with the project's own
// writers, so every seed is a valid input the loaders accept (the fuzzer mutates from there):
//   corpus/fuzz_transfer_file/  coefficient files: orders 1..3, 1 and 3 channels, F32 and F16,
//                               with and without AO, bent normals and primitive ranges;
//   corpus/fuzz_scene_obj/      small OBJ files (triangles, quads, vn/vt, negative indices);
//   corpus/fuzz_scene_gltf/     GLB files from scene::write_glb and a .gltf with a data URI;
//   corpus/fuzz_env_map/        selector byte + small .hdr and .pfm maps of each layout;
//   corpus/fuzz_env_map_exr/    selector byte + small .exr maps of each layout (its regression_*
//                               files are kept findings of the target, not written here);
//   corpus/fuzz_glossy_file/ … fuzz_texture/, fuzz_link_cache/, fuzz_part_file/: the binary
//                               formats, textures, link caches and farm parts (format_seeds.h);
//   corpus/fuzz_part_merge/     operations on fixed parts (fuzz_part_merge.cpp): each bake's
//                               valid set, through check_parts_fit and called directly, reordered,
//                               a shard dropped, one duplicated, a row range changed.
// Usage: make_fuzz_corpus OUT_DIR   (scripts/fuzz.sh runs it when a corpus folder is empty).
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "format_seeds.h"
#include "prt/formats/transfer_file.h"
#include "relight/image_io.h"
#include "scene/glb_writer.h"
#include "scene/procedural_mesh.h"

namespace fs = std::filesystem;

namespace {

void write_bytes(const fs::path& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

std::string read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_transfer_seeds(const fs::path& dir) {
  int n = 0;
  for (uint32_t order : {1u, 2u, 3u}) {
    for (uint32_t channels : {1u, 3u}) {
      for (prt::Precision storage : {prt::Precision::F32, prt::Precision::F16}) {
        prt::TransferData d;
        d.kind = order == 3 ? prt::TransferKind::Interreflected : prt::TransferKind::Shadowed;
        d.order = order;
        d.channels = channels;
        d.storage = storage;
        d.vertex_count = order == 1 ? 1 : 17;  // 17: one full block of 16 plus a padded one
        for (uint64_t v = 0; v < d.vertex_count; ++v) {
          d.positions.insert(d.positions.end(), {float(v), 0.5f * float(v), -1.0f});
          d.normals.insert(d.normals.end(), {0.f, 1.f, 0.f});
        }
        for (uint64_t i = 0; i < d.vertex_count * channels * order * order; ++i)
          d.coefficients.push_back(0.25f - 0.01f * float(i % 50));
        if (order >= 2) {
          d.ao.assign(d.vertex_count, 0.75f);
          for (uint64_t v = 0; v < d.vertex_count; ++v)
            d.bent_normals.insert(d.bent_normals.end(), {0.f, 0.f, 1.f});
          d.primitives.push_back({0, d.vertex_count, "mesh/0"});
        }
        d.metadata_json = R"({"seed":)" + std::to_string(n) + "}";
        auto bytes = prt::encode_transfer_file(d, "seed");
        if (!bytes.ok()) throw std::runtime_error(bytes.status().message());
        write_bytes(dir / ("seed_" + std::to_string(n++) + ".prt"),
                    std::string(bytes->begin(), bytes->end()));
      }
    }
  }
}

void write_obj_seeds(const fs::path& dir) {
  write_bytes(dir / "triangle.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write_bytes(dir / "quad_vn_vt.obj",
              "o quad\nv 0 0 0\nv 1 0 0\nv 1 0 1\nv 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
              "vn 0 1 0\nf 1/1/1 4/4/1 3/3/1 2/2/1\n");
  write_bytes(dir / "negative_indices.obj",
              "v 0 0 0\nv 1 0 0\nv 0 0 -1\nv 1 0 -1\nf -4 -3 -2\nf -3 -1 -2\n");
  write_bytes(dir / "two_shapes_crlf.obj",
              "g a\r\nv 0 0 0\r\nv 1 0 0\r\nv 0 1 0\r\nf 1 2 3\r\ng b\r\nv 0 0 1\r\nv 1 0 1\r\n"
              "v 0 1 1\r\nf 4 5 6\r\n");
  write_bytes(dir / "degenerate.obj",
              "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 1 4\nf 1 2 4\nvn 0 0 1\n");
}

void write_gltf_seeds(const fs::path& dir) {
  const fs::path tmp = dir / "tmp.glb";
  prt::scene::write_glb(
      tmp.string(), prt::scene::make_box({-1, -1, -1}, {1, 1, 1}, 1, false, {0.5f, 0.5f, 0.5f}));
  fs::rename(tmp, dir / "box.glb");
  prt::scene::write_glb(tmp.string(), prt::scene::make_quad({0, 0, 0}, {1, 0, 0}, {0, 0, -1}, 1, 1,
                                                            {0.8f, 0.2f, 0.2f}));
  fs::rename(tmp, dir / "quad.glb");
  // One triangle, no normals, no indices, a node with TRS, a camera, positions in a data URI:
  // 3 vec3 floats (0,0,0) (1,0,0) (0,1,0) = 36 bytes in base64.
  write_bytes(dir / "triangle.gltf", R"({"asset":{"version":"2.0"},"scene":0,
"scenes":[{"nodes":[0,1]}],
"nodes":[{"mesh":0,"translation":[0,1,0],"rotation":[0,0,0,1],"scale":[2,2,2]},
 {"camera":0,"translation":[0,0,3]}],
"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":0.1}}],
"meshes":[{"primitives":[{"attributes":{"POSITION":0},"material":0}]}],
"materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.5,0.6,0.7,1]}}],
"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3",
 "min":[0,0,0],"max":[1,1,0]}],
"bufferViews":[{"buffer":0,"byteLength":36}],
"buffers":[{"byteLength":36,
 "uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]}
)");
}

// PFM bytes: "PF"/"Pf", size, scale (-1: little-endian, 1: big-endian), rows bottom first.
std::string pfm_bytes(int w, int h, int channels, const std::vector<float>& values,
                      bool big_endian) {
  std::string file = std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(w) + " " +
                     std::to_string(h) + "\n" + (big_endian ? "1.0" : "-1.0") + "\n";
  const std::size_t row = std::size_t(w) * channels;
  for (int r = h - 1; r >= 0; --r)
    for (std::size_t i = 0; i < row; ++i) {
      char b[4];
      std::memcpy(b, &values[std::size_t(r) * row + i], 4);
      if (big_endian) {
        std::swap(b[0], b[3]);
        std::swap(b[1], b[2]);
      }
      file.append(b, 4);
    }
  return file;
}

std::string written_by_openimageio(const fs::path& dir, const std::string& extension, int w, int h,
                                   const std::vector<float>& rgb) {
  const fs::path tmp = dir / ("tmp" + extension);
  prt::relight::write_image(tmp.string(), w, h, 3, rgb.data());
  std::string file = read_bytes(tmp);
  fs::remove(tmp);
  return file;
}

// corpus/fuzz_env_map/: selector byte b (decoder {Radiance, PFM}[b % 2], layout {guess, latlong,
// angular, cross, faces}[(b / 2) % 5]; fuzz_env_map.cpp) + a small map of each layout as .hdr
// (OpenImageIO's writer: flat below width 8, RLE from 8) and PFM, plus the rarer encodings the
// decoders handle: grey and big-endian PFM, old-style RLE, a bottom-up and a column-major .hdr.
// corpus/fuzz_env_map_exr/: selector byte (layout = b % 5) + the same maps as .exr.
void write_env_seeds(const fs::path& dir, const fs::path& exr_dir) {
  struct Size {
    int w, h, layout;
  };
  const std::vector<Size> sizes = {{8, 4, 1},  {4, 4, 2}, {6, 8, 3},
                                   {2, 12, 4}, {1, 1, 0}, {16, 8, 0}};
  int n = 0, e = 0;
  auto seed = [&](int decoder, int layout, const std::string& file) {
    const char selector = static_cast<char>(decoder + 2 * layout);
    write_bytes(dir / ("map_" + std::to_string(n++)), std::string(1, selector) + file);
  };
  for (const Size& s : sizes) {
    std::vector<float> rgb(static_cast<std::size_t>(s.w) * s.h * 3);
    for (std::size_t i = 0; i < rgb.size(); ++i) rgb[i] = 0.1f + 0.37f * float(i % 7);
    seed(0, s.layout, written_by_openimageio(dir, ".hdr", s.w, s.h, rgb));
    seed(1, s.layout, pfm_bytes(s.w, s.h, 3, rgb, false));
    write_bytes(exr_dir / ("map_" + std::to_string(e++)),
                std::string(1, static_cast<char>(s.layout)) +
                    written_by_openimageio(dir, ".exr", s.w, s.h, rgb));
  }
  // Grey big-endian PFM, 4x2 lat-long.
  seed(1, 1, pfm_bytes(4, 2, 1, {0.5f, 1.f, 2.f, 4.f, 8.f, 16.f, 32.f, 64.f}, true));
  const std::string header = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n";
  // Old-style RLE, 10x5 lat-long, each scanline: a pixel, repeat 3; a pixel, repeat 1, repeat 0
  // (shifted: 0 << 8); a pixel, repeat 3.
  std::string scanline("\x80\x40\x20\x81\x01\x01\x01\x03\x10\x20\x80\x82", 12);
  scanline += std::string("\x01\x01\x01\x01\x01\x01\x01\x00\x05\x06\x07\x85", 12);
  scanline += std::string("\x01\x01\x01\x03", 4);
  std::string old_rle = header + "-Y 5 +X 10\n";
  for (int row = 0; row < 5; ++row) old_rle += scanline;
  seed(0, 0, old_rle);
  // Bottom-up rows and column-major scanlines, 2x1 lat-long, flat pixels.
  const std::string two_pixels("\x80\x40\x20\x81\x10\x20\x80\x82", 8);
  seed(0, 1, header + "+Y 1 +X 2\n" + two_pixels);
  seed(0, 1, header + "+X 2 -Y 1\n" + two_pixels);
}

// corpus/fuzz_part_merge/: byte 0 the bake, byte 1 the plan (bit 0 direct, bits 1–3 file
// operations, bits 4–7 field operations), then the operations (fuzz_part_merge.cpp).
void write_part_merge_seeds(const fs::path& dir) {
  const std::string u32_0("\0\0\0\0", 4), u32_1("\1\0\0\0", 4), u32_2("\2\0\0\0", 4);
  for (char kind = 0; kind < 6; ++kind) {
    const std::string k(1, kind), name = "kind" + std::to_string(int(kind));
    write_bytes(dir / (name + "_valid"), k);
    write_bytes(dir / (name + "_valid_direct"), k + '\1');
    write_bytes(dir / (name + "_swapped"), k + '\2' + '\2' + u32_0 + u32_2);  // swap 0 and 2
    write_bytes(dir / (name + "_dropped"), k + '\2' + '\0' + u32_1);          // drop shard 1
    write_bytes(dir / (name + "_duplicated"), k + '\2' + '\1' + u32_1);       // shard 1 twice
    // Field operation 2 (rows.first) on part 1 in both views, to its neighbour's value + 1.
    write_bytes(dir / (name + "_rows_direct"), k + '\x11' + u32_1 + '\2' + '\2' + '\3');
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_fuzz_corpus OUT_DIR\n";
    return 2;
  }
  try {
    const fs::path out = argv[1];
    const fs::path dirs[] = {out / "fuzz_transfer_file", out / "fuzz_scene_obj",
                             out / "fuzz_scene_gltf",    out / "fuzz_env_map",
                             out / "fuzz_env_map_exr",   out / "fuzz_part_merge"};
    for (const fs::path& d : dirs) fs::create_directories(d);
    write_transfer_seeds(dirs[0]);
    write_obj_seeds(dirs[1]);
    write_gltf_seeds(dirs[2]);
    write_env_seeds(dirs[3], dirs[4]);
    write_part_merge_seeds(dirs[5]);
    prt::fuzz::write_format_seeds(out);
  } catch (const std::exception& e) {
    std::cerr << e.what() << "\n";
    return 1;
  }
  return 0;
}
