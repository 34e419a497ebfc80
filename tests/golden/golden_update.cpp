// tests/golden/golden_update.cpp — see golden_update.h.
#include "golden_update.h"

#include <unistd.h>
#include <filesystem>
#include <stdexcept>

#include "relight/image_io.h"

namespace prt::golden {
namespace {

namespace fs = std::filesystem;

bool is_exr(const fs::path& path) {
  std::string e = path.extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e == ".exr";
}

}  // namespace

std::string UpdateResult::describe() const {
  if (!existed) return "new reference";
  const std::string figures = comparison.describe();
  if (!comparison.same_shape) return "CHANGED: " + figures;
  if (!rewritten)
    return "unchanged: stored pixels identical (render against reference: " + figures + ")";
  if (comparison.passed()) return "changed within tolerance: " + figures;
  return "CHANGED beyond tolerance: " + figures;
}

UpdateResult update_reference(const fs::path& reference, const fs::path& render) {
  UpdateResult r;
  const relight::FloatImage image = relight::read_image(render.string());
  // The render in its stored form: EXR goes through a half-float file first.
  relight::FloatImage stored = image;
  fs::path staged = render;
  if (is_exr(reference)) {
    staged = render.parent_path() / (render.stem().string() + ".half.exr");
    relight::ImageWriteOptions half;
    half.exr_half = true;
    relight::write_image(staged.string(), image.width, image.height, image.channels,
                         image.pixels.data(), half);
    stored = relight::read_image(staged.string());
  }
  r.existed = fs::exists(reference);
  bool differs = true;
  if (r.existed) {
    const relight::FloatImage old = relight::read_image(reference.string());
    r.comparison = compare_images(old, image, tolerance_for(reference));
    differs = !(old.width == stored.width && old.height == stored.height &&
                old.channels == stored.channels && old.pixels == stored.pixels);
  }
  if (differs) {
    const fs::path temporary = reference.string() + ".tmp-" + std::to_string(::getpid());
    fs::copy_file(staged, temporary, fs::copy_options::overwrite_existing);
    fs::rename(temporary, reference);
    r.rewritten = true;
  }
  return r;
}

}  // namespace prt::golden
