// bake/progress.h — progress reporting for long bakes.
//
// ProgressSink is what the baker calls: start() at the beginning of a phase, advance() from
// worker threads (thread-safe), finish() at the end. ConsoleProgress writes to stderr:
//   * on a terminal (isatty), one status line redrawn in place with '\r' (at most 10×/s);
//   * otherwise (logs, pipes), a plain line every few seconds;
//   * nothing at all when quiet.
// Each line shows the phase, done/total, vertices/s, Mrays/s and the estimated time left.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <mutex>
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

class ConsoleProgress final : public ProgressSink {
 public:
  // `out` is normally stderr; `interactive` defaults to isatty(out).
  explicit ConsoleProgress(bool quiet = false, std::FILE* out = stderr);
  ConsoleProgress(bool quiet, std::FILE* out, bool interactive);

  void start(const std::string& phase, uint64_t total) override;
  void advance(uint64_t units, uint64_t rays) override;
  void finish() override;

  // Seconds between plain lines when not interactive.
  void set_plain_interval(double seconds) { plain_interval_ = seconds; }

 private:
  using Clock = std::chrono::steady_clock;
  void draw(bool final_line);

  bool quiet_;
  std::FILE* out_;
  bool interactive_;
  double plain_interval_ = 5.0;
  std::string phase_;
  uint64_t total_ = 0;
  std::atomic<uint64_t> done_{0};
  std::atomic<uint64_t> rays_{0};
  Clock::time_point start_time_{};
  std::atomic<int64_t> last_draw_ns_{0};
  std::mutex draw_mutex_;
};

// Formats seconds as "1h02m", "3m05s" or "4.2s".
std::string format_duration(double seconds);

}  // namespace prt::bake
