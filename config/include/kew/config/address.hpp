#pragma once
// The one reader of "HOST:PORT" for every tool and every configuration key: kewd's
// listeners, inputs and CAT004 destination, kew-replay --to, kew-watch.

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace kew::config {

struct HostPort {
  std::string host;        ///< a name, an IPv4 address, or an IPv6 address without brackets
  std::uint16_t port = 0;  ///< 1–65535
  bool operator==(const HostPort&) const = default;
};

/// Parses "HOST:PORT". HOST is a name or an IPv4 address, or an IPv6 address in brackets
/// ("[::1]:4747"; a bare IPv6 address is refused, since its last group would read as the
/// port). PORT is decimal, 1–65535: port 0 is refused everywhere, as a listener on it
/// would be unreachable at an unknown port and a destination on it does not exist.
/// Returns nullopt when malformed, with `*error` (when given) set to a message that
/// quotes the text and says what is wrong.
std::optional<HostPort> parse_host_port(std::string_view text, std::string* error = nullptr);

/// parse_host_port for an address that was already checked when its configuration was
/// read (or that came from code, as in tests): throws ConfigError with the message
/// instead of returning nullopt.
HostPort require_host_port(std::string_view text);

/// "host:port", or "[host]:port" when host is an IPv6 address: what parse_host_port reads.
std::string to_string(const HostPort& address);

/// An IPv4 or IPv6 address (no brackets, no port) in its canonical text ("::0001" →
/// "::1"; an IPv4-mapped IPv6 address → its IPv4 form, as a dual-stack socket reports an
/// IPv4 peer), or nullopt when `text` is no address. Names are not resolved.
std::optional<std::string> canonical_ip(std::string_view text);

/// Where a listener bound to `host` can be reached from. Only literal addresses and
/// "localhost" count as loopback: any other name may resolve to an external address.
enum class ListenScope {
  Loopback,  ///< 127.0.0.0/8, ::1, "localhost": this machine only
  Wildcard,  ///< 0.0.0.0 or ::: every interface
  Other,     ///< an interface address, a multicast group or a name: reachable from outside
};
ListenScope listen_scope(std::string_view host);

}  // namespace kew::config
