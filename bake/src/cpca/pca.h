// bake/src/cpca/pca.h (internal) — the dense linear algebra of the CPCA compressor, all in double:
// a cyclic Jacobi eigensolver for small symmetric matrices, modified Gram–Schmidt, and the
// principal vectors of one cluster by randomized subspace iteration with Rayleigh–Ritz
// (Halko, Martinsson & Tropp 2011, algorithm 4.4; [85] of docs/REFERENCES.md).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace prt::detail {

// Eigen-decomposition of the symmetric p×p matrix a (row-major; destroyed): eigenvalues in
// descending order into values[p], eigenvectors as the COLUMNS of vectors[p·p] (row-major).
void jacobi_eigen(std::size_t p, std::vector<double>& a, std::vector<double>& values,
                  std::vector<double>& vectors);

// Orthonormalizes the `rows` rows (each of length d) of q in place, in order, by modified
// Gram–Schmidt applied twice; a row whose norm falls below 1e-9 of its norm before projection
// (it lies in the span of the earlier rows) becomes zero. Returns the number of nonzero rows.
std::size_t orthonormalize_rows(std::size_t rows, std::size_t d, double* q);

// Σ a[i]·b[i] with four partial sums (fixed order: deterministic).
double dot(const double* a, const double* b, std::size_t n);

struct PcaInput {
  const float* x = nullptr;           // all vectors, vertex-major, d floats each
  std::size_t d = 0;                  // dimension
  const uint32_t* members = nullptr;  // ascending vertex indices of the cluster
  std::size_t member_count = 0;
  std::size_t k = 0;                          // principal vectors wanted
  const std::vector<double>* warm = nullptr;  // k·d previous vectors (or null / empty)
  unsigned power_iterations = 2;
  uint64_t seed = 0;  // for the random start vectors
};

// mean[d] and basis[k·d] (orthonormal rows sorted by decreasing variance; zero rows when the
// members span fewer than k dimensions). When k ≥ min(members, d) the rows span every
// centred member exactly (to rounding). Holds O(256·d + members·(k + 8)) doubles: the centred
// members are made 256 at a time, never all at once. Throws std::bad_alloc only.
void cluster_pca(const PcaInput& in, std::vector<double>* mean, std::vector<double>* basis);

}  // namespace prt::detail
