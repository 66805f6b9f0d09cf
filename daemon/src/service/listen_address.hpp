#pragma once
// How kewd opens its listeners: the addresses `kewd --listen-any` widens, the passive
// endpoint of a "HOST:PORT", and errors that name the listener.

#include <stdexcept>
#include <string>
#include <string_view>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <fmt/format.h>

namespace kew::daemon {

/// "127.0.0.1:4747" → "0.0.0.0:4747" (and "[::1]:P" → "[::]:P") when the operator asked
/// for every interface; other addresses were chosen on purpose and are kept.
std::string widen_if_loopback(const std::string& address);
/// The address to listen on: `configured`, widened when `listen_any`.
inline std::string listen_address(const std::string& configured, bool listen_any) {
  return listen_any ? widen_if_loopback(configured) : configured;
}

/// The endpoint to bind for "HOST:PORT"; throws config::ConfigError for a malformed
/// address, boost::system::system_error when it does not resolve.
boost::asio::ip::tcp::endpoint resolve_listen(boost::asio::io_context& io, const std::string& address);

/// Runs `open` (which binds `address`), naming the listener and its address in what it
/// throws: a bare "bind: Address already in use" does not say which port.
template <class Open>
auto open_listener(std::string_view name, std::string_view address, Open&& open) {
  try {
    return open();
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{} = \"{}\": {}", name, address, e.what()));
  }
}

}  // namespace kew::daemon
