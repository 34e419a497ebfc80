// tests/golden/prt_golden.cpp — the golden-image set from the command line (used by
// scripts/update-golden.sh; the test is test_golden_images):
//
//   prt_golden list                          each image: file, what it shows, its commands
//   prt_golden render PRT WORK [NAME...]     render the set (or the named images) into WORK
//   prt_golden compare REFERENCE RENDER [DIFF.png]
//                                            per-pixel comparison; exit 1 when beyond tolerance
//   prt_golden update PRT WORK [NAME...]     render and replace the references whose pixels
//                                            changed; one line per image saying how much
//
// Exit status: 0 success, 1 a comparison failed or a command did not run, 2 bad usage.
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>
#include <vector>

#include "golden_set.h"
#include "golden_update.h"
#include "image_compare.h"
#include "relight/image_io.h"

namespace fs = std::filesystem;
using namespace prt::golden;

namespace {

int usage() {
  std::fprintf(stderr,
               "usage: prt_golden list | render PRT WORK [NAME...] | compare REFERENCE RENDER "
               "[DIFF.png] | update PRT WORK [NAME...]\n");
  return 2;
}

std::vector<const GoldenImage*> selected(const std::vector<std::string>& names) {
  std::vector<const GoldenImage*> out;
  if (names.empty())
    for (const GoldenImage& image : golden_images()) out.push_back(&image);
  for (const std::string& name : names) out.push_back(&golden_image(name));
  return out;
}

int list() {
  for (const GoldenImage& image : golden_images()) {
    std::printf("%s -> tests/golden/references/%s\n  %s\n", image.name.c_str(), image.file.c_str(),
                image.what.c_str());
    // A placeholder that needs no quoting, shown as $WORK.
    const std::string work = "WORKDIR",
                      out = work + "/" + image.name + fs::path(image.file).extension().string();
    for (const auto& command : image.commands) {
      std::string line = command_line(command, "prt", "data", work, out);
      for (std::size_t at; (at = line.find(work)) != std::string::npos;)
        line.replace(at, work.size(), "$WORK");
      std::printf("  %s\n", line.c_str());
    }
  }
  return 0;
}

int render(const fs::path& prt, const fs::path& work, const std::vector<std::string>& names) {
  for (const GoldenImage* image : selected(names)) {
    const Render r = render_golden(*image, prt, work);
    std::printf("%s: %s\n", image->name.c_str(), r.image.c_str());
  }
  return 0;
}

int compare(const fs::path& reference, const fs::path& render, const fs::path& diff) {
  const prt::relight::FloatImage a = prt::relight::read_image(reference.string());
  const prt::relight::FloatImage b = prt::relight::read_image(render.string());
  const Tolerance tolerance = tolerance_for(reference);
  const Comparison c = compare_images(a, b, tolerance);
  std::printf("%s: %s: %s\n", render.c_str(), c.passed() ? "pass" : "FAIL", c.describe().c_str());
  if (!diff.empty() && c.same_shape) write_difference_image(diff, a, b, tolerance);
  return c.passed() ? 0 : 1;
}

int update(const fs::path& prt, const fs::path& work, const std::vector<std::string>& names) {
  for (const GoldenImage* image : selected(names)) {
    const Render r = render_golden(*image, prt, work);
    const fs::path reference = references_dir() / image->file;
    prt::relight::FloatImage old;
    if (fs::exists(reference)) old = prt::relight::read_image(reference.string());
    const UpdateResult u = update_reference(reference, r.image);
    if (u.existed && u.comparison.same_shape && u.rewritten)
      write_difference_image(work / (image->name + "_diff.png"), old,
                             prt::relight::read_image(r.image.string()), tolerance_for(reference));
    std::printf("%s (%s): %s\n", image->name.c_str(), image->file.c_str(), u.describe().c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  try {
    if (args.size() == 1 && args[0] == "list") return list();
    if (args.size() >= 3 && args[0] == "render")
      return render(args[1], args[2], {args.begin() + 3, args.end()});
    if ((args.size() == 3 || args.size() == 4) && args[0] == "compare")
      return compare(args[1], args[2], args.size() == 4 ? fs::path(args[3]) : fs::path());
    if (args.size() >= 3 && args[0] == "update")
      return update(args[1], args[2], {args.begin() + 3, args.end()});
    return usage();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "prt_golden: %s\n", e.what());
    return 1;
  }
}
