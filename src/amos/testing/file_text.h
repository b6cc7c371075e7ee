#pragma once
// A file's bytes as a string, for tests that compare output files ("" when it cannot be read: the comparison then
// fails naming what differs).
#include <filesystem>
#include <string>

#include "amos/core/whole_file.h"

namespace amos::testing {

inline std::string fileText(const std::filesystem::path& path) {
  return core::readWholeFile(path).value_or(std::string());
}

}  // namespace amos::testing
