// tests/cli/test_progress_reporter.cpp — the CLI's progress reporter (cli/progress_reporter.h) as
// a unit, with a file as its output: throttling of plain lines, --quiet, a terminal's status line
// redrawn in place and erased when a phase is cut short.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <catch2/catch.hpp>

#include "progress_reporter.h"
#include "support/test_data.h"
#include "support/text_lines.h"

namespace fs = std::filesystem;

namespace {

fs::path scratch(const std::string& name) {
  const fs::path dir = prt::test::output_path("progress_reporter") / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

using prt::test::count_containing;
using prt::test::lines_of;

}  // namespace

TEST_CASE("progress reporter: plain lines are throttled to one per interval") {
  const fs::path dir = scratch("reporter");
  const fs::path log = dir / "log.txt";
  std::FILE* file = std::fopen(log.string().c_str(), "w");
  REQUIRE(file);
  const double interval = 0.05;
  const auto start = std::chrono::steady_clock::now();
  {
    prt::cli::ProgressReporter reporter(false, file, false, interval);
    reporter.start_fraction("work");
    for (int i = 1; i <= 400; ++i) {
      reporter.set_done(i, 400);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
    reporter.finish();
    reporter.start_items("quick", 10, "item");  // ends before the first interval: silent
    reporter.set_done(10, 10);
    reporter.finish();
  }
  const double elapsed =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::fclose(file);
  const std::vector<std::string> lines = lines_of(read_all(log));
  INFO(read_all(log));
  // One line per elapsed interval at most (the first after one interval), plus the final line.
  REQUIRE(!lines.empty());
  CHECK(lines.size() <= static_cast<std::size_t>(elapsed / interval) + 1);
  CHECK(lines.back().find("work: done in") == 0);
  CHECK(count_containing(read_all(log), "quick") == 0);
  if (elapsed > 4 * interval) CHECK(lines.size() >= 2);  // progress while it worked

  // Quiet: nothing, whatever the interval.
  std::FILE* silent = std::fopen(log.string().c_str(), "w");
  REQUIRE(silent);
  {
    prt::cli::ProgressReporter reporter(true, silent, false, 0.0);
    reporter.start("bake", 5);
    reporter.advance(5, 100);
    reporter.message("a step");
    reporter.finish();
  }
  std::fclose(silent);
  CHECK(read_all(log).empty());
}

TEST_CASE("progress reporter: a terminal gets one status line redrawn in place") {
  const fs::path log = scratch("terminal") / "tty.txt";
  std::FILE* file = std::fopen(log.string().c_str(), "w");
  REQUIRE(file);
  {
    prt::cli::ProgressReporter reporter(false, file, true, 5.0);
    reporter.start_items("turntable", 3, "frame");
    std::this_thread::sleep_for(std::chrono::milliseconds(350));  // past the 0.3 s delay
    reporter.set_done(1, 3);
    reporter.message("a note");  // ends the status line first
    std::this_thread::sleep_for(std::chrono::milliseconds(120));
    reporter.set_done(3, 3);
    reporter.finish();
  }
  std::fclose(file);
  const std::string text = read_all(log);
  INFO(text);
  // Each redraw returns the carriage and erases the old line (ESC[K) before writing.
  CHECK(text.find("\r\033[Kturntable: frame 1/3") != std::string::npos);
  CHECK(text.find("\na note\n") != std::string::npos);
  CHECK(text.find("\r\033[Kturntable: 3 frames done in") != std::string::npos);
  CHECK(text.back() == '\n');

  // A phase cut short (an exception unwinding past the reporter) leaves an erased line, not a
  // half-drawn one that the error message would be appended to.
  std::FILE* cut = std::fopen(log.string().c_str(), "w");
  REQUIRE(cut);
  {
    prt::cli::ProgressReporter reporter(false, cut, true, 5.0);
    reporter.start_fraction("projecting");
    std::this_thread::sleep_for(std::chrono::milliseconds(350));
    reporter.set_done(1, 4);
  }
  std::fclose(cut);
  const std::string cut_text = read_all(log);
  INFO(cut_text);
  CHECK(cut_text.find("projecting:  25%") != std::string::npos);
  CHECK(cut_text.size() >= 4);
  CHECK(cut_text.substr(cut_text.size() - 4) == "\r\033[K");
}
