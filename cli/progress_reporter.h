// cli/progress_reporter.h — the one progress reporter of every `prt` subcommand.
//
// The libraries never print: they take a progress callback (bake::ProgressSink for bakes and the
// ground truth, sh::ProjectionProgress for projections, a per-frame callback for relighting,
// a line callback for the report's steps); each subcommand makes one ProgressReporter and hands
// it (or its adapters) to them.
//
// Policy (all output on stderr, stdout is left to results):
//   * --quiet: nothing at all.
//   * A terminal: one status line redrawn in place (\r and ESC[K, at most 10 times a second)
//     once a phase has run 0.3 s; when the phase ends the line is completed ("done in …") and
//     kept; a phase cut short by an error has its line erased.
//   * Not a terminal (logs, pipes, tests): a plain line once a phase has run `interval` seconds,
//     then one every `interval` seconds, and a final "done" line for a phase that printed any.
//     `interval` is 5 s, or the value of the environment variable PRT_PROGRESS_INTERVAL in
//     seconds (0: a line on every update — for tests and verbose logs).
//   So commands that finish quickly print nothing, and anything longer shows where it is.
// Lines: "PHASE: 42.0% 2100/5000  1234/s  0.35 Mrays/s  3.1s left" for counted phases (bakes,
// image rows; the ray rate only when rays are counted), "PHASE: frame 7/36  1.2/s  24s left" for
// items, "PHASE: 42%  3.1s left" for fractions of abstract work (projections), and
// "PHASE: 12 so far in 3.0s" for open-ended phases.
// Thread-safe: advance() may be called from any thread; the others from one thread at a time.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <mutex>
#include <string>

#include "bake/progress.h"
#include "sh/projection.h"

namespace prt::cli {

class ProgressReporter final : public bake::ProgressSink {
 public:
  // stderr; interactive when it is a terminal; interval from PRT_PROGRESS_INTERVAL or 5 s.
  explicit ProgressReporter(bool quiet);
  ProgressReporter(bool quiet, std::FILE* out, bool interactive, double interval_seconds);
  // Clears a terminal status line left open (a phase ended by an exception), so that the error
  // message main() prints starts on a clean line.
  ~ProgressReporter() override;

  // bake::ProgressSink: a counted phase (units and rays; total 0 = open-ended).
  void start(const std::string& phase, uint64_t total) override;
  void advance(uint64_t units, uint64_t rays) override;
  void finish() override;

  // A phase of `total` named items ("frame"), advanced by advance(1, 0) or set by set_done().
  void start_items(const std::string& phase, uint64_t total, const std::string& item);
  // A phase measured in abstract work units (shown as a percentage), set by set_done().
  void start_fraction(const std::string& phase);
  // Sets the work done so far and the total (callbacks that report absolute progress).
  void set_done(uint64_t done, uint64_t total);

  // A one-off line (e.g. a step of `prt report`), unless quiet; it never interrupts a status
  // line mid-way (the line is ended first).
  void message(const std::string& line);

  // A callback for sh::project that reports into a fraction phase named `phase` (started on
  // the first call) — finish() ends it.
  sh::ProjectionProgress projection(const std::string& phase);

  bool quiet() const { return quiet_; }

 private:
  using Clock = std::chrono::steady_clock;
  enum class Style { Count, Items, Fraction };
  void begin(const std::string& phase, uint64_t total, Style style, const std::string& item);
  void maybe_draw();
  void draw(bool final_line);
  std::string format_line(bool final_line, double elapsed) const;

  bool quiet_;
  std::FILE* out_;
  bool interactive_;
  double interval_;
  Style style_ = Style::Count;
  std::string phase_, item_;
  std::atomic<uint64_t> total_{0};
  std::atomic<uint64_t> done_{0};
  std::atomic<uint64_t> rays_{0};
  Clock::time_point start_time_{};
  std::atomic<int64_t> last_draw_ns_{-1};  // −1: nothing drawn in this phase yet
  bool open_line_ = false;                 // a terminal status line without its newline
  bool in_phase_ = false;
  std::mutex draw_mutex_;
};

// Formats seconds as "1h02m", "3m05s" or "4.2s" ("?" for a negative or non-finite value).
std::string format_duration(double seconds);

}  // namespace prt::cli
