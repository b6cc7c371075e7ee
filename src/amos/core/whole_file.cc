#include "amos/core/whole_file.h"

#include <fstream>
#include <sstream>

namespace amos::core {

std::optional<std::string> readWholeFile(const std::filesystem::path& path) {
  std::error_code error;
  if (std::filesystem::is_directory(path, error)) return std::nullopt;  // which an ifstream would open, empty
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace amos::core
