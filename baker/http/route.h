// What a local server's routes take and give (docs/studio.md, "The server's
// promises"): plain requests and responses, a route table entry, and the
// refusal a handler throws. No HTTP library types: the layer's one .cpp that
// includes cpp-httplib (http/local_server.cpp) converts at the edge.
#pragma once

#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/error.h"

namespace rockbake::http {

struct Request {
  std::string method;                                        // GET, HEAD or POST
  std::string path;                                          // percent-decoded, as the route pattern matched it
  std::vector<std::string> matches;                          // the pattern's groups; [0] is the whole path
  std::multimap<std::string, std::string> query;             // decoded ?key=value pairs
  std::vector<std::pair<std::string, std::string>> headers;  // names in lower case, in arrival order
  std::string body;                                          // at most Limits::max_body_bytes

  // The first value of `?name=`, or nothing.
  std::optional<std::string> param(const std::string& name) const;
  // The first header of that name (any case), or nothing.
  std::optional<std::string> header(const std::string& name) const;
};

struct Response {
  int status = 200;
  std::string content_type = "application/json";
  std::string body;
  std::vector<std::pair<std::string, std::string>> headers;  // extra headers (Cache-Control, ...)
};

// A request the server refuses: a 4xx (or 503) status and a message saying
// what is wrong and what to do, sent as {"error": message}. Handlers throw it.
// Control bytes in the message (it may quote the request) are written as \xNN,
// so what() holds all of it.
class HttpError : public std::runtime_error {
 public:
  HttpError(int status, const std::string& message)
      : std::runtime_error(escapeControlBytes(message)), status_(status) {}
  int status() const { return status_; }

 private:
  int status_;
};

using Handler = std::function<Response(const Request&)>;

struct Route {
  std::string method;   // "GET" (which answers HEAD too) or "POST"
  std::string pattern;  // ECMAScript regular expression over the whole decoded path
  Handler handler;
};

}  // namespace rockbake::http
