#include "kew/config/nats_servers.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "kew/config/address.hpp"

namespace kew::config {

namespace {

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  const auto last = text.find_last_not_of(" \t");
  return text.substr(first, last - first + 1);
}

}  // namespace

bool valid_nats_server(std::string_view url, std::string* error) {
  const auto refuse = [&](std::string_view why) {
    if (error) *error = fmt::format("\"{}\" is not a NATS server (nats://HOST:PORT): {}", url, why);
    return false;
  };
  const auto scheme_end = url.find("://");
  if (scheme_end == std::string_view::npos) return refuse("no nats:// before the host");
  const std::string_view scheme = url.substr(0, scheme_end);
  if (scheme != "nats" && scheme != "tls") return refuse(fmt::format("the scheme is {}, not nats or tls", scheme));
  std::string_view rest = url.substr(scheme_end + 3);
  // Credentials may hold ':' but not '@' (the client splits at the last '@' too).
  if (const auto at = rest.rfind('@'); at != std::string_view::npos) {
    if (at == 0) return refuse("nothing before '@'");
    rest = rest.substr(at + 1);
  }
  if (rest.find_first_of("/?# \t,") != std::string_view::npos)
    return refuse("a server is HOST:PORT, with no path, space or comma after it");
  // Without a port (no ':' after the host, or after an IPv6 address's ']'), NATS's own.
  const bool bracketed = !rest.empty() && rest.front() == '[';
  const auto close = rest.find(']');
  const bool has_port = bracketed ? close != std::string_view::npos && close + 1 < rest.size()
                                  : rest.find(':') != std::string_view::npos;
  const std::string host_port = has_port ? std::string(rest) : fmt::format("{}:{}", rest, kDefaultNatsPort);
  std::string why;
  return parse_host_port(host_port, &why) || refuse(why);
}

std::optional<std::vector<std::string>> parse_nats_servers(std::string_view text, std::string* error) {
  std::vector<std::string> servers;
  std::size_t start = 0;
  for (;;) {
    const std::size_t comma = text.find(',', start);
    const std::string_view entry = trimmed(text.substr(start, comma == std::string_view::npos ? comma : comma - start));
    if (entry.empty()) {
      if (error) *error = fmt::format("\"{}\" names no NATS server {}", text,
                                      text.empty() ? "(nats://HOST:PORT)" : "between two commas or at an end");
      return std::nullopt;
    }
    if (!valid_nats_server(entry, error)) return std::nullopt;
    servers.emplace_back(entry);
    if (comma == std::string_view::npos) return servers;
    start = comma + 1;
  }
}

std::string join_nats_servers(const std::vector<std::string>& servers) { return fmt::format("{}", fmt::join(servers, ",")); }

}  // namespace kew::config
