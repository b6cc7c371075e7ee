#include "amos/core/whole_file.h"

#include <fstream>
#include <sstream>
#include <utility>

#include "amos/core/error.h"

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

std::string readWholeFileOrThrow(const std::filesystem::path& path, const std::string& message) {
  std::optional<std::string> text = readWholeFile(path);
  require(text.has_value(), message);
  return std::move(*text);
}

}  // namespace amos::core
