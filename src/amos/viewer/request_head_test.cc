#include "amos/viewer/request_head.h"

#include <gtest/gtest.h>

namespace amos::viewer {
namespace {

const HostRule kLoopback{"127.0.0.1", 8090};

ScreenedHead screen(const std::string& head, const HostRule& hosts = kLoopback) {
  return screenHead(head, hosts, HeadLimits{});
}

int statusOf(const ScreenedHead& s) { return s.refusal ? s.refusal->status : 0; }

TEST(RequestHead, FindsTheEndOfTheHead) {
  EXPECT_EQ(headLength("GET / HTTP/1.1\r\nHost: a\r\n"), 0u);
  EXPECT_EQ(headLength("GET / HTTP/1.1\r\nHost: a\r\n\r\nGET"), 27u);
}

TEST(RequestHead, HostMustBeThisServer) {
  EXPECT_TRUE(kLoopback.allows("127.0.0.1:8090"));
  EXPECT_TRUE(kLoopback.allows("localhost:8090"));
  EXPECT_TRUE(kLoopback.allows("[::1]:8090"));
  EXPECT_FALSE(kLoopback.allows("127.0.0.1:8091"));
  EXPECT_FALSE(kLoopback.allows("127.0.0.1"));
  EXPECT_FALSE(kLoopback.allows("evil.example:8090"));
  EXPECT_FALSE(kLoopback.allows("192.168.1.5:8090"));
  const HostRule everywhere{"0.0.0.0", 8090};
  EXPECT_TRUE(everywhere.allows("192.168.1.5:8090"));
  EXPECT_TRUE(everywhere.allows("[fe80::1]:8090"));
  EXPECT_FALSE(everywhere.allows("evil.example:8090"));
  EXPECT_FALSE(everywhere.allows("1.2.3.4.evil.example:8090"));
  EXPECT_TRUE((HostRule{"192.168.1.5", 80}.allows("192.168.1.5")));
}

TEST(RequestHead, PassesAGetWithoutRangeAndExpect) {
  const ScreenedHead s =
      screen("GET /files/a.png HTTP/1.1\r\nHost: 127.0.0.1:8090\r\nRange: bytes=0-9\r\nExpect: 100-continue\r\n\r\n");
  EXPECT_EQ(statusOf(s), 0);
  EXPECT_EQ(s.forwarded, "GET /files/a.png HTTP/1.1\r\nHost: 127.0.0.1:8090\r\n\r\n");
  EXPECT_EQ(s.range, "bytes=0-9");
}

TEST(RequestHead, AListOfRangesIsDropped) {
  const ScreenedHead s = screen("GET / HTTP/1.1\r\nHost: 127.0.0.1:8090\r\nRange: bytes=0-,0-,0-\r\n\r\n");
  EXPECT_EQ(statusOf(s), 0);
  EXPECT_TRUE(s.range.empty());
  EXPECT_EQ(s.forwarded.find("Range"), std::string::npos);
}

TEST(RequestHead, RefusesWhatIsNotASmallGet) {
  const std::string host = "Host: 127.0.0.1:8090\r\n";
  EXPECT_EQ(statusOf(screen("POST / HTTP/1.1\r\n" + host + "\r\n")), 405);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + "Content-Length: 5\r\n\r\n")), 413);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + "Transfer-Encoding: chunked\r\n\r\n")), 413);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + "Content-Length: 0\r\n\r\n")), 0);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\nHost: evil.example:8090\r\n\r\n")), 421);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + host + "\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET /a%00b HTTP/1.1\r\n" + host + "\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET http://evil/ HTTP/1.1\r\n" + host + "\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET / HTTP/2.0\r\n" + host + "\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + " folded\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + "Bad\nHeader: x\r\n\r\n")), 400);
  EXPECT_EQ(statusOf(screen("GET /" + std::string(5000, 'a') + " HTTP/1.1\r\n" + host + "\r\n")), 414);
  std::string many;
  for (int i = 0; i < 101; ++i) many += "X: y\r\n";
  EXPECT_EQ(statusOf(screen("GET / HTTP/1.1\r\n" + host + many + "\r\n")), 431);
}

TEST(RequestHead, AnIncompleteHeadIsRefusedOnceTooLong) {
  const HeadLimits limits;
  EXPECT_FALSE(refuseIncompleteHead("GET / HTTP/1.1\r\nHost", limits));
  EXPECT_EQ(refuseIncompleteHead("GET /" + std::string(5000, 'a'), limits)->status, 414);
  EXPECT_EQ(refuseIncompleteHead("GET / HTTP/1.1\r\nX: " + std::string(40000, 'a'), limits)->status, 431);
}

TEST(RequestHead, ARefusalIsAWholeReplyThatCloses) {
  const std::string reply = refusalReply({405, "read-only", "Allow: GET, HEAD"});
  EXPECT_EQ(reply.rfind("HTTP/1.1 405 Method Not Allowed\r\n", 0), 0u);
  EXPECT_NE(reply.find("Connection: close\r\n"), std::string::npos);
  EXPECT_NE(reply.find("Allow: GET, HEAD\r\n"), std::string::npos);
  EXPECT_NE(reply.find("\r\n\r\nrefused: read-only\n"), std::string::npos);
}

}  // namespace
}  // namespace amos::viewer
