#pragma once
// The IP address of a connection's peer, as the slot policy (slot_policy.hpp) compares
// addresses.

#include <string>

#include <boost/asio/ip/tcp.hpp>

namespace kew::daemon {

/// The peer's IP address in canonical text form; "" when the socket has no peer (it was
/// reset before it could be asked).
inline std::string peer_address(const boost::asio::ip::tcp::socket& socket) {
  boost::system::error_code ec;
  const boost::asio::ip::tcp::endpoint peer = socket.remote_endpoint(ec);
  return ec ? std::string() : peer.address().to_string();
}

}  // namespace kew::daemon
