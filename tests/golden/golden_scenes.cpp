// tests/golden/golden_scenes.cpp — see golden_scenes.h.
#include "golden_scenes.h"

#include <array>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "relight/image_io.h"

namespace prt::golden {
namespace {

namespace fs = std::filesystem;

using Vec3 = std::array<double, 3>;

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Builds an OBJ of planar quads, one object per `begin`, one flat normal per quad.
class ObjWriter {
 public:
  explicit ObjWriter(const std::string& mtllib) {
    text_ << "# written by tests/golden (prt golden-image set)\n";
    if (!mtllib.empty()) text_ << "mtllib " << mtllib << "\n";
  }

  void begin(const std::string& object, const std::string& material) {
    text_ << "o " << object << "\n";
    if (!material.empty()) text_ << "usemtl " << material << "\n";
  }

  // A quad with corners in order around it, turned so that its normal points toward `toward`
  // (away from it when `away`); uv (optional) gives each corner's texture coordinate.
  void quad(std::array<Vec3, 4> c, const Vec3& toward, bool away = false,
            std::array<std::array<double, 2>, 4> uv = {}, bool textured = false) {
    Vec3 n = cross(sub(c[1], c[0]), sub(c[2], c[0]));
    const Vec3 centre = {(c[0][0] + c[2][0]) / 2, (c[0][1] + c[2][1]) / 2, (c[0][2] + c[2][2]) / 2};
    const bool flip = (dot(n, sub(toward, centre)) < 0) != away;
    if (flip) {
      std::swap(c[1], c[3]);
      std::swap(uv[1], uv[3]);
      n = {-n[0], -n[1], -n[2]};
    }
    const double length = std::sqrt(dot(n, n));
    for (const Vec3& p : c) text_ << "v " << p[0] << " " << p[1] << " " << p[2] << "\n";
    text_ << "vn " << n[0] / length << " " << n[1] / length << " " << n[2] / length << "\n";
    if (textured)
      for (const auto& t : uv) text_ << "vt " << t[0] << " " << t[1] << "\n";
    ++normals_;
    text_ << "f";
    for (int k = 0; k < 4; ++k) {
      const int v = vertices_ + k + 1;
      text_ << " " << v << "/";
      if (textured) text_ << texcoords_ + k + 1;
      text_ << "/" << normals_;
    }
    text_ << "\n";
    vertices_ += 4;
    if (textured) texcoords_ += 4;
  }

  // A parallelogram from `corner` along edge_u and edge_v as nu × nv quads sharing their
  // vertices, facing the side of cross(edge_u, edge_v) (the other side when `flip`).
  void grid(const Vec3& corner, const Vec3& edge_u, const Vec3& edge_v, int nu, int nv,
            bool flip = false) {
    Vec3 n = cross(edge_u, edge_v);
    const double length = std::sqrt(dot(n, n)) * (flip ? -1 : 1);
    text_ << "vn " << n[0] / length << " " << n[1] / length << " " << n[2] / length << "\n";
    ++normals_;
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {
        const double u = double(i) / nu, v = double(j) / nv;
        text_ << "v";
        for (int k = 0; k < 3; ++k) text_ << " " << corner[k] + u * edge_u[k] + v * edge_v[k];
        text_ << "\n";
      }
    const auto at = [&](int i, int j) { return vertices_ + j * (nu + 1) + i + 1; };
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        int q[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
        if (flip) std::swap(q[1], q[3]);
        text_ << "f";
        for (int v : q) text_ << " " << v << "//" << normals_;
        text_ << "\n";
      }
    vertices_ += (nu + 1) * (nv + 1);
  }

  // The five faces of an axis-aligned box standing on y = lo[1] (its bottom is left out).
  void box(const Vec3& lo, const Vec3& hi) {
    const Vec3 mid = {(lo[0] + hi[0]) / 2, (lo[1] + hi[1]) / 2, (lo[2] + hi[2]) / 2};
    const double x0 = lo[0], y0 = lo[1], z0 = lo[2], x1 = hi[0], y1 = hi[1], z1 = hi[2];
    quad({{{x0, y1, z0}, {x1, y1, z0}, {x1, y1, z1}, {x0, y1, z1}}}, mid, true);
    quad({{{x0, y0, z0}, {x1, y0, z0}, {x1, y1, z0}, {x0, y1, z0}}}, mid, true);
    quad({{{x0, y0, z1}, {x1, y0, z1}, {x1, y1, z1}, {x0, y1, z1}}}, mid, true);
    quad({{{x0, y0, z0}, {x0, y0, z1}, {x0, y1, z1}, {x0, y1, z0}}}, mid, true);
    quad({{{x1, y0, z0}, {x1, y0, z1}, {x1, y1, z1}, {x1, y1, z0}}}, mid, true);
  }

  std::string str() const { return text_.str(); }

 private:
  std::ostringstream text_;
  int vertices_ = 0, texcoords_ = 0, normals_ = 0;
};

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.good()) throw std::runtime_error(path.string() + ": cannot write");
}

// The Cornell box's published corners (millimetres) scaled to metres.
Vec3 mm(double x, double y, double z) {
  return {x / 1000, y / 1000, z / 1000};
}

void cornell_block(ObjWriter& obj, const std::array<Vec3, 4>& top, double height) {
  Vec3 mid = {0, height / 2, 0};
  for (const Vec3& p : top) mid = {mid[0] + p[0] / 4, mid[1], mid[2] + p[2] / 4};
  obj.quad(top, mid, true);
  for (int k = 0; k < 4; ++k) {
    const Vec3& a = top[static_cast<std::size_t>(k)];
    const Vec3& b = top[static_cast<std::size_t>((k + 1) % 4)];
    obj.quad({{{a[0], 0, a[2]}, {b[0], 0, b[2]}, b, a}}, mid, true);
  }
}

}  // namespace

void write_cornell_box(const fs::path& dir) {
  write_text(dir / "cornell_box.mtl",
             "newmtl white\nKd 0.73 0.73 0.73\n"
             "newmtl red\nKd 0.63 0.065 0.05\n"
             "newmtl green\nKd 0.14 0.45 0.091\n"
             "newmtl light\nKd 0.78 0.78 0.78\nKe 20 20 20\n");
  ObjWriter obj("cornell_box.mtl");
  const Vec3 inside = mm(278, 274, 280);
  obj.begin("floor", "white");
  obj.quad({mm(552.8, 0, 0), mm(0, 0, 0), mm(0, 0, 559.2), mm(549.6, 0, 559.2)}, inside);
  obj.begin("ceiling", "white");
  obj.quad({mm(556, 548.8, 0), mm(556, 548.8, 559.2), mm(0, 548.8, 559.2), mm(0, 548.8, 0)},
           inside);
  obj.begin("back_wall", "white");
  obj.quad({mm(549.6, 0, 559.2), mm(0, 0, 559.2), mm(0, 548.8, 559.2), mm(556, 548.8, 559.2)},
           inside);
  obj.begin("green_wall", "green");
  obj.quad({mm(0, 0, 559.2), mm(0, 0, 0), mm(0, 548.8, 0), mm(0, 548.8, 559.2)}, inside);
  obj.begin("red_wall", "red");
  obj.quad({mm(552.8, 0, 0), mm(549.6, 0, 559.2), mm(556, 548.8, 559.2), mm(556, 548.8, 0)},
           inside);
  obj.begin("lamp", "light");  // 1 cm below the ceiling, so the two do not coincide
  obj.quad({mm(343, 538.8, 227), mm(343, 538.8, 332), mm(213, 538.8, 332), mm(213, 538.8, 227)},
           inside);
  obj.begin("short_block", "white");
  cornell_block(obj, {mm(130, 165, 65), mm(82, 165, 225), mm(240, 165, 272), mm(290, 165, 114)},
                0.165);
  obj.begin("tall_block", "white");
  cornell_block(obj, {mm(423, 330, 247), mm(265, 330, 296), mm(314, 330, 456), mm(472, 330, 406)},
                0.330);
  write_text(dir / "cornell_box.obj", obj.str());
}

void write_sun_pillar(const fs::path& dir) {
  // Subdivided here rather than with --max-edge, which Haar relighting does not take: cells of
  // 0.125, the floor's 1089 vertices resolve the shadow's edge.
  ObjWriter obj("");
  obj.begin("floor", "");
  obj.grid({-2, 0, 2}, {4, 0, 0}, {0, 0, -4}, 32, 32);
  obj.begin("pillar", "");
  const double a = -0.25, b = 0.25, h = 1.5;
  obj.grid({a, h, b}, {0.5, 0, 0}, {0, 0, -0.5}, 4, 4);  // top, facing +Y
  obj.grid({a, 0, b}, {0.5, 0, 0}, {0, h, 0}, 4, 12);    // +Z
  obj.grid({b, 0, a}, {-0.5, 0, 0}, {0, h, 0}, 4, 12);   // -Z
  obj.grid({b, 0, b}, {0, 0, -0.5}, {0, h, 0}, 4, 12);   // +X
  obj.grid({a, 0, a}, {0, 0, 0.5}, {0, h, 0}, 4, 12);    // -X
  write_text(dir / "sun_pillar.obj", obj.str());
}

void write_textured_wall(const fs::path& dir) {
  // A running-bond brick pattern: bricks 32 × 16 texels, 2-texel mortar, a little variation per
  // brick (the pattern of scripts/textured-example.py at half the size).
  const int w = 128, h = 64;
  std::vector<float> texels;
  texels.reserve(static_cast<std::size_t>(w * h * 3));
  for (int y = 0; y < h; ++y) {
    const int course = y / 16;
    for (int x = 0; x < w; ++x) {
      const int shifted = x + (course % 2 ? 16 : 0);
      const int brick = (shifted / 32) % (w / 32);
      const bool mortar = y % 16 < 2 || shifted % 32 < 2;
      const int k = (brick * 7 + course * 13) % 5;
      const std::array<int, 3> rgb = mortar
                                         ? std::array<int, 3>{200, 195, 185}
                                         : std::array<int, 3>{150 + 12 * k, 55 + 5 * k, 40 + 4 * k};
      for (int c : rgb) texels.push_back(static_cast<float>(c) / 255.f);
    }
  }
  relight::write_image((dir / "bricks.png").string(), w, h, 3, texels.data());
  write_text(dir / "textured_wall.mtl",
             "newmtl bricks\nKd 1 1 1\nmap_Kd bricks.png\n"
             "newmtl grey\nKd 0.5 0.5 0.5\n"
             "newmtl white\nKd 0.8 0.8 0.8\n");
  ObjWriter obj("textured_wall.mtl");
  obj.begin("wall", "bricks");
  obj.quad({{{-2, 0, -1}, {2, 0, -1}, {2, 2, -1}, {-2, 2, -1}}}, {0, 1, 1}, false,
           {{{0, 0}, {2, 0}, {2, 2}, {0, 2}}}, true);
  obj.begin("floor", "grey");
  obj.quad({{{-3, 0, -1}, {3, 0, -1}, {3, 0, 3}, {-3, 0, 3}}}, {0, 1, 0});
  obj.begin("cube", "white");
  obj.box({0.4, 0, 0.0}, {1.2, 0.8, 0.8});
  write_text(dir / "textured_wall.obj", obj.str());
}

}  // namespace prt::golden
