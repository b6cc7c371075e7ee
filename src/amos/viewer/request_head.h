#pragma once
// The first look at an HTTP request, before cpp-httplib sees a byte of it (guarded_server.h). Debian's cpp-httplib
// (0.11, a compiled library: its CPPHTTPLIB_* limits cannot be changed from here) grows a request line or header
// line without bound until its newline, takes any number of headers, reads any body, and answers a Range header of
// hundreds of ranges with hundreds of copies of the file. So the head (request line and headers, through the blank
// line) is read and checked here first, within the limits below, and httplib only gets a head that passed: without
// its Range (one range is passed on to the handlers as a plain header; more are ignored, which HTTP allows: the
// whole file) and without Expect.
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace amos::viewer {

struct HeadLimits {
  std::size_t max_request_line = 4096;  // bytes of "GET /path HTTP/1.1" (more: 414)
  std::size_t max_head = 32768;         // bytes of the request line and the headers (more: 431)
  std::size_t max_headers = 100;        // header lines (more: 431)
};

// Which Host a request may name: the server's port with `localhost`, 127.0.0.1, [::1] or the address it is bound
// to (any IP address when it is bound to all of them). Any other name is how a web page the user visits reads a
// local server through DNS rebinding (its own name made to resolve to 127.0.0.1).
struct HostRule {
  std::string bind;  // the address listened on
  int port = 0;
  bool allows(std::string_view host) const;
};

// A request refused before it reaches a handler: the status, a one-line reason for the body, an extra header line
// ("Allow: GET, HEAD") or none.
struct Refusal {
  int status = 400;
  std::string reason;
  std::string extra_header;
};

// The whole HTTP/1.1 reply for a refusal; it closes the connection.
std::string refusalReply(const Refusal& refusal);

// Length of the head at the start of `buffer` (through its blank line), 0 while it is incomplete.
std::size_t headLength(std::string_view buffer);

// The refusal of a head still incomplete that is already longer than allowed (414 / 431), none otherwise.
std::optional<Refusal> refuseIncompleteHead(std::string_view partial, const HeadLimits& limits);

struct ScreenedHead {
  std::optional<Refusal> refusal;  // set: answer this and close
  std::string forwarded;           // the head httplib parses (without Range and Expect)
  std::string range;               // the Range value when it names exactly one byte range, else empty
};

// Checks a complete head (headLength() bytes): syntax (CRLF lines, no control bytes, a target starting with '/',
// no encoded control byte in it), the limits, Host, the method (GET or HEAD: 405 otherwise; the server is
// read-only) and no body (Content-Length other than 0 or Transfer-Encoding: 413, never read).
ScreenedHead screenHead(std::string_view head, const HostRule& hosts, const HeadLimits& limits);

}  // namespace amos::viewer
