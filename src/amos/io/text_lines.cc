#include "amos/io/text_lines.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>

#include "amos/core/error.h"

namespace amos::io {

std::vector<TextLine> readTextLines(const std::string& path) {
  std::ifstream in(path);
  core::require(in.good(), fmt::format("cannot open '{}'", path));
  return readTextLines(in);
}

std::vector<TextLine> readTextLines(std::istream& in) {
  std::vector<TextLine> lines;
  std::string raw;
  int number = 0;
  while (std::getline(in, raw)) {
    ++number;
    if (number == 1 && raw.rfind("\xEF\xBB\xBF", 0) == 0) raw.erase(0, 3);  // UTF-8 BOM
    TextLine line;
    line.number = number;
    std::string field;
    for (char c : raw) {
      if (c == ' ' || c == '\t' || c == ',' || c == '\r') {
        if (!field.empty()) line.fields.push_back(std::move(field)), field.clear();
      } else {
        field.push_back(c);
      }
    }
    if (!field.empty()) line.fields.push_back(std::move(field));
    if (line.fields.empty() || line.fields.front()[0] == '#') continue;
    lines.push_back(std::move(line));
  }
  return lines;
}

double parseNumber(const std::string& text, const std::string& path, int line, const std::string& what) {
  errno = 0;
  char* end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE || !std::isfinite(value)) {
    throw core::Error(fmt::format("{}:{}: {} is not a number: '{}'", path, line, what, text));
  }
  return value;
}

}  // namespace amos::io
