// tests/golden/golden_set.cpp — see golden_set.h. The arguments of every image are here and
// only here; tests/golden/README.md shows them as `prt_golden list` prints them.
#include "golden_set.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <stdexcept>

#include "golden_scenes.h"

namespace prt::golden {
namespace {

namespace fs = std::filesystem;

std::vector<GoldenImage> make_set() {
  std::vector<GoldenImage> set;
  set.push_back({"demo",
                 "demo.png",
                 "data/demo.glb baked with interreflections (order 4, 64 rays) and relit under "
                 "data/sky.hdr; PNG at the automatic exposure: SH bake, interreflection solve, SH "
                 "relighting, renderer, auto exposure, filmic curve, sRGB",
                 nullptr,
                 {{"bake", "@DATA@/demo.glb", "-o", "@WORK@/demo.prt", "--transfer",
                   "interreflected", "--order", "4", "--samples", "64", "--seed", "1"},
                  {"relight", "@DATA@/demo.glb", "@WORK@/demo.prt", "@DATA@/sky.hdr", "-o", "@OUT@",
                   "--size", "128x96", "--spp", "2"}}});
  set.push_back(
      {"glossy_sphere",
       "glossy_sphere.exr",
       "the red sphere of `prt make-scene --scene glossy` made glTF 2.0's BRDF (roughness 0.3) "
       "with --material, glossy transfer (order 5, shadowed, 256 rays), relit toward the camera "
       "under data/sky.hdr; linear EXR: glossy bake, BRDF projection, glossy relighting kernel",
       nullptr,
       {{"make-scene", "--scene", "glossy", "-o", "@WORK@/glossy.glb"},
        {"bake", "@WORK@/glossy.glb", "--glossy", "--order", "5", "--samples", "256", "--transfer",
         "shadowed", "--material", "glossy_red=gltf:base=0.7/0.08/0.06,roughness=0.3", "--seed",
         "1", "-o", "@WORK@/glossy.prtg"},
        {"relight", "@WORK@/glossy.glb", "@WORK@/glossy.prtg", "@DATA@/sky.hdr", "-o", "@OUT@",
         "--size", "128x96", "--spp", "2", "--camera", "-0.6,1.5,2.6,-1.1,0.55,0.2,0,1,0,35"}}});
  set.push_back(
      {"cornell_radiosity",
       "cornell_radiosity.png",
       "the Cornell box lit by its lamp: radiosity on patches of at most 10 cm (804), analytic "
       "form "
       "factors, Gauss-Seidel; PNG at a fixed exposure: subdivision, form factors, solver, "
       "renderer, filmic curve",
       write_cornell_box,
       {{"radiosity", "@WORK@/cornell_box.obj", "-o", "@OUT@", "--max-edge", "0.1", "--size",
         "96x96", "--spp", "2", "--exposure", "0", "--camera",
         "0.278,0.273,-0.8,0.278,0.273,0,0,1,0,39.3"}}});
  set.push_back(
      {"haar_sun",
       "haar_sun.exr",
       "a pillar on a floor, Haar transfer (cube 32, shadowed) relit under data/sky.hdr with "
       "200 non-linear terms: the 1-degree sun's sharp shadow; linear EXR: Haar bake, "
       "wavelet transform, non-linear approximation, sparse relighting",
       write_sun_pillar,
       {{"bake", "@WORK@/sun_pillar.obj", "--basis", "haar", "--cube", "32", "--transfer",
         "shadowed", "--seed", "1", "-o", "@WORK@/haar.prt"},
        {"relight", "@WORK@/sun_pillar.obj", "@WORK@/haar.prt", "@DATA@/sky.hdr", "--terms", "200",
         "-o", "@OUT@", "--size", "128x96", "--spp", "2", "--camera",
         "-3.2,3.2,3.6,-0.5,0.2,-0.5,0,1,0,45"}}});
  set.push_back(
      {"textured_wall",
       "textured_wall.png",
       "a brick-textured wall (map_Kd) by a white cube, interreflected SH bake (order 4, 64 "
       "rays, albedo kept apart) relit under data/sky.hdr; PNG at a fixed exposure: texture "
       "decoding, per-pixel trilinear texturing, textured interreflection",
       write_textured_wall,
       {{"bake", "@WORK@/textured_wall.obj", "--transfer", "interreflected", "--order", "4",
         "--samples", "64", "--max-edge", "0.25", "--seed", "1", "-o", "@WORK@/wall.prt"},
        {"relight", "@WORK@/textured_wall.obj", "@WORK@/wall.prt", "@DATA@/sky.hdr", "--max-edge",
         "0.25", "-o", "@OUT@", "--size", "128x96", "--spp", "2", "--exposure", "-1.5", "--camera",
         "0.5,1.6,4.5,0,0.9,-1,0,1,0,45"}}});
  return set;
}

std::string substitute(std::string arg, const std::string& data, const std::string& work,
                       const std::string& out) {
  const std::pair<const char*, const std::string*> keys[] = {
      {"@DATA@", &data}, {"@WORK@", &work}, {"@OUT@", &out}};
  for (const auto& [key, value] : keys)
    for (std::size_t at; (at = arg.find(key)) != std::string::npos;)
      arg.replace(at, std::char_traits<char>::length(key), *value);
  return arg;
}

std::string shell_quote(const std::string& s) {
  if (s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789"
                          "_-./,=:@+") == std::string::npos &&
      !s.empty())
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

// Runs argv with stdout and stderr appended to `log`; returns the exit status (-1: not run).
int run_logged(const std::vector<std::string>& argv, const fs::path& log) {
  std::vector<char*> args;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  const pid_t pid = fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    if (fd < 0) _exit(127);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    ::close(fd);
    ::execv(args[0], args.data());
    _exit(127);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) < 0) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string tail_of(const fs::path& path, std::size_t lines) {
  std::ifstream in(path);
  std::vector<std::string> all;
  for (std::string line; std::getline(in, line);) all.push_back(line);
  std::string out;
  for (std::size_t i = all.size() > lines ? all.size() - lines : 0; i < all.size(); ++i)
    out += "  " + all[i] + "\n";
  return out;
}

}  // namespace

const std::vector<GoldenImage>& golden_images() {
  static const std::vector<GoldenImage> set = make_set();
  return set;
}

const GoldenImage& golden_image(const std::string& name) {
  for (const GoldenImage& image : golden_images())
    if (image.name == name) return image;
  throw std::runtime_error("no golden image named '" + name + "'");
}

fs::path references_dir() {
  return fs::path(PRT_SOURCE_DIR) / "tests" / "golden" / "references";
}

std::string command_line(const std::vector<std::string>& args, const std::string& prt,
                         const std::string& data, const std::string& work, const std::string& out) {
  std::string line = shell_quote(prt);
  for (const std::string& a : args) {
    line += ' ';
    line += shell_quote(substitute(a, data, work, out));
  }
  return line;
}

Render render_golden(const GoldenImage& image, const fs::path& prt, const fs::path& work,
                     const std::vector<std::string>& extra) {
  fs::create_directories(work);
  Render r;
  r.image = work / (image.name + fs::path(image.file).extension().string());
  r.log = work / (image.name + ".log");
  fs::remove(r.image);
  fs::remove(r.log);
  if (image.write_scene) image.write_scene(work);
  const std::string data = (fs::path(PRT_SOURCE_DIR) / "data").string();
  for (std::size_t i = 0; i < image.commands.size(); ++i) {
    std::vector<std::string> argv = {prt.string()};
    for (const std::string& a : image.commands[i])
      argv.push_back(substitute(a, data, work.string(), r.image.string()));
    if (i + 1 == image.commands.size()) argv.insert(argv.end(), extra.begin(), extra.end());
    std::string line;
    for (const std::string& a : argv) {
      if (!line.empty()) line += ' ';
      line += shell_quote(a);
    }
    std::ofstream(r.log, std::ios::app) << "$ " << line << "\n";
    const int status = run_logged(argv, r.log);
    if (status != 0)
      throw std::runtime_error(image.name + ": `" + line + "` exited with status " +
                               std::to_string(status) + "; the end of " + r.log.string() + ":\n" +
                               tail_of(r.log, 8));
  }
  if (!fs::exists(r.image))
    throw std::runtime_error(image.name + ": the commands wrote no " + r.image.string());
  return r;
}

double reported_exposure(const fs::path& log) {
  std::ifstream in(log);
  const std::regex pattern(R"(exposure (-?[0-9.]+) EV \(automatic)");
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_search(line, m, pattern)) return std::stod(m[1].str());
  }
  throw std::runtime_error(log.string() + ": no automatic exposure reported");
}

}  // namespace prt::golden
