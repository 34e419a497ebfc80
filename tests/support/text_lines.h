// tests/support/text_lines.h — a program's text output taken line by line, for tests that count
// what it printed (progress lines, warnings).
#pragma once

#include <cstddef>
#include <sstream>
#include <string>
#include <vector>

namespace prt::test {

// The lines of `text`, without their '\n' (a last line without one counts).
inline std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

// How many lines of `text` contain `needle`.
inline std::size_t count_containing(const std::string& text, const std::string& needle) {
  std::size_t n = 0;
  for (const std::string& line : lines_of(text)) n += line.find(needle) != std::string::npos;
  return n;
}

}  // namespace prt::test
