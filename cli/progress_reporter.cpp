// cli/progress_reporter.cpp — the progress reporter of the `prt` subcommands (see
// progress_reporter.h).
#include "progress_reporter.h"

#include <unistd.h>
#include <cmath>
#include <cstdlib>

namespace prt::cli {
namespace {

constexpr double kTerminalDelay = 0.3;          // seconds before a terminal status line appears
constexpr double kTerminalInterval = 0.1;       // seconds between redraws on a terminal
constexpr double kDefaultInterval = 5.0;        // seconds between plain lines
constexpr const char* kEraseLine = "\r\033[K";  // carriage return, erase to the end of line

double interval_from_environment() {
  const char* text = std::getenv("PRT_PROGRESS_INTERVAL");
  if (!text || !*text) return kDefaultInterval;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value) || value < 0) return kDefaultInterval;
  return value;
}

int64_t to_ns(double seconds) {
  return static_cast<int64_t>(seconds * 1e9);
}

}  // namespace

std::string format_duration(double seconds) {
  char buf[64];
  if (!std::isfinite(seconds) || seconds < 0) return "?";
  if (seconds < 60) {
    std::snprintf(buf, sizeof buf, "%.1fs", seconds);
  } else if (seconds < 3600) {
    const int s = static_cast<int>(seconds);
    std::snprintf(buf, sizeof buf, "%dm%02ds", s / 60, s % 60);
  } else {
    const int m = static_cast<int>(seconds / 60);
    std::snprintf(buf, sizeof buf, "%dh%02dm", m / 60, m % 60);
  }
  return buf;
}

ProgressReporter::ProgressReporter(bool quiet)
    : ProgressReporter(quiet, stderr, isatty(fileno(stderr)) != 0, interval_from_environment()) {}

ProgressReporter::ProgressReporter(bool quiet, std::FILE* out, bool interactive,
                                   double interval_seconds)
    : quiet_(quiet || out == nullptr),
      out_(out),
      interactive_(interactive),
      interval_(interval_seconds) {}

ProgressReporter::~ProgressReporter() {
  if (quiet_ || !open_line_) return;
  std::fputs(kEraseLine, out_);
  std::fflush(out_);
}

void ProgressReporter::begin(const std::string& phase, uint64_t total, Style style,
                             const std::string& item) {
  std::lock_guard<std::mutex> lock(draw_mutex_);
  phase_ = phase;
  item_ = item;
  style_ = style;
  total_ = total;
  done_ = 0;
  rays_ = 0;
  start_time_ = Clock::now();
  last_draw_ns_ = -1;
  in_phase_ = true;
}

void ProgressReporter::start(const std::string& phase, uint64_t total) {
  begin(phase, total, Style::Count, "");
}

void ProgressReporter::start_items(const std::string& phase, uint64_t total,
                                   const std::string& item) {
  begin(phase, total, Style::Items, item);
}

void ProgressReporter::start_fraction(const std::string& phase) {
  begin(phase, 0, Style::Fraction, "");
}

void ProgressReporter::advance(uint64_t units, uint64_t rays) {
  done_.fetch_add(units, std::memory_order_relaxed);
  rays_.fetch_add(rays, std::memory_order_relaxed);
  maybe_draw();
}

void ProgressReporter::set_done(uint64_t done, uint64_t total) {
  total_ = total;
  done_ = done;
  maybe_draw();
}

// Draws when the phase has run long enough and the last line is old enough; one thread draws.
void ProgressReporter::maybe_draw() {
  if (quiet_) return;
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_time_).count();
  int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
  if (last < 0) {
    if (now < to_ns(interactive_ ? kTerminalDelay : interval_)) return;
  } else if (now - last < to_ns(interactive_ ? kTerminalInterval : interval_)) {
    return;
  }
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;  // another thread draws
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock()) draw(false);
}

void ProgressReporter::finish() {
  std::lock_guard<std::mutex> lock(draw_mutex_);
  // A phase that never showed a line stays silent (it was quick).
  if (!quiet_ && in_phase_ && last_draw_ns_.load() >= 0) draw(true);
  in_phase_ = false;
}

void ProgressReporter::message(const std::string& line) {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(draw_mutex_);
  if (open_line_) std::fputc('\n', out_);
  open_line_ = false;
  std::fprintf(out_, "%s\n", line.c_str());
  std::fflush(out_);
}

sh::ProjectionProgress ProgressReporter::projection(const std::string& phase) {
  return [this, phase, started = false](uint64_t done, uint64_t total) mutable {
    if (!started) {
      start_fraction(phase);
      started = true;
    }
    set_done(done, total);
  };
}

std::string ProgressReporter::format_line(bool final_line, double elapsed) const {
  const uint64_t done = done_.load(), total = total_.load(), rays = rays_.load();
  const auto count = [](uint64_t n) { return static_cast<unsigned long long>(n); };
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double left = rate > 0 && total >= done ? static_cast<double>(total - done) / rate : NAN;
  const double pct = total ? 100.0 * static_cast<double>(done) / static_cast<double>(total) : 0.0;
  const std::string took = format_duration(elapsed);
  char line[320];
  if (style_ == Style::Fraction) {
    if (final_line)
      std::snprintf(line, sizeof line, "%s: done in %s", phase_.c_str(), took.c_str());
    else
      std::snprintf(line, sizeof line, "%s: %3.0f%%  %s left", phase_.c_str(), pct,
                    format_duration(left).c_str());
  } else if (style_ == Style::Items) {
    if (final_line)
      std::snprintf(line, sizeof line, "%s: %llu %ss done in %s", phase_.c_str(), count(done),
                    item_.c_str(), took.c_str());
    else
      std::snprintf(line, sizeof line, "%s: %s %llu/%llu  %.2f/s  %s left", phase_.c_str(),
                    item_.c_str(), count(done), count(total), rate, format_duration(left).c_str());
  } else if (total == 0) {  // open-ended phase (solver iterations): count and time only
    std::snprintf(line, sizeof line, "%s: %llu %s in %s", phase_.c_str(), count(done),
                  final_line ? "done" : "so far", took.c_str());
  } else if (final_line) {
    const int n = std::snprintf(line, sizeof line, "%s: %llu/%llu done in %s", phase_.c_str(),
                                count(done), count(total), took.c_str());
    if (rays > 0 && n > 0 && static_cast<std::size_t>(n) < sizeof line)
      std::snprintf(line + n, sizeof line - n, " (%.0f/s, %.2f Mrays/s)", rate,
                    static_cast<double>(rays) / elapsed * 1e-6);
  } else if (rays == 0) {
    std::snprintf(line, sizeof line, "%s: %5.1f%% %llu/%llu  %.0f/s  %s left", phase_.c_str(), pct,
                  count(done), count(total), rate, format_duration(left).c_str());
  } else {
    std::snprintf(line, sizeof line, "%s: %5.1f%% %llu/%llu  %.0f/s  %.2f Mrays/s  %s left",
                  phase_.c_str(), pct, count(done), count(total), rate,
                  elapsed > 0 ? static_cast<double>(rays) / elapsed * 1e-6 : 0.0,
                  format_duration(left).c_str());
  }
  return line;
}

void ProgressReporter::draw(bool final_line) {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_time_).count();
  const std::string line = format_line(final_line, elapsed);
  if (interactive_) {
    std::fprintf(out_, "%s%s%s", kEraseLine, line.c_str(), final_line ? "\n" : "");
    open_line_ = !final_line;
  } else {
    std::fprintf(out_, "%s\n", line.c_str());
  }
  std::fflush(out_);
}

}  // namespace prt::cli
