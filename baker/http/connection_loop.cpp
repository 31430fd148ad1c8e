#include "http/connection_loop.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <deque>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "http/json_body.h"
#include "http/request_framing.h"

namespace rockbake::http {
namespace {

using Clock = std::chrono::steady_clock;

// After a refused body, what the client still sends is read and dropped for this
// long (or this much) before the connection closes, so that its answer arrives
// instead of a reset (a "lingering close").
constexpr auto kDrainTime = std::chrono::seconds(2);
constexpr std::size_t kMaxDrainBytes = std::size_t(16) << 20;
// Accepting stops for this long when the process is out of file descriptors.
constexpr auto kAcceptPause = std::chrono::milliseconds(100);

const char* reason(int status) {
  switch (status) {
    case 200:
      return "OK";
    case 400:
      return "Bad Request";
    case 403:
      return "Forbidden";
    case 404:
      return "Not Found";
    case 408:
      return "Request Timeout";
    case 411:
      return "Length Required";
    case 413:
      return "Content Too Large";
    case 431:
      return "Request Header Fields Too Large";
    case 500:
      return "Internal Server Error";
    case 503:
      return "Service Unavailable";
    default:
      return "Error";
  }
}

struct Connection {
  int fd = -1;
  std::string peer;
  int peer_port = 0;
  std::string local;
  int local_port = 0;
  // Reading the request; with a worker (the loop leaves `in` and `out` alone);
  // sending the answer; dropping what the client still sends after a refusal.
  enum class Phase { Reading, WithWorker, Writing, Draining } phase = Phase::Reading;
  Clock::time_point opened, deadline;
  std::string in;
  Framing framing;           // header_bytes > 0 once the headers are whole
  std::size_t reserved = 0;  // body bytes counted against Limits::max_buffered_bytes
  std::string out;
  std::string_view sending;  // `out`, or the answer made beforehand for running out of memory
  std::size_t sent = 0;
  bool drain = false;  // after the answer: Draining, not closed
  std::size_t drained = 0;
};

// An address and port as text ("127.0.0.1", "::1").
std::pair<std::string, int> addressOf(const sockaddr_storage& address) {
  std::array<char, INET6_ADDRSTRLEN> text{};
  if (address.ss_family == AF_INET) {
    const auto& a = reinterpret_cast<const sockaddr_in&>(address);
    ::inet_ntop(AF_INET, &a.sin_addr, text.data(), text.size());
    return {text.data(), ntohs(a.sin_port)};
  }
  if (address.ss_family == AF_INET6) {
    const auto& a = reinterpret_cast<const sockaddr_in6&>(address);
    ::inet_ntop(AF_INET6, &a.sin6_addr, text.data(), text.size());
    return {text.data(), ntohs(a.sin6_port)};
  }
  return {"", 0};
}

}  // namespace

std::string plainAnswer(int status, const std::string& message) {
  const std::string body = errorResponse(status, message).body;
  return fmt::format(
      "HTTP/1.1 {} {}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n"
      "X-Content-Type-Options: nosniff\r\nX-Frame-Options: DENY\r\n"
      "Content-Security-Policy: default-src 'none'; frame-ancestors 'none'\r\n\r\n{}",
      status, reason(status), body.size(), body);
}

struct ConnectionLoop::Impl {
  Impl(int listener_fd, const Limits& server_limits, Answerer answerer)
      : listener(listener_fd), limits(server_limits), answer(std::move(answerer)) {
    framing_limits = {limits.max_header_bytes, limits.max_headers, limits.max_body_bytes};
    out_of_memory = plainAnswer(503, "the server ran out of memory answering this request; try again");
    wake = ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
    if (wake < 0) throw std::runtime_error(std::string("cannot make an event descriptor: ") + std::strerror(errno));
    // Every connection may be answered at once: handing an answer over never allocates.
    answered.reserve(limits.max_connections + 1);
  }
  ~Impl() {
    for (auto& [fd, c] : connections) ::close(fd);
    ::close(listener);
    ::close(wake);
  }

  void run();
  void serveOnce();
  void acceptAll();
  void admit(int fd, const sockaddr_storage& peer);
  bool makeRoom();
  void dropSlow(Connection& c);
  void limitSlowPerClient(Clock::time_point now);
  void readFrom(Connection& c);
  bool advance(Connection& c);
  void writeTo(Connection& c);
  void drainFrom(Connection& c);
  void refuse(Connection& c, int status, const std::string& message, bool drain);
  void enqueue(Connection& c);
  void collectAnswers();
  void expire(Clock::time_point now);
  void close(int fd);
  void work();
  void signal() const {
    const std::uint64_t one = 1;
    [[maybe_unused]] const ssize_t n = ::write(wake, &one, sizeof one);
  }

  int listener;
  Limits limits;
  FramingLimits framing_limits;
  Answerer answer;
  std::string out_of_memory;  // made beforehand: when it is needed, nothing more may be allocatable
  int wake = -1;
  std::atomic<bool> stopping{false};
  std::map<int, std::unique_ptr<Connection>> connections;  // by descriptor; the loop's thread only
  std::size_t buffered = 0;                                // sum of Connection::reserved
  Clock::time_point accept_paused_until{};

  // Hand-over between the loop and the workers.
  std::mutex mutex;
  std::condition_variable work_ready;
  std::deque<Connection*> waiting;
  std::vector<Connection*> answered;
  bool workers_stop = false;
  std::vector<std::thread> workers;
};

void ConnectionLoop::Impl::run() {
  struct JoinWorkers {
    Impl& loop;
    ~JoinWorkers() {
      {
        std::lock_guard lock(loop.mutex);
        loop.workers_stop = true;
      }
      loop.work_ready.notify_all();
      for (auto& worker : loop.workers) worker.join();
      loop.workers.clear();
    }
  } join{*this};
  for (int i = 0; i < std::max(1, limits.workers); ++i) workers.emplace_back([this] { work(); });
  while (!stopping) {
    try {
      serveOnce();
    } catch (const std::bad_alloc&) {
      // Out of memory in the loop itself: drop the unfinished requests (their
      // buffers are what can be given back) and carry on.
      for (auto it = connections.begin(); it != connections.end();) {
        if (it->second->phase != Connection::Phase::Reading) {
          ++it;
          continue;
        }
        buffered -= it->second->reserved;
        ::close(it->first);
        it = connections.erase(it);
      }
    }
  }
}

void ConnectionLoop::Impl::serveOnce() {
  collectAnswers();
  const Clock::time_point now = Clock::now();
  std::vector<pollfd> polled = {{wake, POLLIN, 0}};
  const bool accepting = now >= accept_paused_until;
  if (accepting) polled.push_back({listener, POLLIN, 0});
  Clock::time_point next = accepting ? Clock::time_point::max() : accept_paused_until;
  for (const auto& [fd, c] : connections) {
    if (c->phase == Connection::Phase::WithWorker) continue;
    polled.push_back({fd, short(c->phase == Connection::Phase::Writing ? POLLOUT : POLLIN), 0});
    next = std::min(next, c->deadline);
    if (c->phase == Connection::Phase::Reading && c->opened + limits.slow_after > now)
      next = std::min(next, c->opened + limits.slow_after);  // when it turns slow (limitSlowPerClient)
  }
  const int timeout =
      next == Clock::time_point::max()
          ? -1
          : int(std::clamp<std::int64_t>(std::chrono::duration_cast<std::chrono::milliseconds>(next - now).count() + 1,
                                         0, 60'000));
  if (::poll(polled.data(), polled.size(), timeout) < 0) {
    if (errno == ENOMEM) throw std::bad_alloc();
    if (errno != EINTR) throw std::runtime_error(std::string("poll failed: ") + std::strerror(errno));
    return;
  }
  if (polled[0].revents) {
    std::uint64_t count = 0;
    [[maybe_unused]] const ssize_t n = ::read(wake, &count, sizeof count);
  }
  std::size_t first = 1;
  if (accepting) {
    if (polled[1].revents) acceptAll();
    first = 2;
  }
  for (std::size_t i = first; i < polled.size(); ++i) {
    if (!polled[i].revents) continue;
    const auto it = connections.find(polled[i].fd);
    if (it == connections.end()) continue;
    Connection& c = *it->second;
    if (c.phase == Connection::Phase::Reading)
      readFrom(c);
    else if (c.phase == Connection::Phase::Writing)
      writeTo(c);
    else if (c.phase == Connection::Phase::Draining)
      drainFrom(c);
  }
  expire(Clock::now());
}

void ConnectionLoop::Impl::acceptAll() {
  for (;;) {
    sockaddr_storage peer{};
    socklen_t length = sizeof peer;
    const int fd = ::accept4(listener, reinterpret_cast<sockaddr*>(&peer), &length, SOCK_NONBLOCK | SOCK_CLOEXEC);
    if (fd >= 0) {
      admit(fd, peer);
      continue;
    }
    if (errno == EINTR || errno == ECONNABORTED) continue;
    if (errno == EMFILE || errno == ENFILE || errno == ENOBUFS || errno == ENOMEM) {
      spdlog::warn("http: cannot accept a connection ({}); waiting", std::strerror(errno));
      accept_paused_until = Clock::now() + kAcceptPause;
    }
    return;
  }
}

// Room for one more connection: past max_connections, the oldest request
// still arriving after slow_after (of any client) makes way for it. False
// when there is none.
bool ConnectionLoop::Impl::makeRoom() {
  if (connections.size() < limits.max_connections) return true;
  const Clock::time_point slow = Clock::now() - limits.slow_after;
  Connection* oldest = nullptr;
  for (const auto& [fd, c] : connections)
    if (c->phase == Connection::Phase::Reading && c->opened <= slow && (!oldest || c->opened < oldest->opened))
      oldest = c.get();
  if (!oldest) return false;
  dropSlow(*oldest);
  return true;
}

// A request still arriving that makes way for others: 408, and closed at once.
void ConnectionLoop::Impl::dropSlow(Connection& c) {
  const std::string answer_bytes = plainAnswer(
      408, "the request did not arrive in time: its client keeps more slow requests than the server allows");
  [[maybe_unused]] const ssize_t n = ::send(c.fd, answer_bytes.data(), answer_bytes.size(), MSG_NOSIGNAL);
  close(c.fd);
}

// Each client keeps at most max_connections_per_client requests that have been
// arriving for longer than slow_after: its oldest beyond that are dropped.
void ConnectionLoop::Impl::limitSlowPerClient(Clock::time_point now) {
  std::map<std::string_view, std::vector<Connection*>> slow_by_client;
  for (const auto& [fd, c] : connections)
    if (c->phase == Connection::Phase::Reading && c->opened <= now - limits.slow_after)
      slow_by_client[c->peer].push_back(c.get());
  std::vector<Connection*> dropped;
  for (auto& [peer, slow] : slow_by_client) {
    if (slow.size() <= limits.max_connections_per_client) continue;
    std::sort(slow.begin(), slow.end(), [](const Connection* a, const Connection* b) { return a->opened < b->opened; });
    dropped.insert(dropped.end(), slow.begin(), slow.end() - std::ptrdiff_t(limits.max_connections_per_client));
  }
  for (Connection* c : dropped) dropSlow(*c);  // after the map: its keys view the connections' strings
}

void ConnectionLoop::Impl::admit(int fd, const sockaddr_storage& peer_address) {
  const auto [peer, peer_port] = addressOf(peer_address);
  if (stopping || !makeRoom()) {
    const std::string refusal = plainAnswer(
        503, fmt::format("the server is busy: it has {} connections open; try again in a moment", connections.size()));
    [[maybe_unused]] const ssize_t n = ::send(fd, refusal.data(), refusal.size(), MSG_NOSIGNAL);
    ::close(fd);
    return;
  }
  const int on = 1;  // answers go out whole at once: nothing to gain from Nagle's delay
  ::setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &on, sizeof on);
  auto c = std::make_unique<Connection>();
  c->fd = fd;
  c->peer = peer;
  c->peer_port = peer_port;
  sockaddr_storage local{};
  socklen_t length = sizeof local;
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&local), &length) == 0)
    std::tie(c->local, c->local_port) = addressOf(local);
  c->opened = Clock::now();
  c->deadline = c->opened + limits.request_time;
  connections.emplace(fd, std::move(c));
}

void ConnectionLoop::Impl::readFrom(Connection& c) {
  std::array<char, 16384> chunk;
  while (c.phase == Connection::Phase::Reading) {
    // Never past the request: its headers' limit until they are whole, then its length.
    const std::size_t limit = !c.framing.header_bytes ? limits.max_header_bytes + limits.max_body_bytes
                              : c.framing.chunked     ? c.framing.header_bytes + maxBodyWireBytes(framing_limits) + 1
                                                      : c.framing.requestBytes();
    const std::size_t want = std::min(chunk.size(), limit - std::min(limit, c.in.size()));
    const ssize_t n = want ? ::recv(c.fd, chunk.data(), want, 0) : 0;
    if (n > 0) {
      c.in.append(chunk.data(), std::size_t(n));
      if (!advance(c)) return;
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    close(c.fd);  // the client went away before its request was whole
    return;
  }
}

// Judges what has arrived; false once the connection has left the Reading phase.
bool ConnectionLoop::Impl::advance(Connection& c) {
  const bool had_headers = c.framing.header_bytes > 0;
  if (had_headers && !c.framing.chunked) {
    if (c.in.size() < c.framing.requestBytes()) return true;
    enqueue(c);
    return false;
  }
  c.framing = frameRequest(c.in, framing_limits);  // a chunked body is judged afresh as it grows
  if (c.framing.state == Framing::State::Refused) {
    refuse(c, c.framing.status, c.framing.message, /*drain=*/true);
    return false;
  }
  if (!c.framing.header_bytes) return true;
  if (!had_headers) {
    const std::size_t body = c.framing.chunked ? maxBodyWireBytes(framing_limits) : c.framing.content_length;
    if (buffered + body > limits.max_buffered_bytes) {
      refuse(c, 503, "the server is busy reading other requests' bodies; try again in a moment", true);
      return false;
    }
    c.reserved = body;
    buffered += body;
    if (c.framing.expect_continue && c.framing.state != Framing::State::Complete) {
      static const std::string kContinue = "HTTP/1.1 100 Continue\r\n\r\n";
      [[maybe_unused]] const ssize_t n = ::send(c.fd, kContinue.data(), kContinue.size(), MSG_NOSIGNAL);
    }
  }
  if (c.framing.state != Framing::State::Complete) return true;
  enqueue(c);
  return false;
}

void ConnectionLoop::Impl::enqueue(Connection& c) {
  {
    std::lock_guard lock(mutex);
    if (waiting.size() < limits.max_waiting_requests) {
      waiting.push_back(&c);
      c.phase = Connection::Phase::WithWorker;
    }
  }
  if (c.phase != Connection::Phase::WithWorker) {
    refuse(
        c, 503,
        fmt::format("the server is busy: {} requests are waiting; try again in a moment", limits.max_waiting_requests),
        false);
    return;
  }
  work_ready.notify_one();
}

void ConnectionLoop::Impl::refuse(Connection& c, int status, const std::string& message, bool drain) {
  buffered -= c.reserved;
  c.reserved = 0;
  std::string().swap(c.in);
  c.out = plainAnswer(status, message);
  c.sending = c.out;
  c.sent = 0;
  c.drain = drain;
  c.phase = Connection::Phase::Writing;
  c.deadline = Clock::now() + limits.answer_time;
  writeTo(c);
}

void ConnectionLoop::Impl::writeTo(Connection& c) {
  while (c.sent < c.sending.size()) {
    const ssize_t n = ::send(c.fd, c.sending.data() + c.sent, c.sending.size() - c.sent, MSG_NOSIGNAL);
    if (n > 0) {
      c.sent += std::size_t(n);
      continue;
    }
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    close(c.fd);
    return;
  }
  if (!c.drain) {
    close(c.fd);
    return;
  }
  ::shutdown(c.fd, SHUT_WR);
  c.sending = {};
  std::string().swap(c.out);
  c.phase = Connection::Phase::Draining;
  c.deadline = Clock::now() + kDrainTime;
}

void ConnectionLoop::Impl::drainFrom(Connection& c) {
  std::array<char, 16384> chunk;
  for (;;) {
    const ssize_t n = ::recv(c.fd, chunk.data(), chunk.size(), 0);
    if (n > 0 && (c.drained += std::size_t(n)) < kMaxDrainBytes) continue;
    if (n < 0 && errno == EINTR) continue;
    if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK)) return;
    close(c.fd);
    return;
  }
}

void ConnectionLoop::Impl::collectAnswers() {
  std::vector<Connection*> done;
  {
    std::lock_guard lock(mutex);
    done.assign(answered.begin(), answered.end());  // `answered` keeps its room
    answered.clear();
  }
  for (Connection* c : done) {
    buffered -= c->reserved;
    c->reserved = 0;
    std::string().swap(c->in);
    c->sending = c->out.empty() ? std::string_view(out_of_memory) : std::string_view(c->out);
    c->sent = 0;
    c->phase = Connection::Phase::Writing;
    c->deadline = Clock::now() + limits.answer_time;
    writeTo(*c);
  }
}

void ConnectionLoop::Impl::expire(Clock::time_point now) {
  limitSlowPerClient(now);
  std::vector<Connection*> late;
  for (const auto& [fd, c] : connections)
    if (c->phase != Connection::Phase::WithWorker && c->deadline <= now) late.push_back(c.get());
  for (Connection* c : late) {
    if (c->phase == Connection::Phase::Reading)
      refuse(*c, 408,
             fmt::format("the request did not arrive whole within {} s; send it at once",
                         std::chrono::duration<double>(limits.request_time).count()),
             /*drain=*/true);
    else
      close(c->fd);
  }
}

void ConnectionLoop::Impl::close(int fd) {
  const auto it = connections.find(fd);
  if (it == connections.end()) return;
  buffered -= it->second->reserved;
  ::close(fd);
  connections.erase(it);
}

void ConnectionLoop::Impl::work() {
  for (;;) {
    Connection* c = nullptr;
    {
      std::unique_lock lock(mutex);
      work_ready.wait(lock, [&] { return workers_stop || !waiting.empty(); });
      if (waiting.empty()) return;
      c = waiting.front();
      waiting.pop_front();
    }
    const RawRequest request{c->in, c->peer, c->peer_port, c->local, c->local_port};
    std::string out;  // empty: the answerer ran out of memory even for its refusal
    try {
      out = answer(request);
    } catch (...) {
      out.clear();
    }
    {
      std::lock_guard lock(mutex);
      c->out = std::move(out);
      answered.push_back(c);  // within its reserved room
    }
    signal();
  }
}

ConnectionLoop::ConnectionLoop(int listener, const Limits& limits, Answerer answer)
    : impl_(std::make_unique<Impl>(listener, limits, std::move(answer))) {}

ConnectionLoop::~ConnectionLoop() = default;

void ConnectionLoop::run() {
  impl_->run();
}

void ConnectionLoop::stop() {
  impl_->stopping = true;
  impl_->signal();
}

}  // namespace rockbake::http
