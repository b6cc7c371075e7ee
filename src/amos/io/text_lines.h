#pragma once
// Reading whitespace-separated text lists (TUM-style): comments, blank lines, a UTF-8 byte-order mark and
// Windows line endings are tolerated; every parse error names the file and the 1-based line.
#include <functional>
#include <istream>
#include <string>
#include <vector>

namespace amos::io {

struct TextLine {
  int number = 0;                   // 1-based line number in the file
  std::vector<std::string> fields;  // split on spaces, tabs and commas
};

// Non-empty, non-comment lines of `path`. Throws core::Error when the file cannot be opened.
std::vector<TextLine> readTextLines(const std::string& path);
// Same, from a stream (the lists' text in tests and fuzz targets).
std::vector<TextLine> readTextLines(std::istream& in);

// Parses a field as a finite double; throws core::Error "path:line: <what> is not a number: '<text>'".
double parseNumber(const std::string& text, const std::string& path, int line, const std::string& what);

}  // namespace amos::io
