// bake/progress.h — the progress interface of long bakes.
//
// ProgressSink is what the bakers call: start() at the beginning of a phase, advance() from
// worker threads (thread-safe), finish() at the end. The library never prints: the `prt`
// executable's reporter (cli/progress_reporter.h) implements it, and tests may pass their own.
#pragma once

#include <cstdint>
#include <string>

namespace prt::bake {

class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  // Begins a phase of `total` units (vertices); total = 0: open-ended (solver iterations).
  virtual void start(const std::string& phase, uint64_t total) = 0;
  // Adds `units` done and `rays` cast; callable concurrently from any thread.
  virtual void advance(uint64_t units, uint64_t rays) = 0;
  // Ends the current phase.
  virtual void finish() = 0;
};

}  // namespace prt::bake
