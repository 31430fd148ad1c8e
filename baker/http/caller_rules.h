// Who may call a local server (docs/studio.md, "Who may call"). A local server
// has no login, so the browser's own rules are what keep other web pages out:
//   - Host must name the server: the address it listens on or `localhost`, with
//     its port (listening on a wildcard address, 0.0.0.0 or ::, any address of
//     this machine's interfaces, or its host name). A page whose domain was made
//     to resolve to 127.0.0.1 (DNS rebinding) sends its own domain, and is refused.
//   - Origin, when sent, must be http:// and such a host. Browsers send it on
//     every POST and every cross-origin fetch; "null" (a sandboxed frame, a file)
//     is refused.
//   - A POST must say Content-Type: application/json. A form, or a fetch a page
//     may send to another origin without asking first (text/plain), cannot.
// Requests without Origin (curl, scripts, a browser's own navigation) pass on
// Host alone.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "http/route.h"

namespace rockbake::http {

class CallerRules {
 public:
  // `host` as the server was bound (a name, an address, or a wildcard), and its port.
  CallerRules(const std::string& host, int port);

  // Nothing when the request may go on, else the refusal (403 or 415, with a
  // message that names what to do). Header values as received (nothing: absent).
  std::optional<HttpError> refusal(const std::string& method, const std::optional<std::string>& host,
                                   const std::optional<std::string>& origin,
                                   const std::optional<std::string>& content_type) const;

  // Every Host value accepted, lower case ("127.0.0.1:8631", "localhost:8631").
  const std::vector<std::string>& hosts() const { return hosts_; }

 private:
  bool knownHost(const std::string& host) const;
  std::vector<std::string> hosts_;
  std::string address_;  // http://HOST:PORT/, for messages
};

}  // namespace rockbake::http
