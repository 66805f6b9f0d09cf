#include "kew/config/address.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>

#include <array>
#include <cstring>

#include <fmt/format.h>

#include "kew/config/config_error.hpp"

namespace kew::config {

std::optional<HostPort> parse_host_port(std::string_view text, std::string* error) {
  const auto refuse = [&](std::string_view why) -> std::optional<HostPort> {
    if (error) *error = fmt::format("\"{}\" is not HOST:PORT: {}", text, why);
    return std::nullopt;
  };
  std::string_view host, port;
  if (!text.empty() && text.front() == '[') {
    const auto close = text.find(']');
    if (close == std::string_view::npos) return refuse("no ']' after the IPv6 address");
    if (close + 1 >= text.size() || text[close + 1] != ':') return refuse("no ':PORT' after ']'");
    host = text.substr(1, close - 1);
    port = text.substr(close + 2);
  } else {
    const auto colon = text.rfind(':');
    if (colon == std::string_view::npos) return refuse("no ':PORT'");
    host = text.substr(0, colon);
    port = text.substr(colon + 1);
    if (host.find(':') != std::string_view::npos) return refuse("an IPv6 address goes in brackets, as [::1]:4747");
  }
  if (host.empty()) return refuse("empty host");
  if (port.empty()) return refuse("empty port");
  unsigned value = 0;
  for (const char c : port) {
    if (c < '0' || c > '9') return refuse("the port is not a decimal number");
    value = value * 10 + static_cast<unsigned>(c - '0');
    if (value > 65535) return refuse("the port is above 65535");
  }
  if (value == 0) return refuse("port 0 is not a port one can reach");
  return HostPort{std::string(host), static_cast<std::uint16_t>(value)};
}

HostPort require_host_port(std::string_view text) {
  std::string error;
  std::optional<HostPort> address = parse_host_port(text, &error);
  if (!address) throw ConfigError(error);
  return std::move(*address);
}

std::string to_string(const HostPort& address) {
  if (address.host.find(':') != std::string::npos) return fmt::format("[{}]:{}", address.host, address.port);
  return fmt::format("{}:{}", address.host, address.port);
}

std::optional<std::string> canonical_ip(std::string_view text) {
  const std::string host(text);
  std::array<char, INET6_ADDRSTRLEN> buffer{};
  in_addr v4{};
  if (::inet_pton(AF_INET, host.c_str(), &v4) == 1)
    return std::string(::inet_ntop(AF_INET, &v4, buffer.data(), buffer.size()));
  in6_addr v6{};
  if (::inet_pton(AF_INET6, host.c_str(), &v6) != 1) return std::nullopt;
  if (IN6_IS_ADDR_V4MAPPED(&v6)) {
    std::memcpy(&v4, &v6.s6_addr[12], sizeof v4);
    return std::string(::inet_ntop(AF_INET, &v4, buffer.data(), buffer.size()));
  }
  return std::string(::inet_ntop(AF_INET6, &v6, buffer.data(), buffer.size()));
}

ListenScope listen_scope(std::string_view host) {
  if (host == "localhost") return ListenScope::Loopback;
  const std::optional<std::string> ip = canonical_ip(host);
  if (!ip) return ListenScope::Other;
  if (*ip == "0.0.0.0" || *ip == "::") return ListenScope::Wildcard;
  if (*ip == "::1" || ip->starts_with("127.")) return ListenScope::Loopback;
  return ListenScope::Other;
}

}  // namespace kew::config
