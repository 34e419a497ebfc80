// prt/haar/transform.h — the 2D non-standard Haar wavelet transform of cube-map faces.
//
// Ng, Ramamoorthi & Hanrahan (SIGGRAPH 2003) project lighting and transfer onto the 2D Haar
// basis of each cube face; we use the non-standard (quadtree) decomposition of Stollnitz,
// DeRose & Salesin, "Wavelets for Computer Graphics" (1995/96): each step maps every 2×2
// block (p00 p01 / p10 p11) of the current averages to
//   average                    (p00 + p01 + p10 + p11)/2
//   band 0, horizontal detail  (p00 − p01 + p10 − p11)/2
//   band 1, vertical detail    (p00 + p01 − p10 − p11)/2
//   band 2, diagonal detail    (p00 − p01 − p10 + p11)/2,
// an orthogonal 4×4 matrix, so the whole transform is orthonormal: Σ c² = Σ x², and the
// inverse is the transpose. Internally it runs in double; a round trip loses only the two
// float roundings of the stored coefficients and the output.
//
// Coefficient index q ∈ [0, N²) of an N×N face (quadtree order, coarse to fine):
//   q = 0                      the scaling coefficient (basis 1/N on the whole face);
//   q ∈ [4^j, 4^(j+1)), j = 0 .. log2(N)−1   level j:  q = 4^j + band·4^j + y·2^j + x,
//        band ∈ {0 horizontal, 1 vertical, 2 diagonal}, (y, x) ∈ [0, 2^j)² the block position.
//   Basis function of level j: support = the block of s×s texels, s = N/2^j, at rows y·s..,
//   columns x·s..; value ±1/s there (band 0: + on the left half, − on the right; band 1: + on
//   the top half, − on the bottom; band 2: the product of the two signs), 0 elsewhere.
// On a cube map the wavelet index is i = face·N² + q (faces +X, −X, +Y, −Y, +Z, −Z); the
// coefficients of a 6-face RGB cube are stored like CubeMap::rgb: rgb[3i + c].
// Compiles as C++17.
// References: [4], [9] of docs/REFERENCES.md.
#pragma once

#include <cstdint>
#include <vector>

#include "prt/core/status.h"
#include "prt/haar/cube_map.h"

namespace prt {

// The basis and index convention above, as every JSON output that describes Haar transfer
// prints it.
inline constexpr const char* kHaarBasisConvention =
    "2D non-standard Haar wavelets per cube face (quadtree order, coarse to fine), index "
    "i = face*N^2 + q, faces +X,-X,+Y,-Y,+Z,-Z, scene frame glTF (+Y up)";

// Where a quadtree-ordered coefficient lives.
struct HaarCoefficientInfo {
  int level = 0;         // j (0 for the scaling coefficient and the three coarsest details)
  int band = -1;         // −1 scaling, 0 horizontal, 1 vertical, 2 diagonal
  int support_size = 0;  // s: the support is s×s texels
  int support_row = 0;   // top-left texel of the support
  int support_col = 0;
};

// Describes coefficient q of an N×N face (N a power of two, 0 ≤ q < N²).
HaarCoefficientInfo describe_haar_coefficient(int size, int q) noexcept;

// Value of the orthonormal basis function q at texel (row, col) of an N×N face — the slow
// reference the fast transform is tested against.
double evaluate_haar_basis(int size, int q, int row, int col) noexcept;

// Forward transform of one N×N face, in place: on entry data[stride·(row·N + col)] holds the
// texel values; on return data[stride·q] holds coefficient q. N must be a power of two ≥ 1.
// `stride` lets one channel of interleaved RGB be transformed (stride 3).
void forward_haar_2d(float* data, int size, int stride = 1);

// The exact inverse of forward_haar_2d, in place.
void inverse_haar_2d(float* data, int size, int stride = 1);

// Haar coefficients of an RGB cube map: rgb[3·(face·N² + q) + c].
struct WaveletCube {
  int size = 0;
  std::vector<float> rgb;
  int64_t coefficient_count() const { return int64_t{kCubeFaceCount} * size * size; }
};

// Transforms every face and channel of a cube map. Errors: invalid size or rgb size.
Result<WaveletCube> transform_cube(const CubeMap& cube);

// The inverse of transform_cube.
Result<CubeMap> inverse_transform_cube(const WaveletCube& wavelets);

}  // namespace prt
