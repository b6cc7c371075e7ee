#pragma once
// A file of a finished run as the reply to GET /files/PATH: streamed from disk in pieces (a file of any size costs a
// reply the same memory), whole or the one byte range the request's Range header names (request_head.h passes a
// single range on and drops a list of them, so no reply is ever larger than the file).
#include <cstdint>
#include <filesystem>
#include <string>

namespace httplib {
struct Response;
}

namespace amos::viewer {

struct ByteSpan {
  enum class Kind { Whole, Part, Unsatisfiable } kind = Kind::Whole;
  std::uint64_t offset = 0, length = 0;
};

// What `range` ("bytes=A-B", "bytes=A-", "bytes=-N"; empty: none) names in a file of `size` bytes: the whole file
// when there is no range or it is invalid (B < A: HTTP says to ignore it), Unsatisfiable when it starts at or beyond
// the end (or asks for the last 0 bytes), else the part, its end clipped to the file's.
ByteSpan byteSpanOf(const std::string& range, std::uint64_t size);

// Sets `res` to `file` (200), its part (206 with Content-Range) or 416 (Content-Range: bytes */SIZE), with
// Accept-Ranges: bytes. A file that cannot be opened is 404.
void replyWithFile(const std::filesystem::path& file, const std::string& range, httplib::Response& res);

}  // namespace amos::viewer
