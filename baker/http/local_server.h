// One HTTP layer for rockbake's local servers (docs/studio.md, "The server's
// promises"): the studio's, and any page to come. A LocalServer answers a route
// table on one address, and keeps these promises for every route:
//   - who may call: Host, Origin and a POST's Content-Type (http/caller_rules.h);
//   - limits: each request is read whole, under `Limits`, before a worker sees it
//     (http/connection_loop.h), so slow or oversized clients cost a buffer and a
//     deadline, never a worker; bodies of JSON are parsed with bounded nesting
//     (http/json_body.h); static files stay inside their folder (http/static_files.h);
//   - answers: a refused request gets a 4xx (or 503) and {"error": "..."} saying
//     what to do; a handler that throws HttpError chooses both; running out of
//     memory is a 503 and the server carries on; any other exception is a 500
//     with its message, logged. Every answer closes its connection.
// cpp-httplib parses requests and writes answers (http/local_server.cpp, the
// one file that includes it); this layer owns the sockets.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "http/limits.h"
#include "http/route.h"

namespace rockbake::http {

class LocalServer {
 public:
  LocalServer(std::vector<Route> routes, Limits limits = {});
  ~LocalServer();
  LocalServer(const LocalServer&) = delete;
  LocalServer& operator=(const LocalServer&) = delete;

  // Listens on host:port (port 0: a free one) and returns the port; clients
  // wait in the backlog until serve(). Throws std::runtime_error naming the
  // address and why it cannot be used.
  int listen(const std::string& host, int port);
  // Serves until stop(), then returns once every handler under way is done.
  void serve();
  // From any thread but a signal handler, at any time (before serve(): serve() returns at once).
  void stop();

  std::string url() const;  // http://HOST:PORT/ as listened on

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace rockbake::http
