// docs/ENGINE.md quotes examples/engine_example.cpp verbatim; this keeps them identical.
#include <fstream>
#include <sstream>
#include <string>

#include <catch2/catch.hpp>

#include "support/test_data.h"

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  REQUIRE(in.good());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("docs/ENGINE.md quotes engine_example.cpp exactly", "[docs]") {
  const std::string root = PRT_SOURCE_DIR;
  const std::string doc = read_text(root + "/docs/ENGINE.md");
  const std::string source = read_text(root + "/examples/engine_example.cpp");
  const std::string begin = "<!-- BEGIN examples/engine_example.cpp -->\n```cpp\n";
  const std::string end = "```\n<!-- END examples/engine_example.cpp -->";
  const std::size_t b = doc.find(begin);
  REQUIRE(b != std::string::npos);
  const std::size_t e = doc.find(end, b);
  REQUIRE(e != std::string::npos);
  const std::string quoted = doc.substr(b + begin.size(), e - b - begin.size());
  REQUIRE(quoted == source);
}
