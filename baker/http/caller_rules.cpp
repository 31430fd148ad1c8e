#include "http/caller_rules.h"

#include <arpa/inet.h>
#include <ifaddrs.h>
#include <netinet/in.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>

namespace rockbake::http {
namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// "host:port", brackets around an IPv6 address, as a Host header writes it.
std::string authority(const std::string& host, int port) {
  const bool ipv6 = host.find(':') != std::string::npos;
  return lower((ipv6 ? "[" + host + "]" : host) + ":" + std::to_string(port));
}

bool isWildcard(const std::string& host) {
  return host.empty() || host == "0.0.0.0" || host == "::" || host == "[::]";
}

// Every address of this machine's interfaces, and its host name.
std::vector<std::string> machineNames() {
  std::vector<std::string> names;
  ifaddrs* list = nullptr;
  if (::getifaddrs(&list) == 0) {
    for (const ifaddrs* a = list; a; a = a->ifa_next) {
      if (!a->ifa_addr) continue;
      std::array<char, INET6_ADDRSTRLEN> text{};
      const int family = a->ifa_addr->sa_family;
      const void* bytes =
          family == AF_INET    ? static_cast<const void*>(&reinterpret_cast<sockaddr_in*>(a->ifa_addr)->sin_addr)
          : family == AF_INET6 ? static_cast<const void*>(&reinterpret_cast<sockaddr_in6*>(a->ifa_addr)->sin6_addr)
                               : nullptr;
      if (bytes && ::inet_ntop(family, bytes, text.data(), text.size())) names.emplace_back(text.data());
    }
    ::freeifaddrs(list);
  }
  std::array<char, 256> name{};
  if (::gethostname(name.data(), name.size() - 1) == 0 && name[0]) names.emplace_back(name.data());
  return names;
}

// The media type of a Content-Type value, without parameters, lower case.
std::string mediaType(const std::string& value) {
  std::string type = value.substr(0, value.find(';'));
  type.erase(std::remove_if(type.begin(), type.end(), [](unsigned char c) { return std::isspace(c); }), type.end());
  return lower(type);
}

}  // namespace

CallerRules::CallerRules(const std::string& host, int port) {
  std::vector<std::string> names = {"localhost"};
  if (isWildcard(host)) {
    const std::vector<std::string> machine = machineNames();
    names.insert(names.end(), machine.begin(), machine.end());
  } else {
    names.push_back(host.size() > 2 && host.front() == '[' && host.back() == ']' ? host.substr(1, host.size() - 2)
                                                                                 : host);
  }
  for (const std::string& name : names) {
    hosts_.push_back(authority(name, port));
    if (port == 80) hosts_.push_back(lower(name.find(':') != std::string::npos ? "[" + name + "]" : name));
  }
  std::sort(hosts_.begin(), hosts_.end());
  hosts_.erase(std::unique(hosts_.begin(), hosts_.end()), hosts_.end());
  address_ = "http://" + authority(isWildcard(host) ? "localhost" : names.back(), port) + "/";
}

bool CallerRules::knownHost(const std::string& host) const {
  return std::binary_search(hosts_.begin(), hosts_.end(), lower(host));
}

std::optional<HttpError> CallerRules::refusal(const std::string& method, const std::optional<std::string>& host,
                                              const std::optional<std::string>& origin,
                                              const std::optional<std::string>& content_type) const {
  if (!host || !knownHost(*host))
    return HttpError(403, "Host '" + host.value_or("") + "' is not this server's address; open it at " + address_);
  if (origin && !(origin->rfind("http://", 0) == 0 && knownHost(origin->substr(7))))
    return HttpError(
        403, "requests from other web pages (Origin '" + *origin + "') are refused; use the page at " + address_);
  if (method == "POST" && mediaType(content_type.value_or("")) != "application/json")
    return HttpError(415,
                     "a POST must have Content-Type: application/json (it had '" + content_type.value_or("") + "')");
  return std::nullopt;
}

}  // namespace rockbake::http
