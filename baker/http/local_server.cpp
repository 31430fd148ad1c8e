#include "http/local_server.h"

#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <strings.h>
#include <cerrno>
#include <cstring>
#include <regex>
#include <stdexcept>

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
#include "http/byte_ranges.h"
#include "http/caller_rules.h"
#include "http/connection_loop.h"
#include "http/json_body.h"

namespace rockbake::http {
namespace {

// cpp-httplib's request parsing and answer writing, run on one request already
// read whole (http/connection_loop.h) through an in-memory stream; its own
// sockets, threads and listening loop are never used.
class HttplibCore : public httplib::Server {
 public:
  using httplib::Server::process_request;
};

class BufferStream final : public httplib::Stream {
 public:
  explicit BufferStream(const RawRequest& request) : request_(request) {}

  bool is_readable() const override { return true; }
  bool is_writable() const override { return true; }
  ssize_t read(char* ptr, size_t size) override {
    const std::size_t n = std::min(size, request_.bytes.size() - read_);
    std::memcpy(ptr, request_.bytes.data() + read_, n);
    read_ += n;
    return ssize_t(n);
  }
  ssize_t write(const char* ptr, size_t size) override {
    // An interim "100 Continue" is the connection loop's to send, before the body
    // arrived; here the body is already read, and the client needs only the answer.
    if (out_.empty() && std::string_view(ptr, size).starts_with("HTTP/1.1 100 ")) return ssize_t(size);
    out_.append(ptr, size);
    return ssize_t(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    ip.assign(request_.peer_address);
    port = request_.peer_port;
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    ip.assign(request_.local_address);
    port = request_.local_port;
  }
  // Never a descriptor: cpp-httplib would refuse one past FD_SETSIZE, which it
  // select()s on; this stream is read from memory.
  socket_t socket() const override { return -1; }

  std::string& output() { return out_; }

 private:
  const RawRequest& request_;
  std::size_t read_ = 0;
  std::string out_;
};

// The pseudo-headers cpp-httplib adds to every request it parses.
bool addedByHttplib(const std::string& name) {
  return name == "REMOTE_ADDR" || name == "REMOTE_PORT" || name == "LOCAL_ADDR" || name == "LOCAL_PORT";
}

// The request's Range header, taken out of its head before cpp-httplib parses
// it: the layer answers ranges itself (http/byte_ranges.h), where cpp-httplib
// would answer a malformed one 416 and send overlapping ones as often as asked.
// Set for the worker's request while it is answered.
thread_local std::optional<std::string> t_range;

std::optional<std::string> takeRangeHeader(std::string& bytes) {
  std::size_t head_end = bytes.find("\r\n\r\n");
  if (head_end == std::string::npos) return std::nullopt;
  std::optional<std::string> value;
  int count = 0;
  std::size_t line = bytes.find("\r\n") + 2;  // after the request line
  while (line < head_end + 2) {
    const std::size_t end = bytes.find("\r\n", line);
    const std::size_t colon = bytes.find(':', line);
    if (colon < end && colon - line == 5 && strncasecmp(bytes.data() + line, "range", 5) == 0) {
      ++count;
      value = bytes.substr(colon + 1, end - colon - 1);
      bytes.erase(line, end + 2 - line);
      head_end -= end + 2 - line;
      continue;
    }
    line = end + 2;
  }
  if (count > 1) return std::nullopt;  // two Range headers: neither is meant, both ignored
  return value;
}

// A quick look for a Range header among the request's headers (any case).
bool containsRangeHeader(std::string_view bytes) {
  const std::size_t head_end = std::min(bytes.find("\r\n\r\n"), bytes.size());
  for (std::size_t i = bytes.find("\r\n"); i < head_end; i = bytes.find("\r\n", i + 2))
    if (head_end - i > 8 && strncasecmp(bytes.data() + i + 2, "range", 5) == 0) return true;
  return false;
}

// What every answer carries (docs/studio.md, "The server's promises"): no other
// page may frame it (a click through an invisible frame would be the user's),
// nor read it as a script, an image or a page of its own, and no type is guessed.
void addHardeningHeaders(httplib::Response& res, bool has_policy) {
  res.set_header("X-Content-Type-Options", "nosniff");
  res.set_header("X-Frame-Options", "DENY");
  res.set_header("Cross-Origin-Resource-Policy", "same-origin");
  res.set_header("Referrer-Policy", "no-referrer");
  // A page names its own policy (http/static_files.h); anything else runs nothing.
  if (!has_policy) res.set_header("Content-Security-Policy", "default-src 'none'; frame-ancestors 'none'");
}

std::optional<std::string> headerOf(const httplib::Request& req, const char* name) {
  if (!req.has_header(name)) return std::nullopt;
  return req.get_header_value(name);
}

}  // namespace

std::optional<std::string> Request::param(const std::string& name) const {
  const auto it = query.find(name);
  if (it == query.end()) return std::nullopt;
  return it->second;
}

std::optional<std::string> Request::header(const std::string& name) const {
  std::string key = name;
  std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const auto& [k, v] : headers)
    if (k == key) return v;
  return std::nullopt;
}

struct LocalServer::Impl {
  struct CompiledRoute {
    Route route;
    std::regex pattern;
  };

  Impl(std::vector<Route> routes, const Limits& server_limits) : limits(server_limits) {
    for (auto& route : routes) {
      std::regex pattern(route.pattern);
      table.push_back({std::move(route), std::move(pattern)});
    }
    const auto dispatch = [this](const httplib::Request& req, httplib::Response& res) { answer(req, res); };
    // Every method to one dispatcher: the route table answers 404 and 405 itself.
    const std::string any = ".*";
    core.Get(any, dispatch);
    core.Post(any, dispatch);
    core.Put(any, dispatch);
    core.Patch(any, dispatch);
    core.Delete(any, dispatch);
    core.Options(any, dispatch);
    core.set_payload_max_length(limits.max_body_bytes);
    // What cpp-httplib refuses itself (a malformed request line, 400) gets a message too.
    core.set_error_handler([](const httplib::Request&, httplib::Response& res) {
      if (!res.body.empty()) return;
      addHardeningHeaders(res, false);
      res.set_content(errorResponse(res.status, "a malformed request").body, "application/json");
    });
  }

  void answer(const httplib::Request& req, httplib::Response& res) const;
  Response route(const Request& request) const;
  std::string answerBytes(const RawRequest& raw);

  Limits limits;
  std::vector<CompiledRoute> table;
  HttplibCore core;
  std::unique_ptr<CallerRules> rules;
  std::unique_ptr<ConnectionLoop> loop;
  std::string url;
  std::mutex stop_mutex;
  bool stopped = false;
};

// Turns a request into an answer: who may call, then the route table.
void LocalServer::Impl::answer(const httplib::Request& req, httplib::Response& res) const {
  Request request;
  request.method = req.method;
  request.path = req.path;
  request.query.insert(req.params.begin(), req.params.end());
  for (const auto& [name, value] : req.headers) {
    if (addedByHttplib(name)) continue;
    std::string key = name;
    std::transform(key.begin(), key.end(), key.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    request.headers.emplace_back(std::move(key), value);
  }
  request.body = req.body;
  Response response;
  if (auto refusal =
          rules->refusal(req.method, headerOf(req, "Host"), headerOf(req, "Origin"), headerOf(req, "Content-Type")))
    response = errorResponse(refusal->status(), refusal->what());
  else
    response = route(request);
  // A 200 to a GET with a Range header is cut to the ranges here (a video
  // seeking in the review page); a HEAD gets the whole answer's headers.
  if (response.status == 200 && req.method == "GET" && t_range) answerRanges(response, *t_range);
  res.status = response.status;
  bool has_policy = false;
  for (const auto& [name, value] : response.headers) {
    res.set_header(name, value);
    has_policy = has_policy || name == "Content-Security-Policy";
  }
  addHardeningHeaders(res, has_policy);
  res.set_content(std::move(response.body), response.content_type);
}

Response LocalServer::Impl::route(const Request& received) const {
  const std::string method = received.method == "HEAD" ? "GET" : received.method;
  std::vector<std::string> allowed;
  for (const auto& [route, pattern] : table) {
    std::smatch match;
    if (!std::regex_match(received.path, match, pattern)) continue;
    if (route.method != method) {
      allowed.push_back(route.method);
      continue;
    }
    Request request = received;
    for (const auto& group : match) request.matches.push_back(group.str());
    try {
      return route.handler(request);
    } catch (const HttpError& e) {
      return errorResponse(e.status(), e.what());
    } catch (const std::bad_alloc&) {
      return errorResponse(503, "the server ran out of memory answering " + method + " " + received.path +
                                    "; nothing else was lost: try again, or free some memory first");
    } catch (const nlohmann::json::exception&) {
      return errorResponse(
          400, "the request's JSON does not have the form " + method + " " + received.path + " takes (docs/studio.md)");
    } catch (const std::exception& e) {
      spdlog::error("http: {} {}: {}", method, escapeControlBytes(received.path), e.what());
      return errorResponse(500, std::string("internal error: ") + e.what());
    }
  }
  if (!allowed.empty()) {
    Response refused = errorResponse(
        405, received.path + " takes " + fmt::format("{}", fmt::join(allowed, ", ")) + ", not " + received.method);
    refused.headers.emplace_back("Allow", fmt::format("{}", fmt::join(allowed, ", ")));
    return refused;
  }
  return errorResponse(404, "not found: " + received.path);
}

std::string LocalServer::Impl::answerBytes(const RawRequest& raw) {
  try {
    // Only a request that has a Range header is copied, to take it out.
    std::string edited;
    RawRequest request = raw;
    t_range.reset();
    if (containsRangeHeader(raw.bytes)) {
      edited.assign(raw.bytes);
      t_range = takeRangeHeader(edited);
      request.bytes = edited;
    }
    BufferStream stream(request);
    bool connection_closed = false;
    core.process_request(stream, /*close_connection=*/true, connection_closed, nullptr);
    return std::move(stream.output());
  } catch (const std::bad_alloc&) {
    return {};  // the connection loop answers 503 with a message made beforehand
  } catch (const std::exception& e) {
    spdlog::error("http: {}", e.what());
    return plainAnswer(500, std::string("internal error: ") + e.what());
  }
}

LocalServer::LocalServer(std::vector<Route> routes, Limits limits)
    : impl_(std::make_unique<Impl>(std::move(routes), limits)) {}

LocalServer::~LocalServer() = default;

int LocalServer::listen(const std::string& host, int port) {
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  hints.ai_flags = AI_PASSIVE | AI_NUMERICSERV;
  addrinfo* found = nullptr;
  const std::string where = fmt::format("{}:{}", host, port);
  if (const int error =
          ::getaddrinfo(host.empty() ? nullptr : host.c_str(), std::to_string(port).c_str(), &hints, &found))
    throw std::runtime_error("cannot listen on " + where + ": " + ::gai_strerror(error));
  int fd = -1, problem = 0;
  for (const addrinfo* a = found; a && fd < 0; a = a->ai_next) {
    fd = ::socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) continue;
    const int on = 1;
    ::setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &on, sizeof on);
    if (::bind(fd, a->ai_addr, a->ai_addrlen) != 0 || ::listen(fd, SOMAXCONN) != 0) {
      problem = errno;
      ::close(fd);
      fd = -1;
    }
  }
  ::freeaddrinfo(found);
  if (fd < 0)
    throw std::runtime_error("cannot listen on " + where + ": " +
                             (problem ? std::strerror(problem) : "no usable address"));
  sockaddr_storage bound{};
  socklen_t length = sizeof bound;
  ::getsockname(fd, reinterpret_cast<sockaddr*>(&bound), &length);
  const int actual = bound.ss_family == AF_INET6 ? ntohs(reinterpret_cast<sockaddr_in6&>(bound).sin6_port)
                                                 : ntohs(reinterpret_cast<sockaddr_in&>(bound).sin_port);
  impl_->rules = std::make_unique<CallerRules>(host, actual);
  impl_->url = fmt::format("http://{}:{}/", host.find(':') != std::string::npos ? "[" + host + "]" : host, actual);
  impl_->loop = std::make_unique<ConnectionLoop>(
      fd, impl_->limits, [impl = impl_.get()](const RawRequest& raw) { return impl->answerBytes(raw); });
  return actual;
}

void LocalServer::serve() {
  if (!impl_->loop) throw std::logic_error("LocalServer::serve before listen");
  {
    std::lock_guard lock(impl_->stop_mutex);
    if (impl_->stopped) return;
  }
  impl_->loop->run();
}

void LocalServer::stop() {
  std::lock_guard lock(impl_->stop_mutex);
  impl_->stopped = true;
  if (impl_->loop) impl_->loop->stop();
}

std::string LocalServer::url() const {
  return impl_->url;
}

}  // namespace rockbake::http
