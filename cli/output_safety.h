// cli/output_safety.h — the checks every subcommand makes before it does any work, so that it
// never loses a file: an output is never one of the command's inputs nor another of its
// outputs, and an output that cannot be written is refused with the same message by every
// command.
//
// File identity: two paths name the same file when both exist and stat() (which follows
// symlinks) gives the same device and inode — so a symlink, a hard link, "./" or ".." do not get
// around the check; when neither exists, when their std::filesystem::weakly_canonical forms are
// equal (a new output reached through a symlinked folder). An existing and a missing path are
// different files.
//
// Messages (one line; main adds "prt SUBCOMMAND: "):
//   UsageError   "OPTION PATH: is the same file as the ROLE INPUT (an output never overwrites an
//                 input)", "OPTION PATH: is the same file as OPTION2 PATH2 (two outputs cannot
//                 share a file)", "stdout is the same file as the ROLE INPUT (... )",
//                 "OPTION PATH: expected an image (.exr, .hdr or .png), not '.jpg'";
//   CommandError "PATH: no such file", "PATH: is a directory, not a file" (inputs),
//                "OPTION PATH: is a directory, not a file", "OPTION PATH: is a file, not a
//                 directory", "OPTION PATH: folder DIR does not exist", "OPTION PATH: folder DIR
//                 is not writable".
#pragma once

#include <string>
#include <vector>

namespace prt::cli {

// What one command reads and writes. `role` names an input for messages ("scene", "environment
// map", ...); `option` names an output ("-o", "--csv", "--turntable frame", ...).
class CommandFiles {
 public:
  // A file the command reads. `required`: it must exist (the files a scene refers to need not:
  // their loader decides).
  void add_input(const std::string& role, const std::string& path, bool required = true);
  void add_inputs(const std::string& role, const std::vector<std::string>& paths);
  void add_output(const std::string& option, const std::string& path);
  // (Nothing is declared for an empty path: an optional output not asked for.)
  // An output file that check() also checks can be written (check_output_file: not a folder,
  // its folder exists and is writable, its extension is one of `extensions` when given).
  void add_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions = {},
                       const std::string& what = "");
  // An output folder, checked as check_output_directory does; the files the command writes in
  // it are declared with add_output.
  void add_output_directory(const std::string& option, const std::string& path);
  // A scene and every file it refers to (input_files.h): roles "scene" and "file read by the
  // scene SCENE".
  void add_scene(const std::string& scene_path);
  // An environment map, or the six faces of a %s pattern: role "environment map".
  void add_environment(const std::string& environment_path);
  // The run record of the command's main output (run_record.h): OUTPUT.run.json, declared and
  // checked as an output ("run record"); main writes it after the work. At most one per command.
  void add_run_record(const std::string& output);
  // The output whose run record main writes; empty when none is declared.
  const std::string& run_record_output() const { return run_record_output_; }

  // Throws CommandError "PATH: no such file" or "PATH: is a directory, not a file" for a
  // required input; then UsageError when an output is the same file as an input or as an
  // earlier output, or when stdout is redirected to one of the inputs
  // (`prt info s.prt --csv >> s.prt`); then checks the outputs declared by add_output_file and
  // add_output_directory. main runs it before every command's work (command_registry.h).
  void check() const;

 private:
  struct Named {
    std::string label, path;
    bool required = true;
    enum class Kind { Plain, File, Directory } kind = Kind::Plain;
    std::vector<std::string> extensions;
    std::string what;
  };
  std::vector<Named> inputs_, outputs_;
  std::string run_record_output_;
};

// True when the two paths name the same file (see the header comment).
bool same_file(const std::string& a, const std::string& b);

// An output file about to be written: not a directory, its folder exists and is writable, and
// (when `extensions` is not empty) its extension is one of them (compared case-insensitively,
// with the dot: ".png"). `what` describes the file for the extension message ("an image";
// default "a file").
void check_output_file(const std::string& option, const std::string& path,
                       const std::vector<std::string>& extensions = {},
                       const std::string& what = "");

// An output folder: not an existing file; created later by the command if it is missing, so
// its nearest existing ancestor must be a writable folder.
void check_output_directory(const std::string& option, const std::string& path);

}  // namespace prt::cli
