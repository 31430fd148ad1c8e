#include "http/local_server.h"

#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <regex>
#include <stdexcept>

#include <fmt/format.h>
#include <httplib.h>
#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include "core/error.h"
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
    // What cpp-httplib refuses itself (a malformed request line, 400; a bad Range, 416) gets a message too.
    core.set_error_handler([](const httplib::Request&, httplib::Response& res) {
      if (!res.body.empty()) return;
      const std::string message =
          res.status == 416 ? "the Range header asks for bytes the answer does not have" : "a malformed request";
      res.set_content(errorResponse(res.status, message).body, "application/json");
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
  // A 200 to a request with a Range header is left for cpp-httplib to number:
  // it cuts the body to the range and answers 206 only when the status is
  // still unset, and a 200 with part of a file reads as the whole file (a
  // video seeking in the review page).
  res.status = response.status == 200 && !req.ranges.empty() ? -1 : response.status;
  for (const auto& [name, value] : response.headers) res.set_header(name, value);
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
    BufferStream stream(raw);
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
