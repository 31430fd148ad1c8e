// Where a request ends and when it is refused before it is buffered (http/request_framing.h).
#include <gtest/gtest.h>

#include <string>

#include "http/request_framing.h"

namespace rockbake::http {
namespace {

const FramingLimits kLimits{1024, 8, 100};

TEST(RequestFraming, AGetEndsAtTheEmptyLine) {
  const std::string request = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
  for (std::size_t n = 0; n < request.size(); ++n)
    EXPECT_EQ(frameRequest(request.substr(0, n), kLimits).state, Framing::State::NeedMore) << n;
  const Framing f = frameRequest(request, kLimits);
  EXPECT_EQ(f.state, Framing::State::Complete);
  EXPECT_EQ(f.requestBytes(), request.size());
}

// A bare LF (or CR) in the head is refused: cpp-httplib would end a line there and read a header
// (a Range, a Content-Length) the framing never saw.
TEST(RequestFraming, LineBreaksOtherThanCrLfAreRefused) {
  for (const std::string head :
       {"GET / HTTP/1.1\r\nX: a\nRange: bytes=0-,0-\r\nHost: x\r\n\r\n",
        "GET / HTTP/1.1\r\nX: a\rRange: bytes=0-\r\n\r\n", "GET / HTTP/1.1\nHost: x\r\n\r\n"}) {
    const Framing f = frameRequest(head, kLimits);
    EXPECT_EQ(f.state, Framing::State::Refused) << head;
    EXPECT_EQ(f.status, 400) << head;
  }
}

TEST(RequestFraming, APostEndsAfterItsContentLength) {
  const std::string head = "POST /api/edit HTTP/1.1\r\ncontent-LENGTH:  5 \r\nExpect: 100-continue\r\n\r\n";
  Framing f = frameRequest(head + "{\"a\"", kLimits);
  EXPECT_EQ(f.state, Framing::State::NeedMore);
  EXPECT_EQ(f.content_length, 5u);
  EXPECT_TRUE(f.expect_continue);
  f = frameRequest(head + "{\"a\":", kLimits);
  EXPECT_EQ(f.state, Framing::State::Complete);
  EXPECT_EQ(f.requestBytes(), head.size() + 5);
}

TEST(RequestFraming, HeadersOverTheirSizeOrCountAreRefused) {
  const std::string endless = "GET / HTTP/1.1\r\nX: " + std::string(2000, 'a');
  Framing f = frameRequest(endless, kLimits);
  EXPECT_EQ(f.state, Framing::State::Refused);
  EXPECT_EQ(f.status, 431);
  EXPECT_NE(f.message.find("over 1 KiB"), std::string::npos) << f.message;
  std::string many = "GET / HTTP/1.1\r\n";
  for (int i = 0; i < 8; ++i) many += "X-" + std::to_string(i) + ": 1\r\n";
  EXPECT_EQ(frameRequest(many + "\r\n", kLimits).state, Framing::State::Complete) << "eight headers are allowed";
  f = frameRequest(many + "X-9: 1\r\n", kLimits);  // refused before the headers end
  EXPECT_EQ(f.status, 431);
  EXPECT_NE(f.message.find("more than 8 headers"), std::string::npos) << f.message;
}

TEST(RequestFraming, BodiesOverTheLimitAndUnframedBodiesAreRefused) {
  Framing f = frameRequest("POST / HTTP/1.1\r\nContent-Length: 101\r\n\r\n", kLimits);
  EXPECT_EQ(f.status, 413);
  EXPECT_NE(f.message.find("101 bytes"), std::string::npos) << f.message;
  EXPECT_EQ(frameRequest("POST / HTTP/1.1\r\nTransfer-Encoding: gzip\r\n\r\n", kLimits).status, 501);
  EXPECT_EQ(frameRequest("POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\nContent-Length: 3\r\n\r\n", kLimits).status,
            400);
  EXPECT_EQ(frameRequest("POST / HTTP/1.1\r\nContent-Length: -1\r\n\r\n", kLimits).status, 400);
  EXPECT_EQ(frameRequest("POST / HTTP/1.1\r\nContent-Length: 1\r\nContent-Length: 2\r\n\r\n", kLimits).status, 400);
  EXPECT_EQ(frameRequest("POST / HTTP/1.1\r\nContent-Length: 99999999999999999999\r\n\r\n", kLimits).status, 400);
}

// Node's http client sends a body of no stated length in chunks.
TEST(RequestFraming, AChunkedBodyEndsAfterItsLastChunkAndTrailers) {
  const std::string head = "POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n";
  const std::string body = "4\r\n{\"a\"\r\n9;ext=1\r\n:[1,2,3]}\r\n0\r\nX-Trailer: 1\r\n\r\n";
  for (std::size_t n = 0; n < body.size(); ++n)
    EXPECT_EQ(frameRequest(head + body.substr(0, n), kLimits).state, Framing::State::NeedMore) << n;
  const Framing f = frameRequest(head + body, kLimits);
  EXPECT_EQ(f.state, Framing::State::Complete);
  EXPECT_TRUE(f.chunked);
  EXPECT_EQ(f.requestBytes(), head.size() + body.size());
  EXPECT_EQ(frameRequest(head + "65\r\n", kLimits).status, 413) << "101 bytes in one chunk";
  EXPECT_EQ(frameRequest(head + "zz\r\n", kLimits).status, 400);
  EXPECT_EQ(frameRequest(head + "1\r\nab\r\n", kLimits).status, 400) << "a chunk longer than it said";
  std::string padded;  // 300 bytes of body in 12 000 of chunks
  for (int i = 0; i < 300; ++i) padded += "1;" + std::string(32, 'e') + "\r\nx\r\n";
  const Framing f2 = frameRequest(head + padded, FramingLimits{1024, 8, 1000});
  EXPECT_EQ(f2.status, 413) << "framing past its share";
  EXPECT_NE(f2.message.find("chunks are too small"), std::string::npos) << f2.message;
}

}  // namespace
}  // namespace rockbake::http
