#include "amos/viewer/file_reply.h"

#include <fmt/format.h>
#include <httplib.h>

#include <algorithm>
#include <cctype>
#include <fstream>
#include <memory>
#include <vector>

#include "amos/viewer/web_assets.h"

namespace amos::viewer {
namespace {

constexpr std::size_t kPieceBytes = 64 * 1024;

std::uint64_t numberOf(const std::string& digits) { return digits.empty() ? 0 : std::stoull(digits); }

}  // namespace

ByteSpan byteSpanOf(const std::string& range, std::uint64_t size) {
  const std::size_t dash = range.find('-');
  std::string unit = range.substr(0, 6);
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
  if (unit != "bytes=" || dash == std::string::npos) return {};
  std::string first = range.substr(6, dash - 6), last = range.substr(dash + 1);
  first.erase(0, first.find_first_not_of(" \t"));
  last.erase(last.find_last_not_of(" \t") + 1);
  const auto digits = [](const std::string& s) {
    return s.size() <= 18 && std::all_of(s.begin(), s.end(), [](unsigned char c) { return c >= '0' && c <= '9'; });
  };
  if ((first.empty() && last.empty()) || !digits(first) || !digits(last)) return {};
  if (first.empty()) {  // the last N bytes
    const std::uint64_t n = std::min(numberOf(last), size);
    if (n == 0) return {ByteSpan::Kind::Unsatisfiable, 0, 0};
    return {ByteSpan::Kind::Part, size - n, n};
  }
  const std::uint64_t begin = numberOf(first);
  if (!last.empty() && numberOf(last) < begin) return {};
  if (begin >= size) return {ByteSpan::Kind::Unsatisfiable, 0, 0};
  const std::uint64_t end = last.empty() ? size - 1 : std::min(numberOf(last), size - 1);
  return {ByteSpan::Kind::Part, begin, end - begin + 1};
}

void replyWithFile(const std::filesystem::path& file, const std::string& range, httplib::Response& res) {
  auto in = std::make_shared<std::ifstream>(file, std::ios::binary);
  std::error_code error;
  const std::uint64_t size = std::filesystem::file_size(file, error);
  if (!*in || error) {
    res.status = 404;
    return;
  }
  res.set_header("Accept-Ranges", "bytes");
  if (size == 0 && range.empty()) return res.set_content("", std::string(mimeTypeOf(file.filename().string())));
  const ByteSpan span = byteSpanOf(range, size);
  if (span.kind == ByteSpan::Kind::Unsatisfiable) {
    res.status = 416;
    res.set_header("Content-Range", fmt::format("bytes */{}", size));
    return;
  }
  const std::uint64_t offset = span.kind == ByteSpan::Kind::Part ? span.offset : 0;
  const std::uint64_t length = span.kind == ByteSpan::Kind::Part ? span.length : size;
  if (span.kind == ByteSpan::Kind::Part) {
    res.status = 206;
    res.set_header("Content-Range", fmt::format("bytes {}-{}/{}", offset, offset + length - 1, size));
  }
  // A file that shrinks while it is sent ends the reply (its connection closes) rather than sending zeros.
  res.set_content_provider(
      length, std::string(mimeTypeOf(file.filename().string())),
      [in, offset](std::size_t at, std::size_t wanted, httplib::DataSink& sink) {
        std::vector<char> piece(std::min(wanted, kPieceBytes));
        in->seekg(static_cast<std::streamoff>(offset + at));
        in->read(piece.data(), static_cast<std::streamsize>(piece.size()));
        const auto got = static_cast<std::size_t>(in->gcount());
        return got > 0 && sink.write(piece.data(), got);
      });
}

}  // namespace amos::viewer
