// Who may call a local server (http/caller_rules.h): its own address and localhost,
// never another web page.
#include <gtest/gtest.h>

#include "http/caller_rules.h"

namespace rockbake::http {
namespace {

int statusOf(const std::optional<HttpError>& refusal) {
  return refusal ? refusal->status() : 0;
}

TEST(CallerRules, TheServersOwnAddressAndLocalhostWithItsPort) {
  const CallerRules rules("127.0.0.1", 8631);
  const std::string json = "application/json";
  EXPECT_EQ(statusOf(rules.refusal("GET", "127.0.0.1:8631", std::nullopt, std::nullopt)), 0);
  EXPECT_EQ(statusOf(rules.refusal("GET", "LOCALHOST:8631", std::nullopt, std::nullopt)), 0);
  EXPECT_EQ(statusOf(rules.refusal("POST", "localhost:8631", "http://localhost:8631", json)), 0);
  EXPECT_EQ(
      statusOf(rules.refusal("POST", "127.0.0.1:8631", "http://127.0.0.1:8631", "Application/JSON; charset=utf-8")), 0);
  // DNS rebinding: a foreign name for this address, or the wrong port.
  EXPECT_EQ(statusOf(rules.refusal("GET", "evil.example:8631", std::nullopt, std::nullopt)), 403);
  EXPECT_EQ(statusOf(rules.refusal("GET", "127.0.0.1:8632", std::nullopt, std::nullopt)), 403);
  EXPECT_EQ(statusOf(rules.refusal("GET", "127.0.0.1", std::nullopt, std::nullopt)), 403);
  EXPECT_EQ(statusOf(rules.refusal("GET", std::nullopt, std::nullopt, std::nullopt)), 403);
  // Another page, or none.
  for (const char* origin : {"http://evil.example", "null", "https://127.0.0.1:8631", "http://127.0.0.1:8631.evil"})
    EXPECT_EQ(statusOf(rules.refusal("GET", "127.0.0.1:8631", std::string(origin), std::nullopt)), 403) << origin;
  // A form or a text/plain fetch.
  for (const char* type : {"text/plain", "application/x-www-form-urlencoded", "multipart/form-data; boundary=x", ""})
    EXPECT_EQ(statusOf(rules.refusal("POST", "127.0.0.1:8631", std::nullopt, std::string(type))), 415) << type;
  EXPECT_EQ(statusOf(rules.refusal("POST", "127.0.0.1:8631", std::nullopt, std::nullopt)), 415);
  const auto refusal = rules.refusal("GET", "evil.example:8631", std::nullopt, std::nullopt);
  EXPECT_NE(std::string(refusal->what()).find("http://127.0.0.1:8631/"), std::string::npos) << refusal->what();
}

TEST(CallerRules, AWildcardAddressTakesThisMachinesAddresses) {
  const CallerRules rules("0.0.0.0", 9000);
  EXPECT_EQ(statusOf(rules.refusal("GET", "127.0.0.1:9000", std::nullopt, std::nullopt)), 0);
  EXPECT_EQ(statusOf(rules.refusal("GET", "localhost:9000", "http://127.0.0.1:9000", std::nullopt)), 0);
  EXPECT_EQ(statusOf(rules.refusal("GET", "evil.example:9000", std::nullopt, std::nullopt)), 403);
  const CallerRules ipv6("::1", 9000);
  EXPECT_EQ(statusOf(ipv6.refusal("GET", "[::1]:9000", "http://[::1]:9000", std::nullopt)), 0);
}

}  // namespace
}  // namespace rockbake::http
