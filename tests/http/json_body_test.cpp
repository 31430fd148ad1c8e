// JSON bodies (http/json_body.h): nesting bounded while parsing, errors that name
// what is wrong without echoing the body, and answers that survive any string.
#include <gtest/gtest.h>

#include "http/json_body.h"

namespace rockbake::http {
namespace {

using nlohmann::json;

Request post(std::string body) {
  Request r;
  r.method = "POST";
  r.body = std::move(body);
  return r;
}

int refusedWith(const std::function<void()>& call, std::string* message = nullptr) {
  try {
    call();
  } catch (const HttpError& e) {
    if (message) *message = e.what();
    return e.status();
  }
  return 0;
}

TEST(JsonBody, NestingIsBoundedWhileParsing) {
  const auto nested = [](int depth) {
    return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']');
  };
  EXPECT_EQ(parseJsonBody(post(nested(kMaxJsonDepth))).dump(), nested(kMaxJsonDepth));
  std::string message;
  EXPECT_EQ(refusedWith([&] { parseJsonBody(post(nested(kMaxJsonDepth + 1))); }, &message), 400);
  EXPECT_EQ(message, "the request body nests deeper than 64 levels");
  // The studio's crash: 100 000 levels in a 200 KB body, objects and lists mixed.
  std::string deep;
  for (int i = 0; i < 100000; ++i) deep += i % 2 ? "[" : "{\"a\":";
  EXPECT_EQ(refusedWith([&] { parseJsonBody(post(deep)); }, &message), 400);
  EXPECT_EQ(message.find("{\"a\""), std::string::npos) << "the body is not echoed";
}

TEST(JsonBody, MalformedJsonIsRefusedWithItsPlaceNotItsText) {
  std::string message;
  EXPECT_EQ(refusedWith([&] { parseJsonBody(post("{\"secret\": tru")); }, &message), 400);
  EXPECT_NE(message.find("not valid JSON (at byte"), std::string::npos) << message;
  EXPECT_EQ(message.find("secret"), std::string::npos) << message;
  EXPECT_EQ(message.find("json.exception"), std::string::npos) << message;
  EXPECT_EQ(refusedWith([&] { parseJsonBody(post("\"\xff\"")); }), 400) << "invalid UTF-8";
}

TEST(JsonBody, MembersAreCheckedForTheirTypes) {
  const json body = {{"name", "rock"}, {"overwrite", "yes"}, {"t", nullptr}};
  EXPECT_EQ(stringMember(body, "name", "{name}"), "rock");
  std::string message;
  EXPECT_EQ(refusedWith([&] { boolMember(body, "overwrite", false); }, &message), 400);
  EXPECT_EQ(message, "overwrite: expected true or false");
  EXPECT_FALSE(boolMember(body, "missing", false));
  EXPECT_EQ(refusedWith([&] { stringMember(body, "missing", "{\"missing\": \"...\"}"); }, &message), 400);
  EXPECT_EQ(message, "missing: missing; expected {\"missing\": \"...\"}");
  EXPECT_EQ(refusedWith([&] { stringMember(json::array(), "name", "{name}"); }), 400);
  EXPECT_EQ(refusedWith([&] { numberValue(body["t"], "t", "a time"); }, &message), 400);
  EXPECT_EQ(message, "t: expected a time");
}

TEST(JsonBody, AnswersCarryAnyStringSafely) {
  const Response r = errorResponse(400, std::string("name: '\xff\x01z' is not a name"));
  EXPECT_EQ(r.status, 400);
  EXPECT_EQ(r.content_type, "application/json");
  const json j = json::parse(r.body);
  EXPECT_EQ(j["error"], "name: '\xEF\xBF\xBD\\x01z' is not a name");
}

}  // namespace
}  // namespace rockbake::http
