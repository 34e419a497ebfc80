// fuzz/merge_fixture.h — the fixed farm bake fuzz_part_merge starts from: a small scene (a 3 × 3
// ground quad and a box standing on it, 40 vertices and 30 triangles), split into kShards shards
// for six bakes (SH shadowed with AO and bent normals, SH interreflected, Haar shadowed and
// interreflected, glossy shadowed and interreflected), each shard's part encoded as the part file
// `prt bake --shard` writes (bytes), and the file the single-process bake writes (bytes), which
// the merge of the unmodified parts must reproduce byte for byte. Baked once per kind, on first
// use (a few hundred milliseconds under the sanitizers).
#pragma once

#include <array>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include "bake/glossy_part.h"
#include "bake/haar_part.h"
#include "bake/transfer_part.h"
#include "bake/transfer_part_file.h"
#include "prt/formats/haar_transfer_file.h"
#include "prt/formats/part_file.h"
#include "prt/formats/transfer_file.h"
#include "scene/procedural_mesh.h"

namespace prt::fuzz {

enum class MergeKind {
  ShShadowed,
  ShInterreflected,
  HaarShadowed,
  HaarInterreflected,
  Glossy,
  GlossyInterreflected
};
constexpr int kMergeKinds = 6;
constexpr uint32_t kShards = 3;
constexpr const char* kMergeSceneName = "merge_scene.obj";
constexpr const char* kMergeVersion = "fuzz";

using Bytes = std::vector<unsigned char>;

// A per-process scratch path in /dev/shm (else $TMPDIR or /tmp): "prt-fuzz-merge-PID-NAME".
// The caller removes what it writes there.
inline std::string merge_scratch_path(const std::string& name) {
  static const std::string directory = [] {
    if (access("/dev/shm", W_OK) == 0) return std::string("/dev/shm");
    const char* tmp = std::getenv("TMPDIR");
    return std::string(tmp != nullptr ? tmp : "/tmp");
  }();
  return directory + "/prt-fuzz-merge-" + std::to_string(static_cast<long>(getpid())) + "-" + name;
}

inline Bytes read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  Bytes bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (!in.good() && !in.eof()) std::abort();
  return bytes;
}

inline void write_all(const std::string& path, const Bytes& bytes) {
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();  // an environment problem, not a finding
  if (!bytes.empty() && std::fwrite(bytes.data(), 1, bytes.size(), f) != bytes.size()) std::abort();
  if (std::fclose(f) != 0) std::abort();
}

// The bytes of `part` as write_part_file writes them.
inline Bytes part_bytes(const prt::PartFile& part) {
  const std::string path = merge_scratch_path("fixture.prtpart");
  if (!prt::write_part_file(path, part).ok()) std::abort();
  Bytes bytes = read_all(path);
  std::remove(path.c_str());
  return bytes;
}

inline scene::Scene merge_scene() {
  scene::Scene s = scene::make_quad({-1.f, 0.f, 1.f}, {2.f, 0.f, 0.f}, {0.f, 0.f, -2.f}, 3, 3,
                                    glm::vec3(0.7f), "ground");
  scene::append_scene(s, scene::make_box({-0.3f, 0.f, -0.3f}, {0.3f, 0.6f, 0.3f}, 1, false,
                                         glm::vec3(0.8f, 0.5f, 0.3f), "box"));
  s.source_path = kMergeSceneName;
  return s;
}

struct MergeFixture {
  MergeKind kind;
  scene::Scene scene;
  bake::BakeOptions sh;
  bake::HaarBakeOptions haar;
  bake::GlossyBakeOptions glossy;
  bake::GlossyInputs inputs;  // glossy: glossy_inputs(scene)
  std::vector<Bytes> parts;   // shard i's part file
  Bytes reference;            // the single bake's output file
};

inline MergeFixture make_merge_fixture(MergeKind kind) {
  MergeFixture fx{kind, merge_scene(), {}, {}, {}, {}, {}, {}};
  const std::string out = merge_scratch_path("reference");
  fx.sh.order = 2;
  fx.sh.samples = 16;
  fx.sh.seed = 7;
  fx.sh.threads = 1;
  fx.haar.cube_size = 8;
  fx.haar.seed = 7;
  fx.haar.bounces = 2;
  fx.haar.threads = 1;
  fx.glossy.order = 2;
  fx.glossy.samples = 16;
  fx.glossy.seed = 7;
  fx.glossy.threads = 1;
  switch (kind) {
    case MergeKind::ShShadowed:
    case MergeKind::ShInterreflected: {
      if (kind == MergeKind::ShShadowed) {
        fx.sh.ao = fx.sh.bent_normals = true;
      } else {
        fx.sh.kind = prt::TransferKind::Interreflected;
        fx.sh.bounces = 2;
      }
      for (uint32_t i = 0; i < kShards; ++i) {
        const bake::TransferPart p = bake::bake_transfer_part(fx.scene, fx.sh, {i, kShards});
        fx.parts.push_back(
            part_bytes(bake::encode_transfer_part(p, fx.scene, fx.sh, kMergeVersion)));
      }
      if (!prt::write_transfer_file(out, bake::bake_transfer(fx.scene, fx.sh).data).ok())
        std::abort();
      break;
    }
    case MergeKind::HaarShadowed:
    case MergeKind::HaarInterreflected: {
      if (kind == MergeKind::HaarInterreflected)
        fx.haar.transport = prt::TransferKind::Interreflected;
      for (uint32_t i = 0; i < kShards; ++i) {
        const bake::HaarPart p = bake::bake_haar_part(fx.scene, fx.haar, {i, kShards});
        fx.parts.push_back(part_bytes(bake::encode_haar_part(p, fx.scene, fx.haar, kMergeVersion)));
      }
      if (!prt::write_haar_transfer_file(out, bake::bake_haar_transfer(fx.scene, fx.haar).file)
               .ok())
        std::abort();
      break;
    }
    case MergeKind::Glossy:
    case MergeKind::GlossyInterreflected: {
      if (kind == MergeKind::GlossyInterreflected) fx.glossy.bounces = 1;
      fx.inputs = bake::glossy_inputs(fx.scene);
      for (uint32_t i = 0; i < kShards; ++i) {
        const bake::GlossyPart p = bake::bake_glossy_part(fx.scene, fx.glossy, {i, kShards});
        fx.parts.push_back(
            part_bytes(bake::encode_glossy_part(p, fx.scene, fx.inputs, fx.glossy, kMergeVersion)));
      }
      (void)bake::bake_glossy_transfer_to_file(fx.scene, fx.glossy, out);
      break;
    }
  }
  fx.reference = read_all(out);
  std::remove(out.c_str());
  if (fx.reference.empty()) std::abort();
  return fx;
}

// The fixture of `kind`, baked on first use.
inline const MergeFixture& merge_fixture(MergeKind kind) {
  static std::array<std::unique_ptr<MergeFixture>, kMergeKinds> cache;
  std::unique_ptr<MergeFixture>& slot = cache[static_cast<int>(kind)];
  if (!slot) slot = std::make_unique<MergeFixture>(make_merge_fixture(kind));
  return *slot;
}

}  // namespace prt::fuzz
