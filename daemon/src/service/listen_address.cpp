#include "listen_address.hpp"

#include <optional>

#include "kew/config/address.hpp"

namespace kew::daemon {

std::string widen_if_loopback(const std::string& address) {
  const std::optional<config::HostPort> parsed = config::parse_host_port(address);
  if (!parsed) return address;
  if (parsed->host == "127.0.0.1" || parsed->host == "localhost") return config::to_string({"0.0.0.0", parsed->port});
  if (parsed->host == "::1") return config::to_string({"::", parsed->port});
  return address;
}

boost::asio::ip::tcp::endpoint resolve_listen(boost::asio::io_context& io, const std::string& address) {
  using boost::asio::ip::tcp;
  const config::HostPort listen = config::require_host_port(address);
  tcp::resolver resolver(io);
  return *resolver.resolve(listen.host, std::to_string(listen.port), tcp::resolver::passive).begin();
}

}  // namespace kew::daemon
