#include "amos/viewer/request_head.h"

#include <arpa/inet.h>
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <vector>

namespace amos::viewer {
namespace {

constexpr std::string_view kCrlf = "\r\n";

std::string lowered(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) { return std::tolower(c); });
  return out;
}

bool isTokenChar(unsigned char c) {
  return std::isalnum(c) || std::string_view("!#$%&'*+-.^_`|~").find(static_cast<char>(c)) != std::string_view::npos;
}

bool isToken(std::string_view s) {
  return !s.empty() && std::all_of(s.begin(), s.end(), [](unsigned char c) { return isTokenChar(c); });
}

// Visible ASCII only: no space, control byte or byte above 0x7e in a request target.
bool isVisibleAscii(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](unsigned char c) { return c > 0x20 && c < 0x7f; });
}

// True when a %XX in `target` encodes a control byte (NUL, CR, LF...): never part of a file name served here.
bool encodesControlByte(std::string_view target) {
  for (std::size_t i = 0; i + 2 < target.size(); ++i) {
    if (target[i] != '%' || !std::isxdigit(static_cast<unsigned char>(target[i + 1])) ||
        !std::isxdigit(static_cast<unsigned char>(target[i + 2])))
      continue;
    const int value = std::stoi(std::string(target.substr(i + 1, 2)), nullptr, 16);
    if (value < 0x20 || value == 0x7f) return true;
  }
  return false;
}

// A header value may hold tabs and bytes above 0x7f, not other control bytes.
bool isFieldValue(std::string_view s) {
  return std::all_of(s.begin(), s.end(), [](unsigned char c) { return c == '\t' || (c >= 0x20 && c != 0x7f); });
}

std::string_view trimmed(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t')) s.remove_suffix(1);
  return s;
}

bool isDigits(std::string_view s, std::size_t max_digits) {
  return s.size() <= max_digits && std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isdigit(c); });
}

// "bytes=A-B", "bytes=A-" or "bytes=-N": one range, numbers of at most 18 digits. Anything else (a list, another
// unit, bad syntax) is not one range, and the Range header is then ignored.
bool isSingleByteRange(std::string_view value) {
  if (value.size() < 6 || lowered(value.substr(0, 6)) != "bytes=") return false;
  const std::string_view spec = trimmed(value.substr(6));
  const std::size_t dash = spec.find('-');
  if (dash == std::string_view::npos) return false;
  const std::string_view first = spec.substr(0, dash), last = spec.substr(dash + 1);
  return (!first.empty() || !last.empty()) && isDigits(first, 18) && isDigits(last, 18);
}

struct RequestHeader {
  std::string_view name, value;
};

ScreenedHead refused(int status, std::string reason, std::string extra_header = {}) {
  ScreenedHead out;
  out.refusal = Refusal{status, std::move(reason), std::move(extra_header)};
  return out;
}

std::vector<std::string_view> linesOf(std::string_view head) {
  std::vector<std::string_view> lines;
  while (!head.empty()) {
    const std::size_t end = head.find(kCrlf);
    if (end == std::string_view::npos) break;
    lines.push_back(head.substr(0, end));
    head.remove_prefix(end + kCrlf.size());
  }
  return lines;
}

// The request line's refusal, if any; `method` is set when it is well formed.
std::optional<Refusal> checkRequestLine(std::string_view line, const HeadLimits& limits, std::string_view& method) {
  if (line.size() > limits.max_request_line)
    return Refusal{414, fmt::format("request line longer than {} bytes", limits.max_request_line), {}};
  const std::size_t first = line.find(' '), second = line.find(' ', first + 1);
  if (first == std::string_view::npos || second == std::string_view::npos || line.find(' ', second + 1) != line.npos)
    return Refusal{400, "malformed request line", {}};
  method = line.substr(0, first);
  const std::string_view target = line.substr(first + 1, second - first - 1), version = line.substr(second + 1);
  if (!isToken(method) || (version != "HTTP/1.1" && version != "HTTP/1.0"))
    return Refusal{400, "malformed request line", {}};
  if (target.empty() || target.front() != '/' || !isVisibleAscii(target) || encodesControlByte(target))
    return Refusal{400, "malformed request target", {}};
  return std::nullopt;
}

}  // namespace

bool HostRule::allows(std::string_view host) const {
  std::string name = lowered(host), port_text;
  const std::size_t colon = name.rfind(':');
  if (colon != std::string::npos && name.find(']', colon) == std::string::npos) {
    port_text = name.substr(colon + 1);
    name.resize(colon);
  }
  if (port_text.empty() ? port != 80 : port_text != std::to_string(port)) return false;
  const std::string bound = bind.find(':') != std::string::npos ? "[" + lowered(bind) + "]" : lowered(bind);
  if (name == "localhost" || name == "127.0.0.1" || name == "[::1]" || name == bound) return true;
  if (bind != "0.0.0.0" && bind != "::" && !bind.empty()) return false;
  // Bound to every address: any IP address (a name that is no address is what DNS rebinding uses).
  unsigned char address[16];
  if (name.size() > 2 && name.front() == '[' && name.back() == ']')
    return inet_pton(AF_INET6, name.substr(1, name.size() - 2).c_str(), address) == 1;
  return inet_pton(AF_INET, name.c_str(), address) == 1;
}

std::string refusalReply(const Refusal& refusal) {
  const std::string body = "refused: " + refusal.reason + "\n";
  const char* text = refusal.status == 400   ? "Bad Request"
                     : refusal.status == 405 ? "Method Not Allowed"
                     : refusal.status == 408 ? "Request Timeout"
                     : refusal.status == 413 ? "Content Too Large"
                     : refusal.status == 414 ? "URI Too Long"
                     : refusal.status == 421 ? "Misdirected Request"
                     : refusal.status == 431 ? "Request Header Fields Too Large"
                     : refusal.status == 503 ? "Service Unavailable"
                                             : "Refused";
  std::string reply = fmt::format("HTTP/1.1 {} {}\r\nContent-Type: text/plain\r\nContent-Length: {}\r\n"
                                  "Connection: close\r\n",
                                  refusal.status, text, body.size());
  if (!refusal.extra_header.empty()) reply += refusal.extra_header + "\r\n";
  return reply + "\r\n" + body;
}

std::size_t headLength(std::string_view buffer) {
  const std::size_t end = buffer.find("\r\n\r\n");
  return end == std::string_view::npos ? 0 : end + 4;
}

std::optional<Refusal> refuseIncompleteHead(std::string_view partial, const HeadLimits& limits) {
  const std::size_t line_end = partial.find(kCrlf);
  if ((line_end == std::string_view::npos ? partial.size() : line_end) > limits.max_request_line)
    return Refusal{414, fmt::format("request line longer than {} bytes", limits.max_request_line), {}};
  if (partial.size() > limits.max_head)
    return Refusal{431, fmt::format("request head longer than {} bytes", limits.max_head), {}};
  return std::nullopt;
}

ScreenedHead screenHead(std::string_view head, const HostRule& hosts, const HeadLimits& limits) {
  if (head.size() > limits.max_head) return refused(431, fmt::format("request head longer than {} bytes", limits.max_head));
  const std::vector<std::string_view> lines = linesOf(head);
  if (lines.size() < 2 || !lines.back().empty()) return refused(400, "malformed request head");
  std::string_view method;
  if (auto refusal = checkRequestLine(lines.front(), limits, method)) return ScreenedHead{std::move(refusal), {}, {}};
  if (lines.size() - 2 > limits.max_headers) return refused(431, fmt::format("more than {} headers", limits.max_headers));
  std::vector<RequestHeader> headers;
  for (std::size_t i = 1; i + 1 < lines.size(); ++i) {
    const std::string_view line = lines[i];
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos || !isToken(line.substr(0, colon)) || !isFieldValue(line.substr(colon + 1)))
      return refused(400, "malformed header line");
    headers.push_back({line.substr(0, colon), trimmed(line.substr(colon + 1))});
  }
  auto named = [&](std::string_view name) {
    std::vector<std::string_view> values;
    for (const RequestHeader& h : headers)
      if (lowered(h.name) == name) values.push_back(h.value);
    return values;
  };
  const auto host = named("host");
  if (host.size() != 1) return refused(400, "a request needs one Host header");
  if (!hosts.allows(host.front()))
    return refused(421, fmt::format("Host '{}' is not this viewer's address (open http://127.0.0.1:{}/)",
                                    std::string(host.front()).substr(0, 200), hosts.port));
  if (method != "GET" && method != "HEAD") return refused(405, "the viewer is read-only (GET, HEAD)", "Allow: GET, HEAD");
  const auto length = named("content-length");
  if (!named("transfer-encoding").empty() || length.size() > 1 || (length.size() == 1 && length.front() != "0"))
    return refused(413, "a request body is never read here");
  ScreenedHead out;
  out.forwarded = std::string(lines.front()) + "\r\n";
  for (const RequestHeader& h : headers) {
    const std::string name = lowered(h.name);
    if (name == "range") {
      if (isSingleByteRange(h.value) && named("range").size() == 1) out.range = std::string(h.value);
    } else if (name != "expect") {
      out.forwarded += fmt::format("{}: {}\r\n", h.name, h.value);
    }
  }
  out.forwarded += "\r\n";
  return out;
}

}  // namespace amos::viewer
