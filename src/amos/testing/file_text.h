#pragma once
// A file's bytes as a string, for tests that compare output files ("" when it cannot be read: the comparison then
// fails naming what differs).
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace amos::testing {

inline std::string fileText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace amos::testing
