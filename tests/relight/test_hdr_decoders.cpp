// Tests of relight/radiance_hdr.h and relight/pfm_image.h (and their use by relight/image_io.h):
// every real .hdr/.pfm map decodes bit-identically to OpenImageIO (an independent decoder);
// images written by OpenImageIO (RLE and flat) with exactly representable values come back
// exactly; hand-made PFMs in both byte orders; the eight Radiance orientations; old-style RLE;
// and malformed files (every truncation of small valid files, bad magic, huge sizes, RLE runs
// overflowing a scanline, zero-length runs) give a one-line "NAME: problem" error, never a crash.
// Also relight/exr_header_check.h: hostile EXR headers are refused before OpenEXR allocates what
// they claim, and real EXRs pass and read as OpenImageIO reads them.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include <OpenImageIO/imageio.h>

#include "relight/exr_header_check.h"
#include "relight/image_io.h"
#include "relight/pfm_image.h"
#include "relight/radiance_hdr.h"
#include "support/error_message.h"
#include "support/test_data.h"

namespace fs = std::filesystem;
using prt::relight::decode_pfm;
using prt::relight::decode_radiance_hdr;
using prt::relight::FloatImage;
using prt::test::error_of;

namespace {

using Bytes = std::vector<unsigned char>;

std::string scratch(const std::string& name) {
  fs::create_directories(prt::test::output_path("hdr_decoders"));
  return prt::test::output_path("hdr_decoders/" + name).string();
}

Bytes read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()),
            static_cast<std::streamsize>(bytes.size()));
}

void append(Bytes& bytes, const std::string& text) {
  bytes.insert(bytes.end(), text.begin(), text.end());
}

// The same image read by OpenImageIO (its own probing open), as float, channels as stored.
FloatImage read_with_oiio(const std::string& path) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) throw std::runtime_error(path + ": OIIO: " + OIIO::geterror());
  const OIIO::ImageSpec& spec = in->spec();
  FloatImage image;
  image.width = spec.width;
  image.height = spec.height;
  image.channels = spec.nchannels;
  image.pixels.resize(static_cast<std::size_t>(spec.width) * spec.height * spec.nchannels);
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw std::runtime_error(path + ": OIIO: " + in->geterror());
  return image;
}

// Bit-identical (so NaNs with the same payload compare equal).
bool same_bits(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

// Index of the first differing float, or -1.
long first_difference(const std::vector<float>& a, const std::vector<float>& b) {
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i)
    if (std::memcmp(&a[i], &b[i], sizeof(float)) != 0) return static_cast<long>(i);
  return a.size() == b.size() ? -1 : static_cast<long>(std::min(a.size(), b.size()));
}

// "NAME: problem", one line.
void check_one_line_error(const std::string& message, const std::string& name) {
  INFO("message: " << message);
  CHECK(message.rfind(name + ": ", 0) == 0);
  CHECK(message.find('\n') == std::string::npos);
  CHECK(message.find('\r') == std::string::npos);
  CHECK(message.size() > name.size() + 2);
}

std::string hdr_error(const Bytes& file) {
  return error_of([&] { decode_radiance_hdr(file.data(), file.size(), "t.hdr"); });
}
std::string pfm_error(const Bytes& file) {
  return error_of([&] { decode_pfm(file.data(), file.size(), "t.pfm"); });
}

Bytes hdr_header(const std::string& resolution) {
  Bytes file;
  append(file, "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n" + resolution + "\n");
  return file;
}

// A PFM: values given top row first (as in FloatImage); written bottom row first.
Bytes make_pfm(int width, int height, int channels, const std::vector<float>& values,
               const std::string& scale, bool big_endian) {
  Bytes file;
  append(file, std::string(channels == 3 ? "PF" : "Pf") + "\n" + std::to_string(width) + " " +
                   std::to_string(height) + "\n" + scale + "\n");
  const std::size_t row = static_cast<std::size_t>(width) * channels;
  for (int r = height - 1; r >= 0; --r)
    for (std::size_t i = 0; i < row; ++i) {
      unsigned char b[4];
      std::memcpy(b, &values[static_cast<std::size_t>(r) * row + i], 4);
      if (big_endian) {
        std::swap(b[0], b[3]);
        std::swap(b[1], b[2]);
      }
      file.insert(file.end(), b, b + 4);
    }
  return file;
}

// Values RGBE holds exactly: channel mantissas m (the largest in 128..255) times 2^k, or 0.
std::vector<float> rgbe_exact_pixels(int width, int height, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> exponent(-30, 30), big(128, 255), channel(0, 2), coin(0, 9);
  std::vector<float> pixels(static_cast<std::size_t>(width) * height * 3);
  for (int row = 0; row < height; ++row) {
    for (int col = 0; col < width; ++col) {
      float* p = &pixels[(static_cast<std::size_t>(row) * width + col) * 3];
      // Row 1 is constant (long runs); row 2 has blocks of 200 equal pixels; the rest is noise
      // with some black pixels (exponent 0).
      const bool copy_left = (row == 1 && col > 0) || (row == 2 && col % 200 != 0);
      if (copy_left) {
        std::copy(p - 3, p, p);
        continue;
      }
      if (coin(random) == 0) continue;  // black
      const int k = exponent(random);
      const int largest = channel(random);
      const int m_max = big(random);
      for (int c = 0; c < 3; ++c) {
        const int m = c == largest ? m_max : std::uniform_int_distribution<int>(0, m_max)(random);
        p[c] = std::ldexp(static_cast<float>(m), k);
      }
    }
  }
  return pixels;
}

}  // namespace

TEST_CASE("every real .hdr and .pfm map decodes bit-identically to OpenImageIO") {
  // OpenImageIO 2.4 converts RGBE as m·2^(e−136) (its rgbe.cpp) and multiplies PFM samples by
  // |scale|; our decoders do the same, so for the standard "-Y H +X W" orientation (every file
  // here) the floats must be identical, tolerance 0.
  const fs::path root = prt::test::shared_data("");
  PRT_REQUIRE_SHARED_DATA(root);
  std::vector<fs::path> files = {prt::test::project_data("sky.hdr")};
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    std::string extension = entry.path().extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    if (entry.is_regular_file() &&
        (extension == ".hdr" || extension == ".pic" || extension == ".pfm"))
      files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  REQUIRE(files.size() >= 2);  // the bundled sky and at least one shared map
  int pfm_count = 0;
  for (const fs::path& path : files) {
    INFO(path.string());
    pfm_count += path.extension() == ".pfm";
    const FloatImage ours = prt::relight::read_image(path.string());
    const FloatImage theirs = read_with_oiio(path.string());
    REQUIRE(ours.width == theirs.width);
    REQUIRE(ours.height == theirs.height);
    REQUIRE(ours.channels == theirs.channels);
    INFO("first differing float: " << first_difference(ours.pixels, theirs.pixels));
    CHECK(same_bits(ours.pixels, theirs.pixels));
  }
  if (pfm_count == 0)
    WARN("no .pfm file in " << root.string() << "; PFMs are covered by the synthetic cases");
}

TEST_CASE("HDR written by OpenImageIO (RLE and flat, widths 1 to 40000) reads back exactly") {
  // Widths below 8 and above 32767 cannot be run-length encoded (the RLE header holds 15 bits)
  // and are written flat; 8..32767 are written with new-style RLE. The values are exact in RGBE,
  // so both our decoder and OpenImageIO's must return them exactly (tolerance 0).
  for (int width : {1, 5, 7, 8, 9, 127, 128, 129, 1000, 32767, 32768, 40000}) {
    const int height = 3;
    INFO("width " << width);
    const std::vector<float> pixels =
        rgbe_exact_pixels(width, height, static_cast<unsigned>(width));
    const std::string path = scratch("exact_" + std::to_string(width) + ".hdr");
    prt::relight::write_image(path, width, height, 3, pixels.data());
    const Bytes file = read_bytes(path);
    // Which encoding OpenImageIO chose: the first scanline starts with 2, 2, width >> 8 in RLE.
    const std::string resolution = "-Y 3 +X " + std::to_string(width) + "\n";
    const std::string text(file.begin(), file.end());
    const std::size_t data = text.find(resolution);
    REQUIRE(data != std::string::npos);
    const unsigned char* first = file.data() + data + resolution.size();
    const bool rle =
        first[0] == 2 && first[1] == 2 && first[2] == (width >> 8) && first[3] == (width & 255);
    CHECK(rle == (width >= 8 && width <= 32767));

    const FloatImage ours = decode_radiance_hdr(file.data(), file.size(), path);
    REQUIRE(ours.width == width);
    REQUIRE(ours.height == height);
    REQUIRE(ours.channels == 3);
    INFO("first differing float: " << first_difference(ours.pixels, pixels));
    CHECK(same_bits(ours.pixels, pixels));
    CHECK(same_bits(read_with_oiio(path).pixels, pixels));
  }
}

TEST_CASE("PFM in both byte orders, RGB and grey, with scales, NaN and infinities") {
  const float inf = std::numeric_limits<float>::infinity();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    int width, height, channels;
    const char* scale;
    bool big_endian;
  };
  const Case cases[] = {{3, 2, 3, "-1.0", false}, {5, 1, 1, "1.0", true}, {4, 3, 3, "-2.5", false},
                        {2, 2, 3, "1", true},     {1, 1, 1, "-1", false}, {7, 5, 1, "0.5", true}};
  int n = 0;
  for (const Case& c : cases) {
    INFO("case " << n << ": " << c.width << "x" << c.height << "x" << c.channels << " scale "
                 << c.scale);
    std::vector<float> values(static_cast<std::size_t>(c.width) * c.height * c.channels);
    for (std::size_t i = 0; i < values.size(); ++i)
      values[i] = 0.1f * static_cast<float>(i) - 0.7f + 1e-3f * static_cast<float>(i * i);
    values[0] = nan;
    if (values.size() > 2) values[1] = inf, values[2] = -inf;
    const Bytes file = make_pfm(c.width, c.height, c.channels, values, c.scale, c.big_endian);
    const std::string path = scratch("case_" + std::to_string(n++) + ".pfm");
    write_bytes(path, file);
    const FloatImage ours = prt::relight::read_image(path);
    REQUIRE(ours.width == c.width);
    REQUIRE(ours.height == c.height);
    REQUIRE(ours.channels == c.channels);
    std::vector<float> expected = values;
    const float magnitude = std::fabs(std::stof(c.scale));
    for (float& v : expected) v *= magnitude;  // OpenImageIO's convention; ×1 keeps the bits
    CHECK(same_bits(ours.pixels, expected));
    const FloatImage theirs = read_with_oiio(path);
    INFO(
        "first float differing from OpenImageIO: " << first_difference(ours.pixels, theirs.pixels));
    CHECK(same_bits(ours.pixels, theirs.pixels));
  }
}

TEST_CASE("the eight Radiance orientations come back upright") {
  // A 3-wide, 2-high image whose texel (col, row) has red = 10·row + col + 1 (row 0 at the top).
  // Radiance's pix2loc (resolu.c): for a "Y-major" line the scanlines are rows, otherwise
  // columns; "-Y" runs from the top, "+Y" from the bottom, "+X" from the left, "-X" from the
  // right. The file stores texel (x, y) of scanline s, position i accordingly.
  const int w = 3, h = 2;
  const char* const lines[] = {"-Y 2 +X 3", "-Y 2 -X 3", "+Y 2 -X 3", "+Y 2 +X 3",
                               "+X 3 -Y 2", "+X 3 +Y 2", "-X 3 +Y 2", "-X 3 -Y 2"};
  for (const char* line : lines) {
    INFO(line);
    const bool y_major = line[1] == 'Y';
    const bool major_up = line[0] == '+';  // +Y: from the bottom; +X: from the left
    const bool minor_up = line[5] == '+';  // the sign of the second axis
    Bytes file = hdr_header(line);
    const int scanlines = y_major ? h : w, length = y_major ? w : h;
    for (int s = 0; s < scanlines; ++s)
      for (int i = 0; i < length; ++i) {
        int col, row;
        if (y_major) {
          row = major_up ? h - 1 - s : s;
          col = minor_up ? i : w - 1 - i;
        } else {
          col = major_up ? s : w - 1 - s;
          row = minor_up ? h - 1 - i : i;
        }
        // Red mantissa 128 + value at exponent 136 → 128 + value; green = 128 (the marker 1, 1,
        // 1 of an old-style repeat must not appear).
        file.push_back(static_cast<unsigned char>(128 + 10 * row + col + 1));
        file.push_back(128);
        file.push_back(0);
        file.push_back(136);
      }
    const FloatImage image = decode_radiance_hdr(file.data(), file.size(), "o.hdr");
    REQUIRE(image.width == w);
    REQUIRE(image.height == h);
    for (int row = 0; row < h; ++row)
      for (int col = 0; col < w; ++col) {
        INFO("col " << col << " row " << row);
        CHECK(image.pixels[(row * w + col) * 3] == static_cast<float>(128 + 10 * row + col + 1));
        CHECK(image.pixels[(row * w + col) * 3 + 1] == 128.0f);
      }
  }
}

TEST_CASE("old-style RLE repeats the previous pixel, with growing shifts") {
  // Width 10 (too short for new-style RLE): A, repeat 3 → 4×A; B, repeat 2, repeat 0 (count
  // 0 << 8) → 3×B; C; D, repeat 1 → 2×D.  Width 300: A, repeat 43, repeat 1 (1 << 8) → 300×A.
  const unsigned char a[4] = {200, 100, 50, 130}, b[4] = {10, 20, 128, 129},
                      c[4] = {255, 0, 0, 120}, d[4] = {0, 0, 0, 0};
  auto pixel = [](Bytes& f, const unsigned char* p) { f.insert(f.end(), p, p + 4); };
  auto repeat = [](Bytes& f, unsigned char n) { f.insert(f.end(), {1, 1, 1, n}); };
  Bytes file = hdr_header("-Y 1 +X 10");
  pixel(file, a), repeat(file, 3), pixel(file, b), repeat(file, 2), repeat(file, 0);
  pixel(file, c), pixel(file, d), repeat(file, 1);
  const FloatImage image = decode_radiance_hdr(file.data(), file.size(), "old.hdr");
  const unsigned char* expected[10] = {a, a, a, a, b, b, b, c, d, d};
  for (int i = 0; i < 10; ++i) {
    INFO("pixel " << i);
    const unsigned char* e = expected[i];
    for (int ch = 0; ch < 3; ++ch) {
      const float want = e[3] == 0 ? 0.0f : std::ldexp(static_cast<float>(e[ch]), e[3] - 136);
      CHECK(image.pixels[i * 3 + ch] == want);
    }
  }
  Bytes wide = hdr_header("-Y 1 +X 300");
  pixel(wide, a), repeat(wide, 43), repeat(wide, 1);
  const FloatImage long_run = decode_radiance_hdr(wide.data(), wide.size(), "old.hdr");
  REQUIRE(long_run.pixels.size() == 900u);
  CHECK(long_run.pixels[899 * 1] == long_run.pixels[2]);
  CHECK(long_run.pixels[897] == std::ldexp(200.0f, 130 - 136));
}

TEST_CASE("every truncation of small valid files is refused with a one-line error") {
  // An RLE .hdr (width 9) and a flat one (width 5) from OpenImageIO's writer, and a PFM: every
  // proper prefix must throw a one-line "NAME: problem" (never crash or read past the end; the
  // sanitizer build checks the latter), and the whole file must decode.
  std::vector<Bytes> hdrs;
  for (int width : {9, 5}) {
    const std::vector<float> pixels = rgbe_exact_pixels(width, 3, 7);
    const std::string path = scratch("truncate_" + std::to_string(width) + ".hdr");
    prt::relight::write_image(path, width, 3, 3, pixels.data());
    hdrs.push_back(read_bytes(path));
  }
  for (const Bytes& file : hdrs) {
    CHECK_NOTHROW(decode_radiance_hdr(file.data(), file.size(), "t.hdr"));
    for (std::size_t cut = 0; cut < file.size(); ++cut) {
      const Bytes prefix(file.begin(), file.begin() + static_cast<std::ptrdiff_t>(cut));
      const std::string message = hdr_error(prefix);
      INFO("cut at " << cut << " of " << file.size());
      REQUIRE(!message.empty());
      check_one_line_error(message, "t.hdr");
    }
  }
  const Bytes pfm = make_pfm(3, 2, 3, std::vector<float>(18, 0.5f), "-1.0", false);
  CHECK_NOTHROW(decode_pfm(pfm.data(), pfm.size(), "t.pfm"));
  for (std::size_t cut = 0; cut < pfm.size(); ++cut) {
    const Bytes prefix(pfm.begin(), pfm.begin() + static_cast<std::ptrdiff_t>(cut));
    const std::string message = pfm_error(prefix);
    INFO("cut at " << cut << " of " << pfm.size());
    REQUIRE(!message.empty());
    check_one_line_error(message, "t.pfm");
  }
}

TEST_CASE("malformed Radiance files give one-line errors that say what is wrong") {
  struct Case {
    const char* what;
    Bytes file;
    const char* expect;  // a fragment of the message
  };
  auto with_data = [](const std::string& resolution, std::initializer_list<unsigned char> data) {
    Bytes f = hdr_header(resolution);
    f.insert(f.end(), data);
    return f;
  };
  auto text = [](const std::string& t) {
    Bytes f;
    append(f, t);
    return f;
  };
  const Case cases[] = {
      {"bad magic", text("#!RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1\n\x80\x80\x80\x81"),
       "#?"},
      {"no magic at all", text("RADIANCE\n"), "#?"},
      {"XYZE", text("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\n\x80\x80\x80\x81"), "xyze"},
      {"other format", text("#?RADIANCE\nFORMAT=bogus\n\n-Y 1 +X 1\n"), "bogus"},
      {"no FORMAT", text("#?RADIANCE\nEXPOSURE=1\n\n-Y 1 +X 1\n\x80\x80\x80\x81"), "FORMAT"},
      {"no blank line", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n"), "truncated"},
      {"bad resolution", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 -Y 1\n"), "resolution"},
      {"resolution junk", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1x\n"), "resolution"},
      {"10 digits", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 1 +X 1000000000\n"),
       "resolution"},
      {"zero size", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 0 +X 5\n"), "zero size"},
      {"huge", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 999999999 +X 999999999\n"),
       "too large"},
      {"just over the cap", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 16385 +X 16384\n"),
       "too large"},
      // 16384 × 8192 is within the cap: refused only because no pixel data follows (and
      // without allocating 1.5 GiB first).
      {"16k map, no data", text("#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n"),
       "truncated"},
      {"RLE length mismatch", with_data("-Y 1 +X 8", {2, 2, 0, 9, 0, 0, 0, 0}), "differs"},
      {"RLE run overflow", with_data("-Y 1 +X 8", {2, 2, 0, 8, 128 + 9, 7, 0, 0}), "overflows"},
      {"RLE run overflow later", with_data("-Y 1 +X 8", {2, 2, 0, 8, 128 + 5, 7, 4, 1, 2, 3}),
       "overflows"},
      {"RLE literal overflow", with_data("-Y 1 +X 8", {2, 2, 0, 8, 9, 1, 2, 3, 4, 5, 6, 7, 8, 9}),
       "overflows"},
      {"zero-length run", with_data("-Y 1 +X 8", {2, 2, 0, 8, 0, 128 + 8, 1, 0}), "zero-length"},
      {"RLE data ends",
       with_data("-Y 1 +X 8", {2, 2, 0, 8, 128 + 8, 1, 128 + 8, 2, 128 + 8, 3, 128 + 8}), "ends"},
      {"repeat first", with_data("-Y 1 +X 2", {1, 1, 1, 1, 128, 128, 128, 128}), "no pixel before"},
      {"repeat overflow", with_data("-Y 1 +X 3", {128, 128, 128, 128, 1, 1, 1, 3}), "overflows"},
      {"shifted repeat overflow",
       with_data("-Y 1 +X 300", {128, 128, 128, 128, 1, 1, 1, 44, 1, 1, 1, 1}), "overflows"},
  };
  for (const Case& c : cases) {
    INFO(c.what);
    const std::string message = hdr_error(c.file);
    check_one_line_error(message, "t.hdr");
    CHECK(message.find(c.expect) != std::string::npos);
  }
}

TEST_CASE("malformed PFM files give one-line errors that say what is wrong") {
  auto text = [](const std::string& t) {
    Bytes f;
    append(f, t);
    return f;
  };
  const struct {
    const char* what;
    Bytes file;
    const char* expect;
  } cases[] = {
      {"bad magic", text("PX\n1 1\n-1.0\n0000"), "PF"},
      {"P6", text("P6\n1 1\n255\n000"), "PF"},
      {"no whitespace after magic", text("PF1 1\n-1.0\n0000"), "PF"},
      {"bad width", text("PF\nx 1\n-1.0\n"), "size"},
      {"negative height", text("PF\n1 -1\n-1.0\n"), "size"},
      {"10 digits", text("PF\n1000000000 1\n-1.0\n"), "size"},
      {"zero size", text("PF\n0 0\n-1.0\n"), "zero size"},
      {"huge", text("PF\n999999999 999999999\n-1.0\n"), "too large"},
      {"zero scale", text("Pf\n1 1\n0.0\n0000"), "non-zero"},
      {"nan scale", text("Pf\n1 1\nnan\n0000"), "non-zero"},
      {"bad scale", text("Pf\n1 1\n-1.0x\n0000"), "scale"},
      {"no scale", text("Pf\n1 1\n"), "scale"},
      {"short pixels", text("Pf\n2 1\n-1.0\n00000"), "truncated"},
      {"16k map, no data", text("PF\n16384 8192\n-1.0\n"), "truncated"},
  };
  for (const auto& c : cases) {
    INFO(c.what);
    const std::string message = pfm_error(c.file);
    check_one_line_error(message, "t.pfm");
    CHECK(message.find(c.expect) != std::string::npos);
  }
  // Comments between header fields are allowed, as OpenImageIO allows them.
  const Bytes commented = text("PF\n# a comment\n1 1 # size\n-1.0\n");
  Bytes with_pixels = commented;
  const float rgb[3] = {1.0f, 2.0f, 3.0f};
  with_pixels.insert(with_pixels.end(), reinterpret_cast<const unsigned char*>(rgb),
                     reinterpret_cast<const unsigned char*>(rgb) + 12);
  const FloatImage image = decode_pfm(with_pixels.data(), with_pixels.size(), "c.pfm");
  CHECK(image.pixels == std::vector<float>{1.0f, 2.0f, 3.0f});
}

TEST_CASE("read_image picks the decoder by magic, then by extension, and names the file") {
  // A Radiance file named .pfm is decoded as Radiance (magic first); a .hdr holding something
  // else is refused by the Radiance decoder (no fall-back to OpenImageIO's probing).
  Bytes rgbe = hdr_header("-Y 1 +X 2");
  rgbe.insert(rgbe.end(), {128, 64, 32, 129, 0, 0, 0, 0});
  const std::string misnamed = scratch("radiance_named.pfm");
  write_bytes(misnamed, rgbe);
  const FloatImage image = prt::relight::read_image(misnamed);
  CHECK(image.pixels == std::vector<float>{1.0f, 0.5f, 0.25f, 0.0f, 0.0f, 0.0f});
  const std::string junk = scratch("junk.hdr");
  std::ofstream(junk) << "not an image at all\n";
  const std::string junk_error = error_of([&] { prt::relight::read_image(junk); });
  check_one_line_error(junk_error, junk);
  CHECK(junk_error.find("#?") != std::string::npos);
  // The size cap is honoured through read_image, before decoding (2x1 > 1 texel).
  const std::string capped = error_of([&] { prt::relight::read_image(misnamed, 1); });
  check_one_line_error(capped, misnamed);
  CHECK(capped.find("too large") != std::string::npos);
  // An EXR is still read by OpenImageIO, and a broken one is refused by the EXR reader.
  const std::string exr = scratch("still_oiio.exr");
  const float pixels[6] = {1, 2, 3, 4, 5, 6};
  prt::relight::write_image(exr, 2, 1, 3, pixels);
  CHECK(prt::relight::read_image(exr).pixels == std::vector<float>(pixels, pixels + 6));
  const std::string broken = scratch("broken.exr");
  std::ofstream(broken, std::ios::binary) << "v/1\x01\x02\x00\x00garbage";
  check_one_line_error(error_of([&] { prt::relight::read_image(broken); }), broken);
}

TEST_CASE("EXR headers claiming more than the file holds are refused before OpenEXR sees them") {
  // A valid EXR from OpenImageIO's writer passes and reads back; the shared EXR passes and reads
  // bit-identically to OpenImageIO's own (probing, file-based) open.
  const std::string good_path = scratch("good.exr");
  std::vector<float> pixels(8 * 4 * 3);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = 0.25f * static_cast<float>(i);
  prt::relight::write_image(good_path, 8, 4, 3, pixels.data());
  const Bytes good = read_bytes(good_path);
  CHECK(prt::relight::exr_header_problem(good.data(), good.size(), prt::relight::kMaxImageTexels)
            .empty());
  CHECK(prt::relight::read_image(good_path).pixels == pixels);
  const fs::path shared = prt::test::shared_data("probes/grace_latlong.exr");
  if (fs::exists(shared)) {
    const Bytes real = read_bytes(shared.string());
    CHECK(prt::relight::exr_header_problem(real.data(), real.size(), prt::relight::kMaxImageTexels)
              .empty());
    CHECK(same_bits(prt::relight::read_image(shared.string()).pixels,
                    read_with_oiio(shared.string()).pixels));
  } else {
    WARN("skipping the shared EXR: " << shared.string() << " is missing");
  }

  // Hostile variants of the good file (the first two are what fuzz_env_map_exr found: OpenEXR
  // allocated 1.9 GB for the string, and line buffers for a 7.6-million-pixel-wide window).
  auto find = [&](const Bytes& file, const std::string& what) {
    const auto at = std::search(file.begin(), file.end(), what.begin(), what.end());
    REQUIRE(at != file.end());
    return static_cast<std::size_t>(at - file.begin()) + what.size();
  };
  auto put_i32 = [](Bytes& file, std::size_t at, std::int32_t v) {
    for (int k = 0; k < 4; ++k) file[at + k] = static_cast<unsigned char>((v >> (8 * k)) & 255);
  };
  const std::size_t window = find(good, std::string("dataWindow\0box2i\0", 17)) + 4;
  struct Case {
    const char* what;
    Bytes file;
    const char* expect;
  };
  std::vector<Case> cases;
  {
    Bytes f(good.begin(), good.begin() + 8);  // magic and version, then a 1.9 GB string
    append(f, std::string("capDate\0string\0", 15));
    const std::size_t at = f.size();
    f.resize(f.size() + 4);
    put_i32(f, at, 1929379859);
    append(f, "2024:01:01 00:00:00");
    cases.push_back({"huge string", f, "claims 1929379859 bytes"});
  }
  {
    Bytes f = good;
    put_i32(f, window + 8, 7631721);  // xMax
    cases.push_back({"wide window", f, "side over 65536"});
  }
  {
    Bytes f = good;
    put_i32(f, window + 8, 59999);  // 60000 x 60000 = 3.6e9 texels
    put_i32(f, window + 12, 59999);
    cases.push_back({"huge window", f, "too large"});
  }
  {
    Bytes f(good.begin(), good.begin() + 8);  // a preview of 65536 x 65536 in 8 bytes
    append(f, std::string("preview\0preview\0", 16));
    f.insert(f.end(), {8, 0, 0, 0, 0, 0, 1, 0, 0, 0, 1, 0});
    cases.push_back({"huge preview", f, "preview"});
  }
  {
    Bytes f(good.begin(), good.begin() + 8);  // a string vector whose string claims 1 GB
    append(f, std::string("names\0stringvector\0", 19));
    f.insert(f.end(), {8, 0, 0, 0, 0, 0, 0, 64, 'a', 'b', 'c', 'd'});
    cases.push_back({"huge string in a vector", f, "string vector"});
  }
  int n = 0;
  for (const Case& c : cases) {
    INFO(c.what);
    const std::string problem = prt::relight::exr_header_problem(c.file.data(), c.file.size(),
                                                                 prt::relight::kMaxImageTexels);
    INFO(problem);
    CHECK(problem.find(c.expect) != std::string::npos);
    // Through read_image: refused with a one-line error naming the file.
    const std::string path = scratch("hostile_" + std::to_string(n++) + ".exr");
    write_bytes(path, c.file);
    const std::string message = error_of([&] { prt::relight::read_image(path); });
    check_one_line_error(message, path);
    CHECK(message.find(c.expect) != std::string::npos);
  }
  // Every truncation of the good file is refused (by the check or by OpenEXR), never a crash.
  for (std::size_t cut = 0; cut < good.size(); cut += 7) {
    const std::string path = scratch("cut.exr");
    write_bytes(path, Bytes(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(cut)));
    INFO("cut at " << cut << " of " << good.size());
    check_one_line_error(error_of([&] { prt::relight::read_image(path); }), path);
  }
}

TEST_CASE("the EXR fuzz target's findings are refused with one-line errors") {
  // fuzz/corpus/fuzz_env_map_exr/regression_*: a 1.9 GB string attribute, a data window 7.6
  // million pixels wide (a 10 s timeout in OpenEXR under ASan) and a bad line-offset table that
  // made OpenImageIO's in-memory reader read before its buffer (run under the sanitizer build to
  // see that regress). Each file is the fuzz input: a selector byte, then the EXR.
  const fs::path dir = fs::path(PRT_SOURCE_DIR) / "fuzz/corpus/fuzz_env_map_exr";
  int found = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().filename().string().rfind("regression_", 0) != 0) continue;
    ++found;
    const Bytes input = read_bytes(entry.path().string());
    REQUIRE(input.size() > 1);
    const std::string path = scratch(entry.path().filename().string() + ".exr");
    write_bytes(path, Bytes(input.begin() + 1, input.end()));
    INFO(entry.path().string());
    check_one_line_error(error_of([&] { prt::relight::read_image(path); }), path);
  }
  CHECK(found == 3);
}
