// Outputs never overwrite inputs, and unwritable outputs are refused alike (output_safety.h).
#include "output_safety.h"

#include <cctype>
#include <filesystem>
#include <system_error>

#include <sys/stat.h>
#include <unistd.h>

#include "command_registry.h"
#include "input_files.h"
#include "run_record.h"

namespace prt::cli {
namespace {

namespace fs = std::filesystem;

struct Identity {
  bool exists = false;
  dev_t device = 0;
  ino_t inode = 0;
  fs::path canonical;
};

Identity identify(const std::string& path) {
  Identity id;
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) {
    id.exists = true;
    id.device = st.st_dev;
    id.inode = st.st_ino;
  }
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) absolute = fs::path(path);
  id.canonical = fs::weakly_canonical(absolute, ec);
  if (ec) id.canonical = absolute.lexically_normal();
  return id;
}

bool same_identity(const Identity& a, const Identity& b) {
  if (a.exists != b.exists) return false;
  if (a.exists) return a.device == b.device && a.inode == b.inode;
  return a.canonical == b.canonical;
}

std::string lower_extension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}

std::string join(const std::vector<std::string>& items) {
  std::string text;
  for (std::size_t i = 0; i < items.size(); ++i)
    text += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + items[i];
  return text;
}

// The folder a new file or folder `path` is created in ("." for a bare name).
fs::path parent_folder(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? fs::path(".") : parent;
}

void check_writable_folder(const std::string& option, const std::string& path,
                           const fs::path& folder) {
  std::error_code ec;
  if (!fs::is_directory(folder, ec))
    throw CommandError(option + " " + path + ": folder " + folder.string() + " does not exist");
  if (::access(folder.c_str(), W_OK) != 0)
    throw CommandError(option + " " + path + ": folder " + folder.string() + " is not writable");
}

}  // namespace

bool same_file(const std::string& a, const std::string& b) {
  return same_identity(identify(a), identify(b));
}

void CommandFiles::add_input(const std::string& role, const std::string& path, bool required) {
  if (!path.empty()) inputs_.push_back({role, path, required, Named::Kind::Plain, {}, ""});
}

void CommandFiles::add_inputs(const std::string& role, const std::vector<std::string>& paths) {
  for (const std::string& path : paths) add_input(role, path);
}

void CommandFiles::add_scene(const std::string& scene_path) {
  const std::vector<std::string> files = scene_files(scene_path);
  add_input("scene", files.front());
  for (std::size_t i = 1; i < files.size(); ++i)
    add_input("file read by the scene " + scene_path + ":", files[i], /*required=*/false);
}

void CommandFiles::add_environment(const std::string& environment_path) {
  add_inputs("environment map", environment_files(environment_path));
}

void CommandFiles::add_output(const std::string& option, const std::string& path) {
  if (!path.empty()) outputs_.push_back({option, path, false, Named::Kind::Plain, {}, ""});
}

void CommandFiles::add_output_file(const std::string& option, const std::string& path,
                                   const std::vector<std::string>& extensions,
                                   const std::string& what) {
  if (!path.empty()) outputs_.push_back({option, path, false, Named::Kind::File, extensions, what});
}

void CommandFiles::add_run_record(const std::string& output) {
  if (output.empty()) return;
  run_record_output_ = output;
  add_output_file("run record", run_record_path(output));
}

void CommandFiles::add_output_directory(const std::string& option, const std::string& path) {
  if (!path.empty()) outputs_.push_back({option, path, false, Named::Kind::Directory, {}, ""});
}

void CommandFiles::check() const {
  for (const Named& input : inputs_) {
    if (!input.required) continue;
    std::error_code ec;
    const fs::file_status status = fs::status(input.path, ec);
    if (!fs::exists(status)) throw CommandError(input.path + ": no such file");
    if (fs::is_directory(status)) throw CommandError(input.path + ": is a directory, not a file");
  }
  std::vector<Identity> inputs;
  for (const Named& input : inputs_) inputs.push_back(identify(input.path));
  std::vector<Identity> outputs;
  for (const Named& output : outputs_) {
    const Identity id = identify(output.path);
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (same_identity(id, inputs[i]))
        throw UsageError(output.label + " " + output.path + ": is the same file as the " +
                         inputs_[i].label + " " + inputs_[i].path +
                         " (an output never overwrites an input)");
    for (std::size_t i = 0; i < outputs.size(); ++i)
      if (same_identity(id, outputs[i]))
        throw UsageError(output.label + " " + output.path + ": is the same file as " +
                         outputs_[i].label + " " + outputs_[i].path +
                         " (two outputs cannot share a file)");
    outputs.push_back(id);
  }
  // stdout redirected to an input: `>` has emptied it already; `>>` would append to it.
  struct stat out {};
  if (::fstat(STDOUT_FILENO, &out) == 0 && S_ISREG(out.st_mode))
    for (std::size_t i = 0; i < inputs.size(); ++i)
      if (inputs[i].exists && inputs[i].device == out.st_dev && inputs[i].inode == out.st_ino)
        throw UsageError("stdout is the same file as the " + inputs_[i].label + " " +
                         inputs_[i].path + " (an output never overwrites an input)");
  for (const Named& output : outputs_) {
    if (output.kind == Named::Kind::File)
      check_output_file(output.label, output.path, output.extensions, output.what);
    else if (output.kind == Named::Kind::Directory)
      check_output_directory(output.label, output.path);
  }
}

void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions, const std::string& what) {
  if (path.empty()) throw UsageError(option + ": an output path is required");
  std::error_code ec;
  if (fs::is_directory(path, ec))
    throw CommandError(option + " " + path + ": is a directory, not a file");
  check_writable_folder(option, path, parent_folder(path));
  if (extensions.empty()) return;
  const std::string ext = lower_extension(path);
  for (const std::string& allowed : extensions)
    if (ext == allowed) return;
  throw UsageError(option + " " + path + ": expected " + (what.empty() ? "a file" : what) + " (" +
                   join(extensions) + ")" +
                   (ext.empty() ? ", but the name has no extension" : ", not '" + ext + "'"));
}

void check_output_directory(const std::string& option, const std::string& path) {
  if (path.empty()) throw UsageError(option + ": an output folder is required");
  std::error_code ec;
  if (fs::exists(path, ec) && !fs::is_directory(path, ec))
    throw CommandError(option + " " + path + ": is a file, not a directory");
  fs::path folder = fs::absolute(path, ec);
  while (!folder.empty() && !fs::exists(folder, ec) && folder != folder.root_path())
    folder = folder.parent_path();
  if (!fs::is_directory(folder, ec))
    throw CommandError(option + " " + path + ": is inside " + folder.string() +
                       ", which is not a directory");
  if (::access(folder.c_str(), W_OK) != 0)
    throw CommandError(option + " " + path + ": folder " + folder.string() + " is not writable");
}

}  // namespace prt::cli
