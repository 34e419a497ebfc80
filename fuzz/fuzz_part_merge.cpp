// fuzz/fuzz_part_merge.cpp — libFuzzer target: the farm merges (merge_transfer_parts,
// bake/transfer_part.h; merge_haar_parts, bake/haar_part.h; merge_glossy_parts_to_file,
// bake/glossy_part.h) on hostile sets of parts. The valid parts of a fixed small bake
// (merge_fixture.h: six kinds, three shards) are the starting point; the input says how to spoil
// them, in three stages:
//   1. the part files' bytes: parts dropped, duplicated or reordered, bytes set, cut or
//      overwritten (and, when asked, the layout id and CRC-32C resealed, so that the mutation
//      reaches the decoder), then read and decoded through the real reader (read_part_file,
//      decode_transfer_part);
//   2. the decoded parts' fields: shard index and count, row range, vertex count, seed,
//      settings, options, direct transfer values (NaN, ±Inf, huge), hit triangles, samples and
//      barycentrics, per-row counts, array lengths, counters, glossy inputs, a part's rows
//      replaced by another's;
//   3. the merge, either as `prt merge` runs it (check_parts_fit, then the merge of its kind on
//      shard 0's scene and options) or called directly with the parts in the given order.
// Input: byte 0 the bake (mod 6); byte 1 bit 0 the direct call, bits 1–3 the number of file
// operations, bits 4–7 the number of field operations; then the operations' bytes (missing
// bytes read as zero). So the one-byte inputs 0..5 are the valid sets.
//
// Invariant: every stage either succeeds or throws a std::exception whose what() is one line
// that names a part file, the scene or the output (fuzz/one_line_error.h), or the shard that is
// missing; never a crash, sanitizer report, hang or unbounded allocation. When the set is the
// unmodified valid parts (in any order through check_parts_fit, in shard order when called
// directly), the merge must succeed and write the single-process bake's file, byte for byte.
// check_parts_fit is given only parts that keep read_part_file's promise (a shard index below a
// count of one at least); the merges called directly get any field.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz_checksum.h"
#include "merge_fixture.h"
#include "one_line_error.h"
#include "scene/scene_label.h"

namespace {

using prt::fuzz::Bytes;
using prt::fuzz::MergeFixture;
using prt::fuzz::MergeKind;
namespace bake = prt::bake;

constexpr std::size_t kChecksumOffset = 64;  // docs/FORMAT.md, "Part files"
constexpr std::size_t kLayoutOffset = 72;
constexpr std::size_t kMaxParts = 6;

// The input as a stream of bytes; zeros once it is used up.
class Input {
 public:
  Input(const uint8_t* data, std::size_t size) : p_(data), n_(size) {}
  uint8_t byte() {
    if (n_ == 0) return 0;
    --n_;
    return *p_++;
  }
  uint32_t u32() {
    uint32_t v = 0;
    for (int i = 0; i < 4; ++i) v |= uint32_t(byte()) << (8 * i);
    return v;
  }
  uint64_t u64() { return u32() | uint64_t(u32()) << 32; }
  std::size_t index(std::size_t size) { return size == 0 ? 0 : u32() % size; }

 private:
  const uint8_t* p_;
  std::size_t n_;
};

// A count or index a hostile part might hold, near `near` or at the edges of 32 and 64 bits.
uint64_t hostile(Input& in, uint64_t near) {
  switch (in.byte() % 10) {
    case 0:
      return 0;
    case 1:
      return near - 1;
    case 2:
      return near;
    case 3:
      return near + 1;
    case 4:
      return in.byte();
    case 5:
      return 0xFFFFFFFFull;
    case 6:
      return 0x100000000ull;
    case 7:
      return uint64_t{1} << 63;
    case 8:
      return ~uint64_t{0};
    default:
      return in.u64();
  }
}

uint32_t hostile32(Input& in, uint64_t near) {
  return static_cast<uint32_t>(hostile(in, near));
}

float hostile_float(Input& in) {
  switch (in.byte() % 9) {
    case 0:
      return std::numeric_limits<float>::quiet_NaN();
    case 1:
      return std::numeric_limits<float>::infinity();
    case 2:
      return -std::numeric_limits<float>::infinity();
    case 3:
      return 3e38f;
    case 4:
      return -3e38f;
    case 5:
      return std::numeric_limits<float>::denorm_min();
    case 6:
      return -0.f;
    case 7:
      return -1.f;
    default: {
      const uint32_t bits = in.u32();
      float f;
      std::memcpy(&f, &bits, 4);
      return f;
    }
  }
}

template <class T>
void set_some(Input& in, std::vector<T>& v, T value) {
  if (!v.empty()) v[in.index(v.size())] = value;
}

template <class T>
void resize_some(Input& in, std::vector<T>& v) {
  if (in.byte() & 1)
    v.push_back(T{});
  else if (!v.empty())
    v.pop_back();
}

// ---- Stage 1: the part files.

struct Files {
  std::vector<Bytes> bytes;
  std::vector<uint32_t> shard;  // which valid part each one started as
  bool modified = false;        // a byte or field changed
};

void reseal(Bytes& b) {
  if (b.size() < kLayoutOffset + 8) return;
  const uint64_t layout = bake::part_layout_id();
  for (int i = 0; i < 8; ++i) b[kLayoutOffset + i] = static_cast<unsigned char>(layout >> 8 * i);
  b = prt::fuzz::resealed(b.data(), b.size(), kChecksumOffset);
}

void file_operation(Input& in, Files& f) {
  const uint8_t op = in.byte() % 6;
  const std::size_t i = in.index(f.bytes.size());
  if (f.bytes.empty()) return;
  Bytes& b = f.bytes[i];
  switch (op) {
    case 0:
      f.bytes.erase(f.bytes.begin() + i);
      f.shard.erase(f.shard.begin() + i);
      return;
    case 1:
      if (f.bytes.size() < kMaxParts) {
        f.bytes.push_back(b);
        f.shard.push_back(f.shard[i]);
      }
      return;
    case 2: {
      const std::size_t j = in.index(f.bytes.size());
      std::swap(f.bytes[i], f.bytes[j]);
      std::swap(f.shard[i], f.shard[j]);
      return;
    }
    case 3:
      if (!b.empty()) b[in.index(b.size())] = in.byte();
      break;
    case 4:
      b.resize(in.index(b.size() + 1));
      break;
    default: {
      const std::size_t at = in.index(b.size() + 1), n = in.byte() % 32;
      for (std::size_t k = 0; k < n && at + k < b.size(); ++k) b[at + k] = in.byte();
      break;
    }
  }
  f.modified = true;
  if (in.byte() & 1) reseal(b);
}

// ---- Stage 2: the decoded parts' fields.

// A decoded SH part's direct transfer and hits point into the file's mapping (read-only, and
// released by the merge); the field operations change copies, held as a baked part holds them.
void own_direct(bake::TransferPart& p) {
  if (!p.direct_view) return;
  p.direct.assign(p.direct_view, p.direct_view + p.direct_count);
  p.direct_view = nullptr;
  p.direct_count = 0;
}

void own_hits(bake::TransferPart& p) {
  if (!p.hits_view) return;
  bake::CompactGather::Block block;
  block.lengths = p.gather_rows;
  block.hits.assign(p.hits_view, p.hits_view + p.hit_count);
  p.gather_blocks.clear();
  p.gather_blocks.push_back(std::move(block));
  p.hits_view = nullptr;
  p.hit_count = 0;
}

// A decoded Haar or glossy part's large arrays point into the file's mapping as well: copied the
// same way before a field operation changes the part.
void own_arrays(bake::HaarPart& p) {
  if (!p.mapped) return;
  const bake::HaarPart::Mapped& m = p.view;
  const uint64_t values = m.entries * static_cast<uint64_t>(p.channels);
  p.sparse_index.assign(m.sparse_index, m.sparse_index + (m.sparse_index ? m.entries : 0));
  p.sparse_values.assign(m.sparse_values, m.sparse_values + (m.sparse_values ? values : 0));
  p.wavelets.assign(m.wavelets, m.wavelets + (m.wavelets ? m.texels : 0));
  p.gather_columns.assign(m.gather_columns, m.gather_columns + (m.gather_columns ? m.gathered : 0));
  p.gather_weights.assign(m.gather_weights, m.gather_weights + (m.gather_weights ? m.gathered : 0));
  p.mapped = false;
  p.view = {};
}

void own_arrays(bake::GlossyPart& p) {
  if (p.direct_view) p.direct.assign(p.direct_view, p.direct_view + p.direct_count);
  if (p.hits_view) p.hits.assign(p.hits_view, p.hits_view + p.hit_count);
  p.direct_view = nullptr;
  p.direct_count = 0;
  p.hits_view = nullptr;
  p.hit_count = 0;
}

// Shard, rows and vertex count: in the part the checks read, in the one the merge of the part's
// kind reads, or in both.
void layout_operation(Input& in, bake::TransferPartFile& f, uint8_t op) {
  const uint8_t where = in.byte() % 3;
  const uint64_t V = f.part.vertices;
  uint64_t value = 0;
  switch (op) {
    case 0:
      value = hostile(in, prt::fuzz::kShards - 1);
      break;
    case 1:
      value = hostile(in, prt::fuzz::kShards);
      break;
    case 2:
      value = hostile(in, f.part.rows.first);
      break;
    case 3:
      value = hostile(in, f.part.rows.end);
      break;
    default:
      value = hostile(in, V);
      break;
  }
  const auto apply = [&](bake::ShardSpec& shard, bake::RowRange& rows, uint64_t& vertices) {
    if (op == 0) shard.index = static_cast<uint32_t>(value);
    if (op == 1) shard.count = static_cast<uint32_t>(value);
    if (op == 2) rows.first = value;
    if (op == 3) rows.end = value;
    if (op == 4) vertices = value;
  };
  if (where != 1) apply(f.part.shard, f.part.rows, f.part.vertices);
  if (where != 0 && f.haar) apply(f.haar_part.shard, f.haar_part.rows, f.haar_part.vertices);
  if (where != 0 && f.glossy)
    apply(f.glossy_part.shard, f.glossy_part.rows, f.glossy_part.vertices);
}

void identity_operation(Input& in, bake::TransferPartFile& f) {
  switch (in.byte() % 5) {
    case 0:
      f.seed = hostile(in, f.seed);
      return;
    case 1:
      f.prt_version += static_cast<char>(in.byte());
      return;
    case 2: {  // a key more: still a JSON object, as decode_transfer_part makes it (check_parts_fit
               // parses it to name the difference)
      const std::string key = "\"fuzz\":" + std::to_string(in.byte());
      if (f.settings.size() >= 2 && f.settings[0] == '{')
        f.settings.insert(1, f.settings == "{}" ? key : key + ",");
      return;
    }
    case 3:
      f.fingerprint ^= uint64_t{1} << (in.byte() % 64);
      return;
    default:
      f.scene_inputs += static_cast<char>(in.byte());
      return;
  }
}

void options_operation(Input& in, bake::TransferPartFile& f) {
  const int small = static_cast<int>(hostile(in, 2));
  switch (in.byte() % 10) {
    case 0:
      f.options.order = small;
      return;
    case 1:
      f.options.samples = small;
      return;
    case 2:
      f.options.kind = static_cast<prt::TransferKind>(in.byte() % 3);
      return;
    case 3:
      f.options.ao = !f.options.ao;
      return;
    case 4:
      f.options.bent_normals = !f.options.bent_normals;
      return;
    case 5:
      f.haar_options.cube_size = small;
      return;
    case 6:
      f.haar_options.transport = static_cast<prt::TransferKind>(in.byte() % 3);
      return;
    case 7:
      f.haar_part.channels = small;
      return;
    case 8:
      f.glossy_options.order = f.glossy_part.order = small;
      return;
    default:
      f.glossy_options.bounces = small % 5 - 1;  // −1..3: a billion bounces is slow, not wrong
      return;
  }
}

void value_operation(Input& in, bake::TransferPartFile& f) {
  const float x = hostile_float(in);
  switch (in.byte() % 6) {
    case 0:
      own_direct(f.part);
      set_some(in, f.part.direct, double(x));
      return;
    case 1:
      set_some(in, f.part.ao, x);
      set_some(in, f.part.bent, x);
      return;
    case 2:
      set_some(in, f.haar_part.sparse_values, x);
      set_some(in, f.haar_part.wavelets, x);
      return;
    case 3:
      set_some(in, f.haar_part.gather_weights, x);
      return;
    case 4:
      set_some(in, f.glossy_part.direct, x);
      return;
    default:
      f.part.ray_offset_max = x;
      return;
  }
}

void hit_operation(Input& in, bake::TransferPartFile& f, uint64_t triangles) {
  const uint64_t V = f.part.vertices;
  switch (in.byte() % 5) {
    case 0: {
      own_hits(f.part);
      if (f.part.gather_blocks.empty() || f.part.gather_blocks[0].hits.empty()) return;
      std::vector<bake::CompactHit>& hits = f.part.gather_blocks[0].hits;
      bake::CompactHit& h = hits[in.index(hits.size())];
      if (in.byte() & 1)
        h.triangle = hostile32(in, triangles);
      else
        h.u = static_cast<uint16_t>(in.u32()), h.v = static_cast<uint16_t>(in.u32());
      return;
    }
    case 1:
      set_some(in, f.haar_part.gather_columns, hostile32(in, V));
      return;
    case 2:
      set_some(in, f.haar_part.sparse_index, hostile32(in, 384));
      return;
    default: {
      std::vector<bake::GlossyHitRecord>& hits = f.glossy_part.hits;
      if (hits.empty()) return;
      bake::GlossyHitRecord& h = hits[in.index(hits.size())];
      switch (in.byte() % 4) {
        case 0:
          h.triangle = hostile32(in, triangles);
          return;
        case 1:
          h.sample = hostile32(in, 16);
          return;
        case 2:
          h.u = hostile_float(in);
          return;
        default:
          h.v = hostile_float(in);
          return;
      }
    }
  }
}

void count_operation(Input& in, bake::TransferPartFile& f) {
  switch (in.byte() % 10) {
    case 0:
      set_some(in, f.part.gather_rows, hostile32(in, 16));
      return;
    case 1:
      set_some(in, f.haar_part.sparse_lengths, hostile32(in, 16));
      return;
    case 2:
      set_some(in, f.haar_part.gather_lengths, hostile32(in, 16));
      return;
    case 3:
      set_some(in, f.glossy_part.hit_counts, hostile32(in, 16));
      return;
    case 4:
      own_direct(f.part);
      resize_some(in, f.part.direct);
      return;
    case 5:
      resize_some(in, f.part.ao);
      resize_some(in, f.part.gather_rows);
      return;
    case 6:
      resize_some(in, f.haar_part.sparse_index);
      resize_some(in, f.haar_part.wavelets);
      return;
    case 7:
      resize_some(in, f.haar_part.gather_columns);
      return;
    case 8:
      resize_some(in, f.glossy_part.direct);
      resize_some(in, f.glossy_part.hits);
      return;
    default:
      resize_some(in, f.glossy_part.hit_counts);
      return;
  }
}

void counter_operation(Input& in, bake::TransferPartFile& f) {
  const uint64_t value = hostile(in, 1000);
  switch (in.byte() % 4) {
    case 0:
      f.part.rays = value;
      return;
    case 1:
      f.part.back_face_hits = value;
      return;
    case 2:
      f.haar_part.rays = value;
      return;
    default:
      f.glossy_part.rays = f.glossy_part.back_face_hits = value;
      return;
  }
}

void inputs_operation(Input& in, bake::TransferPartFile& f) {
  if (!f.glossy_inputs) return;
  bake::GlossyInputs& g = *f.glossy_inputs;
  switch (in.byte() % 4) {
    case 0:
      set_some(in, g.material_of_vertex, hostile32(in, g.materials.size()));
      return;
    case 1:
      set_some(in, g.tangents, glm::vec4(hostile_float(in)));
      return;
    case 2:
      resize_some(in, g.tangents);
      return;
    default:
      if (!g.materials.empty()) g.materials.pop_back();
      return;
  }
}

void field_operation(Input& in, std::vector<bake::TransferPartFile>& parts, uint64_t triangles) {
  bake::TransferPartFile& f = parts[in.index(parts.size())];
  own_arrays(f.haar_part);
  own_arrays(f.glossy_part);
  const uint8_t op = in.byte() % 13;
  switch (op) {
    case 0:
    case 1:
    case 2:
    case 3:
    case 4:
      layout_operation(in, f, op);
      return;
    case 5:
      identity_operation(in, f);
      return;
    case 6:
      options_operation(in, f);
      return;
    case 7:
      value_operation(in, f);
      return;
    case 8:
      hit_operation(in, f, triangles);
      return;
    case 9:
      count_operation(in, f);
      return;
    case 10:
      counter_operation(in, f);
      return;
    case 11:
      inputs_operation(in, f);
      return;
    default: {  // another part's rows in this one
      const bake::TransferPartFile& g = parts[in.index(parts.size())];
      if (&g == &f) return;
      f.part = g.part;
      f.haar_part = g.haar_part;
      f.glossy_part = g.glossy_part;
      return;
    }
  }
}

// ---- Stage 3: the merge.

struct Names {
  std::vector<std::string> names;  // part files, scenes, the output
};

// An error of the merge or its checks: one line naming a part, the scene or the output, or
// check_parts_fit's "shard I/N is missing" and "no parts to merge".
void check_error(const std::string& message, const Names& n) {
  for (const std::string& name : n.names)
    if (prt::fuzz::is_one_line_error(message, name)) return;
  if (message.find('\n') == std::string::npos &&
      (message.rfind("shard ", 0) == 0 || message == "no parts to merge"))
    return;
  std::fprintf(stderr, "fuzz_part_merge: error message breaks the rule: %s\n", message.c_str());
  std::abort();
}

// Merges `parts` (in this order) of `kind` into `output` as `prt merge` does.
void merge_into(MergeKind kind, const prt::scene::Scene& scene,
                const std::vector<const bake::TransferPartFile*>& parts,
                const bake::GlossyInputs& inputs, const std::string& output) {
  const bake::TransferPartFile& first = *parts[0];
  if (kind == MergeKind::Glossy || kind == MergeKind::GlossyInterreflected) {
    bake::GlossyBakeOptions o = first.glossy_options;
    o.threads = 1;
    std::vector<const bake::GlossyPart*> p;
    for (const bake::TransferPartFile* f : parts) p.push_back(&f->glossy_part);
    (void)bake::merge_glossy_parts_to_file(scene, inputs, o, p, output);
  } else if (kind == MergeKind::HaarShadowed || kind == MergeKind::HaarInterreflected) {
    bake::HaarBakeOptions o = first.haar_options;
    o.threads = 1;
    std::vector<const bake::HaarPart*> p;
    for (const bake::TransferPartFile* f : parts) p.push_back(&f->haar_part);
    const prt::Status s =
        prt::write_haar_transfer_file(output, bake::merge_haar_parts(scene, o, p).file);
    if (!s.ok()) throw std::runtime_error(s.message());
  } else {
    bake::BakeOptions o = first.options;
    o.threads = 1;
    std::vector<const bake::TransferPart*> p;
    for (const bake::TransferPartFile* f : parts) p.push_back(&f->part);
    const prt::Status s =
        prt::write_transfer_file(output, bake::merge_transfer_parts(scene, o, p).data);
    if (!s.ok()) throw std::runtime_error(s.message());
  }
}

// The merge of f's family (the glossy and the Haar merge take either transport).
MergeKind kind_of(const bake::TransferPartFile& f) {
  return f.glossy ? MergeKind::Glossy : f.haar ? MergeKind::HaarShadowed : MergeKind::ShShadowed;
}

// The merge through check_parts_fit (`prt merge`) or called directly; true when it wrote.
bool merge(const MergeFixture& fx, const std::vector<bake::TransferPartFile>& parts, bool direct,
           const std::string& output, Names& names) {
  try {
    if (direct) {
      std::vector<const bake::TransferPartFile*> given;
      for (const bake::TransferPartFile& f : parts) given.push_back(&f);
      if (given.empty()) return false;  // the merges take one part at least (their callers')
      merge_into(fx.kind, fx.scene, given, fx.inputs, output);
      return true;
    }
    // check_parts_fit takes decoded parts: decode_transfer_part (read_part_file) promises a
    // shard index below a count of one at least, which the field operations may have broken.
    for (const bake::TransferPartFile& f : parts)
      if (f.part.shard.count == 0 || f.part.shard.index >= f.part.shard.count) return false;
    const std::vector<const bake::TransferPartFile*> ordered = bake::check_parts_fit(parts);
    const bake::TransferPartFile& first = *ordered[0];
    if (first.form_factors || first.subsurface || !first.scene) return false;
    names.names.push_back(prt::scene::scene_label(*first.scene));
    if (first.glossy && !first.glossy_inputs) std::abort();  // decode_transfer_part's promise
    merge_into(kind_of(first), *first.scene, ordered,
               first.glossy_inputs ? *first.glossy_inputs : fx.inputs, output);
    return true;
  } catch (const std::exception& e) {
    check_error(e.what(), names);
    return false;
  }
}

void remove_scratch_files() {
  for (std::size_t i = 0; i < kMaxParts; ++i)
    std::remove(prt::fuzz::merge_scratch_path("part" + std::to_string(i) + ".prtpart").c_str());
  std::remove(prt::fuzz::merge_scratch_path("merged").c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const bool registered = [] { return std::atexit(remove_scratch_files) == 0; }();
  (void)registered;
  Input in(data, size);
  const auto kind = static_cast<MergeKind>(in.byte() % prt::fuzz::kMergeKinds);
  const MergeFixture& fx = prt::fuzz::merge_fixture(kind);
  const uint8_t plan = in.byte();
  const bool direct = plan & 1;
  Files files{fx.parts, {}, false};
  for (uint32_t i = 0; i < prt::fuzz::kShards; ++i) files.shard.push_back(i);
  for (int k = 0; k < ((plan >> 1) & 7); ++k) file_operation(in, files);

  Names names;
  std::vector<bake::TransferPartFile> parts;
  for (std::size_t i = 0; i < files.bytes.size(); ++i) {
    const std::string path = prt::fuzz::merge_scratch_path("part" + std::to_string(i) + ".prtpart");
    names.names.push_back(path);
    prt::fuzz::write_all(path, files.bytes[i]);
    prt::PartFile file;
    const prt::Status read = prt::read_part_file(path, &file);
    if (!read.ok()) {
      prt::fuzz::check_one_line_error(read.message(), path);
      return 0;
    }
    try {
      parts.push_back(bake::decode_transfer_part(file, path));
    } catch (const std::exception& e) {
      prt::fuzz::check_one_line_error(e.what(), path);
      return 0;
    }
  }
  for (int k = 0; k < (plan >> 4) && !parts.empty(); ++k) {
    field_operation(in, parts, fx.scene.triangles.size());
    files.modified = true;
  }

  const std::string output = prt::fuzz::merge_scratch_path("merged");
  names.names.push_back(output);
  names.names.push_back(prt::scene::scene_label(fx.scene));
  std::remove(output.c_str());
  const bool wrote = merge(fx, parts, direct, output, names);
  // The unmodified valid set: every shard once, in shard order when the merge is called directly.
  std::vector<uint32_t> shards = files.shard;
  const bool in_order = std::is_sorted(shards.begin(), shards.end());
  std::sort(shards.begin(), shards.end());
  bool valid = !files.modified && shards.size() == prt::fuzz::kShards && (in_order || !direct);
  for (uint32_t i = 0; valid && i < shards.size(); ++i) valid = shards[i] == i;
  if (valid && (!wrote || prt::fuzz::read_all(output) != fx.reference)) std::abort();
  return 0;
}
