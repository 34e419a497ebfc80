// tests/golden/golden_set.h — the golden-image set: which renders, made by which `prt` commands.
//
// Each image is made by running the prt executable with fixed arguments (fixed seeds, few
// samples, low orders, tiny sizes), after writing its scene when prt does not ship it
// (golden_scenes.h). The references live in tests/golden/references/ under `file`; the test
// (test_golden_images.cpp) and scripts/update-golden.sh both render through render_golden, so
// the two cannot drift apart. In the commands, @DATA@ is the project's data/ folder, @WORK@ a
// scratch folder and @OUT@ the image to write.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace prt::golden {

struct GoldenImage {
  std::string name;  // e.g. "demo"
  std::string file;  // reference file name, e.g. "demo.png" (.png tone mapped, .exr linear)
  std::string what;  // one line: what it shows and what it covers
  void (*write_scene)(const std::filesystem::path& dir) = nullptr;  // into @WORK@, or none
  std::vector<std::vector<std::string>> commands;  // prt arguments (after "prt"), in order
};

// The set, in a fixed order.
const std::vector<GoldenImage>& golden_images();

// The entry named `name`; throws std::runtime_error for an unknown name.
const GoldenImage& golden_image(const std::string& name);

// The folder of the committed references (PRT_SOURCE_DIR/tests/golden/references).
std::filesystem::path references_dir();

// One command with the placeholders replaced, as a shell-quoted line for people to read.
std::string command_line(const std::vector<std::string>& args, const std::string& prt,
                         const std::string& data, const std::string& work, const std::string& out);

struct Render {
  std::filesystem::path image;  // work/NAME.png or .exr
  std::filesystem::path log;    // work/NAME.log: every command line and its stdout and stderr
};

// Writes the scene (if any) into `work` (created), runs the commands with the prt executable
// `prt`, and returns the image. `extra` is appended to the last command (a test's perturbation,
// e.g. {"--exposure", "-1.5"}). Throws std::runtime_error naming the image, the command and the
// log when a command fails or the image is not written.
Render render_golden(const GoldenImage& image, const std::filesystem::path& prt,
                     const std::filesystem::path& work, const std::vector<std::string>& extra = {});

// The automatic exposure a PNG render reported ("exposure -1.75 EV (automatic"), from its log;
// throws when the log has none.
double reported_exposure(const std::filesystem::path& log);

}  // namespace prt::golden
