// prt/core/atomic_file.h — replacing a file atomically: the new contents go to a temporary file in
// the same folder, which is then renamed over the target.
//
// Contract of both functions:
//   * The temporary is PATH.tmp-<process id>, beside PATH, so the rename never crosses a file
//     system: on POSIX a reader of PATH sees either the old file or the complete new one.
//   * On success PATH holds the new contents and the temporary is gone.
//   * On any failure (including an exception thrown by `write`) the temporary is removed and
//     PATH is untouched: an existing file keeps its old contents, a missing one stays missing.
//   * Errors are returned as a Status whose message names PATH; the functions throw nothing
//     of their own (an exception from `write` propagates after the clean-up).
// Compiles as C++17.
#pragma once

#include <cstddef>
#include <functional>
#include <string>

#include "prt/core/status.h"

namespace prt {

// PATH.tmp-<process id>: the temporary both functions below write, for writers that stream
// to it themselves and rename it when complete (may throw std::bad_alloc).
std::string temporary_path_for(const std::string& path);

// Replaces PATH with the file that `write` creates. `write` is given the temporary's name and
// must create that file, fill it and close it, then return Status::Ok() or an error naming PATH
// (returned unchanged). Then the temporary is renamed over PATH; if that fails the error is
// "PATH: cannot rename PATH.tmp-<pid>: <reason>". For writers that need a file name (image
// libraries, glTF writers, other programs).
Status replace_file_atomically(const std::string& path,
                               const std::function<Status(const std::string& temporary)>& write);

// Replaces PATH with the `size` bytes at `data` (written, flushed and closed, then renamed).
// Errors: "PATH: cannot create TEMPORARY: <reason>", "PATH: cannot write TEMPORARY: <reason>",
// the rename error above, and "PATH: out of memory".
Status write_file_atomically(const std::string& path, const void* data, std::size_t size);

}  // namespace prt
