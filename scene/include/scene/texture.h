// scene/texture.h — base-colour textures: decoded images, linearised, with a mip chain, and how
// they are sampled.
//
// Colour: glTF's baseColorTexture and OBJ's map_Kd hold sRGB-encoded colour (glTF 2.0 §3.9.2;
// MTL files are authored the same way), so every sample is linearised with the sRGB EOTF of IEC
// 61966-2-1 (the exact piecewise curve, not a 2.2 power) before anything else. Alpha is dropped
// (prt has no transparency); one- and two-channel images are grey (channel 0 replicated).
//
// Coordinates: glTF's: (u, v) = (0, 0) is the top-left corner of the image's first texel row,
// u grows to the right and v downwards; texel (i, j) covers [i, i+1)/width × [j, j+1)/height and
// its centre is at ((i + ½)/width, (j + ½)/height). (The OBJ loader flips v, whose origin is the
// bottom-left.) Wrap modes as in glTF/OpenGL: REPEAT, CLAMP_TO_EDGE, MIRRORED_REPEAT.
//
// Filtering — what sample() returns for a footprint f (the width, in UV units, of the surface
// region a sample stands for):
//   - magnification (f · max(width, height) <= 1, or the sampler has no mipmaps): bilinear
//     interpolation of the four nearest level-0 texel centres (nearest texel when the sampler
//     asks for NEAREST), with the wrap modes applied to each texel index;
//   - minification with mipmaps: trilinear — bilinear in the two mip levels around
//     λ = log2(f · max(width, height)), blended linearly in λ (the standard GPU filter, isotropic).
// The mip chain is built in linear colour by an exact box filter: level k+1 has ⌊w/2⌋ × ⌊h/2⌋
// texels (at least 1), each the area-weighted mean of the level-k texels it covers (fractional
// coverage for odd sizes), so every level keeps the image's mean.
// Why: the bake samples the albedo where a ray hits (f = 0): bilinear, an unbiased point sample
// of the reconstructed texture, and the many rays of a vertex do the area averaging. The renderer
// samples once per sub-pixel ray and gives the ray's footprint: trilinear mipmapping removes the
// aliasing a far, finely textured surface would otherwise show.
// Non-finite coordinates sample at (0, 0); coordinates beyond ±2^30 are held there.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "scene/float_image.h"

namespace prt::scene {

// Texture images larger than this are refused (8192 × 8192; 1 GiB as linear float RGB with mips).
inline constexpr std::size_t kMaxTextureTexels = std::size_t{1} << 26;

// Textured albedo (texture × factor) is clamped to at most this in every channel: an albedo of 1
// reflects all light and makes an enclosed interreflection solve diverge, and textures often
// hold pure-white texels. The loader notes every texture the clamp touches.
inline constexpr float kMaxTexturedAlbedo = 0.99f;

enum class TextureWrap { Repeat, ClampToEdge, MirroredRepeat };

struct TextureSampler {
  TextureWrap wrap_s = TextureWrap::Repeat;  // along u
  TextureWrap wrap_t = TextureWrap::Repeat;  // along v
  bool nearest_magnification = false;        // glTF magFilter NEAREST
  bool nearest_minification = false;         // minFilter NEAREST or NEAREST_MIPMAP_*
  bool mipmaps = true;                       // minFilter *_MIPMAP_* or unset
};

// The sRGB EOTF (IEC 61966-2-1): display-encoded value in [0, 1] to linear.
double srgb_to_linear(double encoded);

// A texture image in linear RGB with its mip chain (level 0 = the image).
class TextureImage {
 public:
  struct Level {
    int width = 0, height = 0;
    std::vector<float> rgb;  // 3 floats per texel, row-major, row 0 at the top
  };

  // Takes the colour of an image (1 to 4 channels, see above), linearised as sRGB unless
  // srgb_encoded is false (an MTL `-colorspace linear`), and builds the mip chain. Samples are
  // clamped to [0, 1]. `name` (a file path, or "image N" of a glTF file) names it in messages.
  static TextureImage from_image(const FloatImage& image, std::string name,
                                 bool srgb_encoded = true);
  // The alpha channel of an image as linear grey (r = g = b = alpha, clamped to [0, 1]): glTF
  // parameter textures that keep a value in A (KHR_materials_specular's specularTexture). An image
  // without alpha (one or three channels) is opaque: every sample is 1 (glTF 2.0 §3.8.3).
  static TextureImage from_image_alpha(const FloatImage& image, std::string name);
  // The same from linear RGB samples (3 per texel, row 0 at the top): for tests and procedural
  // textures.
  static TextureImage from_linear_rgb(int width, int height, std::vector<float> rgb,
                                      std::string name);

  const std::string& name() const { return name_; }
  int width() const { return levels_.front().width; }
  int height() const { return levels_.front().height; }
  const std::vector<Level>& levels() const { return levels_; }
  glm::dvec3 mean() const { return mean_; }       // mean of level 0, per channel
  glm::vec3 maximum() const { return maximum_; }  // largest level-0 value, per channel
  bool grey() const { return grey_; }             // every texel has r = g = b

  // The filtered colour at `uv` for a footprint of `footprint` UV units (see above).
  glm::vec3 sample(glm::vec2 uv, const TextureSampler& sampler, float footprint = 0.f) const;

 private:
  std::string name_;
  std::vector<Level> levels_;
  glm::dvec3 mean_{0.0};
  glm::vec3 maximum_{0.f};
  bool grey_ = true;
};

// A material's base colour: factor × the texture, read with `sampler` at the primitive's vertex
// texture coordinates (Scene::texcoords).
struct BaseColorTexture {
  std::shared_ptr<const TextureImage> image;
  TextureSampler sampler;
  glm::vec3 factor{1.f};  // glTF baseColorFactor rgb (1 for OBJ)
  int texcoord = 0;       // the TEXCOORD_n set the coordinates came from (glTF)

  // factor × image->sample(...), clamped to [0, kMaxTexturedAlbedo].
  glm::vec3 albedo(glm::vec2 uv, float footprint = 0.f) const;
};

}  // namespace prt::scene
