// A shipped case file's text with some of its lines replaced: the tests that run a smaller, shorter
// or otherwise changed copy of a case from the repository (data/cases, data/packings, tests/...).
#pragma once
#include <catch2/catch.hpp>
#include <fstream>
#include <initializer_list>
#include <sstream>
#include <string>
#include <utility>

namespace test_support {

// The text of `repo_path` (relative to the source tree) with the first occurrence of each `from`
// replaced by its `to`, in order; the file must open and every `from` must be found.
inline std::string case_text(const std::string& repo_path,
                             std::initializer_list<std::pair<std::string, std::string>> replacements) {
  std::ifstream in(std::string(GRANWAVE_SOURCE_DIR) + "/" + repo_path);
  REQUIRE(in);
  std::stringstream text;
  text << in.rdbuf();
  std::string s = text.str();
  for (const auto& [from, to] : replacements) {
    const auto at = s.find(from);
    INFO(repo_path << ": " << from);
    REQUIRE(at != std::string::npos);
    s.replace(at, from.size(), to);
  }
  return s;
}

}  // namespace test_support
