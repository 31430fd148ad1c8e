// The HTTP layer over real sockets (http/local_server.h): routes and their
// answers, who may call, and the limits that keep slow, large or many clients
// from taking the workers. Each test runs a LocalServer on a free loopback port.
#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "http/json_body.h"
#include "http/local_server.h"
#include "socket_client.h"

namespace rockbake::http {
namespace {

using test::bodyOf;
using test::SocketClient;
using test::statusOf;

class Served {
 public:
  explicit Served(std::vector<Route> routes, Limits limits = {}) : server_(std::move(routes), limits) {
    port_ = server_.listen("127.0.0.1", 0);
    thread_ = std::thread([this] { server_.serve(); });
  }
  ~Served() {
    server_.stop();
    thread_.join();
  }
  int port() const { return port_; }
  std::string host() const { return "Host: 127.0.0.1:" + std::to_string(port_) + "\r\n"; }
  // One whole request, its whole answer.
  std::string ask(const std::string& request) {
    SocketClient client(port_);
    client.send(request);
    return client.readAll();
  }
  std::string get(const std::string& path, const std::string& headers = "") {
    return ask("GET " + path + " HTTP/1.1\r\n" + host() + headers + "\r\n");
  }
  std::string post(const std::string& path, const std::string& body,
                   const std::string& headers = "Content-Type: application/json\r\n") {
    return ask("POST " + path + " HTTP/1.1\r\n" + host() + headers + "Content-Length: " + std::to_string(body.size()) +
               "\r\n\r\n" + body);
  }

 private:
  LocalServer server_;
  int port_ = 0;
  std::thread thread_;
};

std::vector<Route> echoRoutes() {
  return {
      {"GET", "/hello/([a-z]+)",
       [](const Request& r) {
         return jsonResponse({{"hello", r.matches[1]}});
       }},
      {"POST", "/echo", [](const Request& r) { return jsonResponse(parseJsonBody(r)); }},
      {"POST", "/name",
       [](const Request& r) {
         return jsonResponse({{"name", stringMember(parseJsonBody(r), "name", "{\"name\": ...}")}});
       }},
      {"GET", "/refuse", [](const Request&) -> Response { throw HttpError(409, "not now; try later"); }},
      {"GET", "/memory", [](const Request&) -> Response { throw std::bad_alloc(); }},
      {"GET", "/type", [](const Request&) -> Response { return jsonResponse(nlohmann::json("x").get<int>()); }},
  };
}

TEST(LocalServer, RoutesAnswerAndRefuseWithMessages) {
  Served s(echoRoutes());
  std::string answer = s.get("/hello/rock");
  EXPECT_EQ(statusOf(answer), 200) << answer;
  EXPECT_EQ(bodyOf(answer), R"({"hello":"rock"})");
  EXPECT_NE(answer.find("Connection: close"), std::string::npos);
  EXPECT_EQ(bodyOf(s.post("/echo", R"({"a":[1,2]})")), R"({"a":[1,2]})");
  answer = s.get("/refuse");
  EXPECT_EQ(statusOf(answer), 409);
  EXPECT_EQ(bodyOf(answer), R"({"error":"not now; try later"})");
  EXPECT_EQ(statusOf(s.get("/nowhere")), 404);
  answer = s.post("/hello/rock", "{}");
  EXPECT_EQ(statusOf(answer), 405);
  EXPECT_NE(answer.find("Allow: GET"), std::string::npos) << answer;
  EXPECT_EQ(statusOf(s.post("/name", R"({"name": 7})")), 400);
  EXPECT_EQ(statusOf(s.get("/type")), 400) << "a library type error is the client's, not a 500";
  answer = s.get("/memory");
  EXPECT_EQ(statusOf(answer), 503);
  EXPECT_NE(bodyOf(answer).find("ran out of memory"), std::string::npos) << answer;
  EXPECT_EQ(statusOf(s.get("/hello/again")), 200) << "still serving";
}

TEST(LocalServer, RefusesOtherPagesAndForeignHosts) {
  Served s(echoRoutes());
  EXPECT_EQ(statusOf(s.ask("GET /hello/x HTTP/1.1\r\nHost: evil.example:" + std::to_string(s.port()) + "\r\n\r\n")),
            403);
  EXPECT_EQ(statusOf(s.get("/hello/x", "Origin: http://evil.example\r\n")), 403);
  EXPECT_EQ(statusOf(s.post("/echo", "{}", "Content-Type: text/plain\r\n")), 415);
  EXPECT_EQ(statusOf(s.post("/echo", "{}", "Content-Type: application/json\r\nOrigin: http://evil.example\r\n")), 403);
  EXPECT_EQ(statusOf(s.post(
                "/echo", "{}",
                "Content-Type: application/json\r\nOrigin: http://localhost:" + std::to_string(s.port()) + "\r\n")),
            200);
}

TEST(LocalServer, RefusesDeepLargeAndMalformedRequestsAndCarriesOn) {
  Limits limits;
  limits.max_body_bytes = 1000;
  Served s(echoRoutes(), limits);
  std::string deep(200000, '[');
  limits.max_body_bytes = deep.size();
  Served wide(echoRoutes(), limits);
  std::string answer = wide.post("/echo", deep);
  EXPECT_EQ(statusOf(answer), 400);
  EXPECT_EQ(bodyOf(answer), R"({"error":"the request body nests deeper than 64 levels"})");
  answer = s.post("/echo", std::string(5000, ' '));
  EXPECT_EQ(statusOf(answer), 413) << "the client reads the answer, not a reset";
  EXPECT_NE(bodyOf(answer).find("5000 bytes; the server takes at most 1000 bytes"), std::string::npos) << answer;
  answer = s.ask("GET /hello/x HTTP/1.1\r\n" + s.host() + "X-Big: " + std::string(20000, 'a') + "\r\n\r\n");
  EXPECT_EQ(statusOf(answer), 431);
  std::string many = "GET /hello/x HTTP/1.1\r\n" + s.host();
  for (int i = 0; i < 100; ++i) many += "X-" + std::to_string(i) + ": 1\r\n";
  EXPECT_EQ(statusOf(s.ask(many + "\r\n")), 431);
  const std::string chunked =
      "POST /echo HTTP/1.1\r\n" + s.host() + "Content-Type: application/json\r\nTransfer-Encoding: chunked\r\n\r\n";
  answer = s.ask(chunked + "3\r\n[1,\r\n2\r\n2]\r\n0\r\n\r\n");
  EXPECT_EQ(statusOf(answer), 200) << answer;
  EXPECT_EQ(bodyOf(answer), "[1,2]");
  EXPECT_EQ(statusOf(s.ask(chunked + "400\r\n")), 413);
  // A header smuggled after a bare LF (cpp-httplib would read it; the layer would not): refused.
  answer = s.ask("GET /hello/x HTTP/1.1\r\n" + s.host() + "X: a\nRange: bytes=0-,0-,0-\r\n\r\n");
  EXPECT_EQ(statusOf(answer), 400) << answer;
  EXPECT_EQ(statusOf(s.get("/hello/x")), 200);
}

// Half-sent requests hold no worker: with one worker and more stalled clients
// than workers, a whole request is still answered while they stall.
TEST(LocalServer, StalledClientsDoNotHoldTheWorkers) {
  Limits limits;
  limits.workers = 1;
  Served s(echoRoutes(), limits);
  std::vector<std::unique_ptr<SocketClient>> stalled;
  for (int i = 0; i < 10; ++i) {
    stalled.push_back(std::make_unique<SocketClient>(s.port()));
    stalled.back()->send(i % 2 ? "GET /hello/x HTTP/1.1\r\nHo"
                               : "POST /echo HTTP/1.1\r\n" + s.host() +
                                     "Content-Type: application/json\r\n"
                                     "Content-Length: 100\r\n\r\n{\"a\":");
  }
  EXPECT_EQ(statusOf(s.get("/hello/x")), 200);
}

// A request that trickles in is cut off when its time is up, with a 408 it can read.
TEST(LocalServer, ARequestMustArriveWholeInTime) {
  Limits limits;
  limits.request_time = std::chrono::milliseconds(300);
  Served s(echoRoutes(), limits);
  SocketClient slow(s.port());
  const std::string request = "GET /hello/x HTTP/1.1\r\n" + s.host() + "\r\n";
  bool cut = false;
  for (const char c : request) {  // a byte every 50 ms: the whole request would take over a second
    if (!slow.send(std::string(1, c))) {
      cut = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  const std::string answer = slow.readAll();
  EXPECT_TRUE(cut || statusOf(answer) == 408) << answer;
  EXPECT_EQ(statusOf(answer), 408) << answer;
  EXPECT_NE(bodyOf(answer).find("did not arrive whole within 0.3 s"), std::string::npos) << answer;
}

// One client's unfinished requests make way for its new ones: past the limit the
// oldest unfinished one is dropped with a 408, and the new request is answered.
TEST(LocalServer, SlowRequestsPerClientAreBounded) {
  Limits limits;
  limits.max_connections_per_client = 4;
  limits.slow_after = std::chrono::milliseconds(0);  // every unfinished request is slow at once
  Served s(echoRoutes(), limits);
  std::vector<std::unique_ptr<SocketClient>> idle;
  for (int i = 0; i < 5; ++i) {
    idle.push_back(std::make_unique<SocketClient>(s.port()));
    idle.back()->send("GET /hel");
  }
  EXPECT_EQ(statusOf(idle.front()->readAll()), 408) << "the oldest slow request past 4 was dropped";
  EXPECT_EQ(statusOf(s.get("/hello/x")), 200);
  EXPECT_TRUE(idle.back()->send("lo/y HTTP/1.1\r\n" + s.host() + "\r\n"));
  EXPECT_EQ(statusOf(idle.back()->readAll()), 200) << "the newer slow requests were kept";
}

TEST(LocalServer, RequestsPastTheLimitAreKeptWhileTheyAreRecent) {
  Limits limits;
  limits.max_connections_per_client = 4;
  limits.slow_after = std::chrono::minutes(1);  // none turns slow in this test
  Served s(echoRoutes(), limits);
  std::vector<std::unique_ptr<SocketClient>> unfinished;
  for (int i = 0; i < 8; ++i) {
    unfinished.push_back(std::make_unique<SocketClient>(s.port()));
    unfinished.back()->send("GET /hel");
  }
  for (auto& client : unfinished) {
    EXPECT_TRUE(client->send("lo/y HTTP/1.1\r\n" + s.host() + "\r\n"));
    EXPECT_EQ(statusOf(client->readAll()), 200);
  }
}

TEST(LocalServer, AtTheConnectionLimitOnlySlowRequestsMakeWay) {
  Limits limits;
  limits.max_connections = 4;
  limits.slow_after = std::chrono::minutes(1);
  Served s(echoRoutes(), limits);
  std::vector<std::unique_ptr<SocketClient>> unfinished;
  for (int i = 0; i < 4; ++i) {
    unfinished.push_back(std::make_unique<SocketClient>(s.port()));
    unfinished.back()->send("GET /hel");
  }
  EXPECT_EQ(statusOf(s.get("/hello/x")), 503) << "none is slow yet: the new one waits its turn";
  EXPECT_TRUE(unfinished.front()->send("lo/y HTTP/1.1\r\n" + s.host() + "\r\n"));
  EXPECT_EQ(statusOf(unfinished.front()->readAll()), 200);
}

TEST(LocalServer, ABurstOfWholeRequestsPastTheLimitIsAnswered) {
  Limits limits;
  limits.max_connections_per_client = 4;
  limits.slow_after = std::chrono::minutes(1);
  Served s(echoRoutes(), limits);
  std::vector<std::unique_ptr<SocketClient>> burst;
  for (int i = 0; i < 24; ++i) {  // each sent whole before the next connects: none is slow, none waits
    burst.push_back(std::make_unique<SocketClient>(s.port()));
    burst.back()->send("GET /hello/x HTTP/1.1\r\n" + s.host() + "\r\n");
  }
  for (auto& client : burst) EXPECT_EQ(statusOf(client->readAll()), 200);
}

}  // namespace
}  // namespace rockbake::http
