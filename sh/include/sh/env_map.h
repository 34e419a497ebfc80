// sh/env_map.h — environment-map layouts: texel directions, exact texel solid angles,
// the inverse mapping and bilinear lookup.
//
// Frame: glTF's, right-handed, +Y up, cameras look down −Z (README.md, "Conventions"). All
// directions are unit vectors (x, y, z) in that frame. Texel (col, row) covers the continuous image
// coordinates [col, col+1) × [row, row+1); row 0 is the top row; its centre is (col+½, row+½).
//
// Layouts:
//   LatLong  W×H (2:1).  u = (col+½)/W, v = (row+½)/H; θ = π v from +Y (row 0 = zenith),
//            φ = 2π(u − ½) = atan2(z, x): the centre column looks to +X, u = ¼ to −Z, u = ¾ to +Z.
//            Direction (sin θ cos φ, cos θ, sin θ sin φ). Blender / glTF-environment convention.
//   Angular  W×W, Debevec light probe. u, v ∈ [−1, 1] with v up; r = √(u²+v²) ≤ 1,
//            θ = π r measured from −Z, direction = (sin θ·u/r, sin θ·v/r, −cos θ): the centre
//            looks to −Z, image right is +X, image up is +Y, the rim r = 1 is the single point +Z.
//            dω = π² sinc(π r) du dv, i.e. (2π/w)²·sinc θ per texel at its centre.
//   Cross    3s×4s Debevec vertical cross of square faces of size s, face-local a (right) and
//            b (down) in [−1, 1] at texel centres:
//              +Y at cell (1,0): (a, 1, −b)      −X at (0,1): (−1, −b, −a)
//              −Z at (1,1):      (a, −b, −1)     +X at (2,1): (1, −b, a)
//              −Y at (1,2):      (a, −1, b)      +Z at (1,3): (a, b, 1)   (stored upside down)
//            The six other cells are empty (not on the sphere).
//   Faces    w×6w: six square faces stacked top to bottom in the order +X, −X, +Y, −Y, +Z, −Z.
//            Every face is mapped exactly as in the cross, except +Z, which is NOT stored upside
//            down here: +Z is (−a, −b, 1). So each face looks as seen from the centre of the cube
//            with +Y up on the side faces (right of +X is +Z, right of +Z is −X, ...), +Y seen with
//            −Z at its bottom edge and −Y with +Z at its bottom edge.
//
// Solid angles are exact per texel (no centre-point approximation):
//   LatLong  (cos θ0 − cos θ1)·2π/W for the row's polar band [θ0, θ1]; any W×H (1×1 is 4π).
//   Cube     the texel-corner formula Ω = Σ± atan(ab/√(a²+b²+1)) over the texel's corners
//            (faces at distance 1; e.g. Mark VandeWettering / Manne Öhrström, "cube map texel
//            solid angle").
//   Angular  the integral of π² sinc(π r) over the texel square clipped to the disc r ≤ 1,
//            computed by Green's theorem as the boundary integral ∮ G(r) dφ with
//            G(r) = 1 − cos(π·min(r, 1)) (G is the radial antiderivative of the density, and
//            G(1) = 2 takes care of the clipping); each straight edge piece is integrated by
//            Gauss–Legendre (the integrand is an entire function of the edge parameter, so the
//            rule converges to rounding), and pieces outside the disc contribute 2·Δφ exactly.
// For every layout and size the texels' solid angles sum to 4π to rounding.
//
// Header only needs the C++17 standard library.
// References: [23] of docs/REFERENCES.md.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace prt::sh {

enum class EnvLayout { LatLong, Angular, Cross, Faces };

// "latlong", "angular", "cross", "faces".
const char* layout_name(EnvLayout layout) noexcept;

// Parses a layout name (case-sensitive; also accepts "lat-long", "equirect", "probe").
bool parse_layout(std::string_view text, EnvLayout* layout) noexcept;

// An environment map of linear radiance: row-major, row 0 at the top, 3 floats (RGB) per texel.
struct EnvMap {
  EnvLayout layout = EnvLayout::LatLong;
  int width = 0, height = 0;
  std::vector<float> rgb;
};

// True if width × height fits the layout (lat-long 2:1, angular 1:1, cross 3:4 with width
// divisible by 3, faces height = 6·width; all non-empty). On false, *why (if given) says why.
bool validate_layout(EnvLayout layout, int width, int height, std::string* why) noexcept;

// Guesses the layout from the aspect ratio: 2:1 lat-long, 1:1 angular, 3:4 cross (width
// divisible by 3), 1:6 faces. *ok is false (and LatLong returned) when nothing fits.
EnvLayout guess_layout(int width, int height, bool* ok) noexcept;

// Unit direction of the centre of texel (col, row). Returns false for texels not on the sphere:
// the six empty cells of a cross, angular texels entirely outside the disc r ≤ 1, and
// out-of-range indices. An angular texel that straddles the rim with its centre outside the disc
// (tiny solid angle, next to +Z) gets the direction of its centre moved radially inwards to
// r = (r_min + 1)/2, r_min being the distance from the image centre to the texel's square.
bool texel_direction(EnvLayout layout, int width, int height, int col, int row,
                     double dir[3]) noexcept;

// Exact solid angle (steradians) of texel (col, row); 0 for texels not on the sphere.
double texel_solid_angle(EnvLayout layout, int width, int height, int col, int row) noexcept;

// The solid angles of all texels, row-major (width·height values). Faster than calling
// texel_solid_angle per texel (angular maps share edge integrals; lat-long is per row) and
// identical to it.
std::vector<double> texel_solid_angles(EnvLayout layout, int width, int height);

// Continuous image coordinates of a direction (the inverse of texel_direction: the centre of
// texel (c, r) maps back to (c + ½, r + ½)). The direction need not be normalised. Returns false
// for a zero or non-finite direction or an invalid size.
bool direction_to_texel(EnvLayout layout, int width, int height, const double dir[3], double* col,
                        double* row) noexcept;

// Bilinear lookup of the map in a direction. Lat-long wraps horizontally and clamps at the poles;
// angular clamps to the image; cross and faces filter within the face (clamped at its edges, no
// filtering across cube edges). Writes 0 for an invalid direction or an empty map.
void sample_bilinear(const EnvMap& env, const double dir[3], float rgb[3]) noexcept;

}  // namespace prt::sh
