#pragma once
// Base64 (RFC 4648, with padding) for the images report.html carries inside itself as data: URLs.
#include <string>
#include <vector>

namespace amos::viewer {

std::string base64Encode(const std::vector<unsigned char>& bytes);

}  // namespace amos::viewer
