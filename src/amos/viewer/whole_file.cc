#include "amos/viewer/whole_file.h"

#include <fstream>
#include <sstream>

namespace amos::viewer {

std::string readWholeFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {};
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace amos::viewer
