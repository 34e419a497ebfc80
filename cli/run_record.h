// cli/run_record.h — what a run cost, kept out of the files it writes.
//
// Output files hold only the result: the same command gives the same bytes whatever the thread
// count, the machine or the time. What changes from run to run goes to a JSON sidecar beside the
// command's main output, OUT.run.json (docs/FORMAT.md, "Run records"):
//   {"command": "prt bake demo.glb -o demo.prt", "output": "demo.prt", "prt_version": "0.1.0",
//    "host": "build-01", "finished_utc": "2026-12-04T21:30:00Z", "threads": 2,
//    "seconds": 3.21, "phase_seconds": {"rays": 2.90, "interreflection solve": 0.25},
//    "peak_resident_bytes": 123456789}
// Commands that measure it add "phase_cpu_seconds": the process CPU time (every thread) of their
// phases, when present.
// "seconds" is the wall time from the start of the command's checks to the end of its work;
// "threads" the worker threads the work was allowed (--threads, or every hardware thread);
// "peak_resident_bytes" prt/core/memory_budget.h's peak_resident_bytes() at the end.
//
// A command declares the record with CommandFiles::add_run_record(OUT) in its files() (so the
// output checks cover OUT.run.json like any output); main writes it after the command's work has
// succeeded (command_registry.h), atomically (prt/core/atomic_file.h). The work reports its
// threads and phases to run_record() as it goes.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace prt::cli {

struct RunRecord {
  int threads = 0;  // 0: not reported (the command runs on one thread or does not say)
  std::vector<std::pair<std::string, double>> phases;      // name, wall seconds, in order
  std::vector<std::pair<std::string, double>> cpu_phases;  // name, process CPU seconds, in order

  void phase(const std::string& name, double seconds) { phases.emplace_back(name, seconds); }
  void cpu_phase(const std::string& name, double seconds) {
    cpu_phases.emplace_back(name, seconds);
  }
};

// The record of this process's run (one command per process).
RunRecord& run_record();

// The threads a `--threads N` option runs on: N, or every hardware thread for 0.
int resolved_threads(int requested);

// OUT.run.json.
std::string run_record_path(const std::string& output);

// Writes OUT.run.json for `output` with run_record()'s threads and phases. On failure removes an
// older OUT.run.json (it would describe another run) and throws CommandError
// "OUT.run.json: cannot write ...: <reason>" (the message of the atomic write).
void write_run_record(const std::string& output, const std::string& command_line,
                      const std::string& version, double seconds);

// FILE.run.json's object, or null when there is none (a file written elsewhere, by an older prt,
// or moved without it); a record that does not parse is given as {"unreadable": reason}.
nlohmann::json read_run_record(const std::string& file);

// `prt info --json`: j["run"] = FILE.run.json's object when there is one.
void add_run_record_json(nlohmann::json& j, const std::string& file);

// `prt info`'s text lines: the run's time, phases, threads, host and peak memory, or that
// FILE.run.json is absent.
void print_run_record(const std::string& file);

}  // namespace prt::cli
