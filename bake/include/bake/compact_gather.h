// bake/compact_gather.h — the diffuse gather matrix H of bake/interreflection_solver.h stored per
// hit ray instead of per merged entry, with its unknowns in a memory-local (Morton) order.
//
// H_pj = (1/N) Σ_{s hits} Σ_{i : v_i = j} b_i(s) (bake/transfer_baker.cpp). Instead of merged
// (column, weight) pairs (8 bytes each, up to 3 per hit ray), a row keeps one 8-byte CompactHit
// per front-face hit: the hit triangle (uint32) and its barycentrics u, v quantised to 16 bits,
//     q_u = round(65535·u), q_v = round(65535·v), q_0 = 65535 − q_u − q_v,
// (q_u + q_v clamped to 65535), so the three weights are non-negative integers summing to 65535
// exactly: every row sum of H stays hits/N, and the contraction ‖ρH‖_max ≤ ρ_max of the Neumann
// series is kept. Quantisation error: |u − q_u/65535| ≤ 1/131070 (and v alike), so one hit's
// interpolated value x_0 + u(x_1 − x_0) + v(x_2 − x_0) moves by ≤ 2·(1/131070)·2‖x‖_max
// = 3.1e-5‖x‖_max; a row by ≤ (hits/N)·3.1e-5‖x‖_max. The solution of (I − ρH)T = D moves by
// ≤ 3.1e-5·q/(1 − q)·‖T‖_max, q = max_p ρ_p·hits_p/N (a worst case; the rounding errors of
// distinct hits are independent and mostly cancel).
//
// Unknowns: row r is the vertex order[r] (make_morton_order: sorted by the Morton code of its
// position), and triangles are renumbered in the order of their first vertex's row, so that the
// rows of x a pass over H reads, and the triangle table it reads them through, lie close in
// memory for spatially close rays. Rows are built in blocks of `block_rows` consecutive rows
// (one block per parallel task of the sampling pass), stored block by block, never copied into
// one array: the gather's memory is what its blocks hold.
//
// Memory: 8 bytes per front-face hit + 4 per row + 12 + 4 per triangle (table and renumbering)
// + 8 per vertex (order and rank). Determinism: a row's hits are sorted (triangle, q_u, q_v)
// and summed in that order in double; rows are independent, so multiply() is bit-identical for
// any thread count and any order in which the sampling pass produced the hits.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "bake/interreflection_solver.h"

namespace prt::bake {

struct CompactHit {
  uint32_t triangle;  // renumbered (CompactGather::triangle_index)
  uint16_t u, v;      // barycentrics of vertices 1 and 2, × 65535, rounded
};
static_assert(sizeof(CompactHit) == 8, "a compact hit is 8 bytes");

// Quantises Embree's barycentrics (u, v ≥ 0, u + v ≤ 1 up to rounding) as described above.
CompactHit quantise_hit(uint32_t triangle, float u, float v);

// Vertex indices sorted by the 63-bit Morton code of their positions in the bounding box (ties
// by index): order[r] = vertex of row r.
std::vector<uint32_t> make_morton_order(const std::vector<glm::vec3>& positions);

class CompactGather {
 public:
  struct Block {
    std::vector<uint32_t> lengths;  // hits per row
    std::vector<CompactHit> hits;   // the rows' hits, concatenated
  };

  CompactGather() = default;
  // Rows follow `order` (a permutation of the vertices); triangles index the vertices. The
  // gather's weight per hit is row_scale (1/N for N cosine-distributed rays). With
  // `for_solve` false the tables are those that encode hits only (a farm shard's: no apply()).
  CompactGather(std::vector<uint32_t> order, const std::vector<glm::uvec3>& triangles,
                std::size_t block_rows, double row_scale, bool for_solve = true);

  std::size_t rows() const { return order_.size(); }
  std::size_t block_rows() const { return block_rows_; }
  std::size_t blocks() const { return (rows() + block_rows_ - 1) / block_rows_; }
  uint32_t vertex_of_row(std::size_t r) const { return order_[r]; }
  uint32_t row_of_vertex(std::size_t v) const { return rank_[v]; }
  uint32_t triangle_index(uint32_t scene_triangle) const { return triangle_rank_[scene_triangle]; }

  // Bytes one block of `rows` rows and `hits` hits will hold (for a MemoryBudget charge).
  static uint64_t block_bytes(std::size_t rows, std::size_t hits) {
    return rows * sizeof(uint32_t) + hits * sizeof(CompactHit);
  }
  // Stores block b (lengths sum to hits.size(); each row's hits are sorted here).
  void set_block(std::size_t b, Block block);
  const Block& block(std::size_t b) const { return blocks_[b]; }

  uint64_t hits() const;
  uint64_t bytes() const;  // everything held, as counted in the header
  // max over rows r and channels c of rho[r·C + c] · (hits of r) · row_scale: a bound on
  // ‖diag(ρ)H‖_max (rho: rows() × C).
  double max_weighted_row_sum(const std::vector<double>& rho, int channels) const;

  // y = diag(ρ)·H·x for blocks of `columns` = C × K columns in row order (x, y: rows() × C·K,
  // channel-major within a row; rho: rows() × C, channel c's ρ scaling columns [cK, (c+1)K)).
  // All channels share one pass over the hits and one scattered read per hit vertex. x is read
  // in float (half the bytes of the scattered reads) or binary16 (a quarter; converted to float,
  // exactly, before the products); each row's sums are double, then rounded once to y's type.
  // The float and half forms take rows `ld` elements apart in x and y (0: `columns`; entries
  // past `columns` are neither read nor written). C ≤ 4 and C divides `columns`.
  void multiply(const std::vector<double>& rho, int channels, const float* x, int columns,
                double* y) const;
  void multiply(const std::vector<double>& rho, int channels, const float* x, int columns, float* y,
                std::size_t ld = 0) const;
  void multiply(const std::vector<double>& rho, int channels, const uint16_t* x, int columns,
                uint16_t* y, std::size_t ld = 0) const;

 private:
  template <class In, class Out>
  void multiply_into(const std::vector<double>& rho, int channels, const In* x, int k,
                     std::size_t ld, Out* y) const;

  std::vector<uint32_t> order_, rank_;
  std::vector<uint32_t> triangle_rank_;
  std::vector<glm::uvec3> triangle_rows_;  // renumbered triangle → the rows of its vertices
  std::size_t block_rows_ = 64;
  double row_scale_ = 1.0;
  std::vector<Block> blocks_;
};

// The bounce rows' stride: `columns` rounded up to 16 elements, so that a float row is a whole
// number of 64-byte cache lines (C·K = 75 → 80 floats, 320 bytes: 5 lines instead of 5 or 6
// when rows straddle lines) and a binary16 row a whole number of 32-byte halves of one (75 → 80
// halfs, 160 bytes: always 3 lines instead of 3 or 4). solve_by_bounces aligns the blocks to 64.
std::size_t padded_row_elements(int columns);

// diag(ρ)·H of a compact gather as the solver's operator (ρ: rows() × C, in row order; columns
// C × K). apply() rounds x to float once (a V × C·K float block it keeps), then gathers;
// apply_float() and apply_half() gather float to float and binary16 to binary16 with no copy,
// rows padded_row_elements(columns) apart. A float bounce changes by ≤ 2^-24 relative, far
// below the quantisation's 3.1e-5; a binary16 bounce by ≤ 2^-11 relative (2^-25 absolute below
// 2^-14). Not for use by two threads at once.
class CompactGatherOperator final : public GatherOperator {
 public:
  CompactGatherOperator(const CompactGather& h, const std::vector<double>& rho, int channels)
      : h_(h), rho_(rho), channels_(channels) {}
  std::size_t rows() const override { return h_.rows(); }
  void apply(const double* x, int columns, double* y) const override;
  std::size_t bounce_stride(int columns) const override { return padded_row_elements(columns); }
  void apply_float(const float* x, int columns, float* y) const override {
    h_.multiply(rho_, channels_, x, columns, y, bounce_stride(columns));
  }
  void apply_half(const uint16_t* x, int columns, uint16_t* y) const override {
    h_.multiply(rho_, channels_, x, columns, y, bounce_stride(columns));
  }

 private:
  const CompactGather& h_;
  const std::vector<double>& rho_;
  int channels_;
  mutable std::vector<float> x_float_;
};

}  // namespace prt::bake
