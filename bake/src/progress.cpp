// bake/src/progress.cpp — console progress with rates and time left (see progress.h).
#include "bake/progress.h"

#include <unistd.h>
#include <cmath>

namespace prt::bake {

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

ConsoleProgress::ConsoleProgress(bool quiet, std::FILE* out)
    : ConsoleProgress(quiet, out, out != nullptr && isatty(fileno(out)) != 0) {}

ConsoleProgress::ConsoleProgress(bool quiet, std::FILE* out, bool interactive)
    : quiet_(quiet || out == nullptr), out_(out), interactive_(interactive) {}

void ConsoleProgress::start(const std::string& phase, uint64_t total) {
  std::lock_guard<std::mutex> lock(draw_mutex_);
  phase_ = phase;
  total_ = total;
  done_ = 0;
  rays_ = 0;
  start_time_ = Clock::now();
  last_draw_ns_ = 0;
}

void ConsoleProgress::advance(uint64_t units, uint64_t rays) {
  done_.fetch_add(units, std::memory_order_relaxed);
  rays_.fetch_add(rays, std::memory_order_relaxed);
  if (quiet_) return;
  const int64_t now =
      std::chrono::duration_cast<std::chrono::nanoseconds>(Clock::now() - start_time_).count();
  const auto interval = static_cast<int64_t>((interactive_ ? 0.1 : plain_interval_) * 1e9);
  int64_t last = last_draw_ns_.load(std::memory_order_relaxed);
  if (now - last < interval) return;
  if (!last_draw_ns_.compare_exchange_strong(last, now)) return;  // another thread draws
  std::unique_lock<std::mutex> lock(draw_mutex_, std::try_to_lock);
  if (lock.owns_lock()) draw(false);
}

void ConsoleProgress::finish() {
  if (quiet_) return;
  std::lock_guard<std::mutex> lock(draw_mutex_);
  draw(true);
}

void ConsoleProgress::draw(bool final_line) {
  const double elapsed = std::chrono::duration<double>(Clock::now() - start_time_).count();
  const uint64_t done = done_.load(), rays = rays_.load();
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double mrays = elapsed > 0 ? static_cast<double>(rays) / elapsed * 1e-6 : 0.0;
  const double left = rate > 0 && total_ >= done ? static_cast<double>(total_ - done) / rate : NAN;
  const double pct =
      total_ ? 100.0 * static_cast<double>(done) / static_cast<double>(total_) : 100.0;
  char line[256];
  if (total_ == 0) {  // open-ended phase (solver iterations): count and rate only
    std::snprintf(line, sizeof line, "%s: %llu %s in %s", phase_.c_str(),
                  static_cast<unsigned long long>(done), final_line ? "done" : "so far",
                  format_duration(elapsed).c_str());
  } else if (final_line && rays == 0) {
    std::snprintf(line, sizeof line, "%s: %llu/%llu done in %s", phase_.c_str(),
                  static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                  format_duration(elapsed).c_str());
  } else if (final_line) {
    std::snprintf(line, sizeof line, "%s: %llu/%llu done in %s (%.0f/s, %.2f Mrays/s)",
                  phase_.c_str(), static_cast<unsigned long long>(done),
                  static_cast<unsigned long long>(total_), format_duration(elapsed).c_str(), rate,
                  mrays);
  } else {
    std::snprintf(line, sizeof line, "%s: %5.1f%% %llu/%llu  %.0f/s  %.2f Mrays/s  %s left",
                  phase_.c_str(), pct, static_cast<unsigned long long>(done),
                  static_cast<unsigned long long>(total_), rate, mrays,
                  format_duration(left).c_str());
  }
  if (interactive_)
    std::fprintf(out_, "\r%-78s%s", line, final_line ? "\n" : "");
  else
    std::fprintf(out_, "%s\n", line);
  std::fflush(out_);
}

}  // namespace prt::bake
