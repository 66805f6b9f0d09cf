#include "free_port.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <stdexcept>

namespace kew::testing {

namespace {

// Binds a socket of `type` to 127.0.0.1:port (0: the kernel picks) and returns the port
// bound, or 0 when the bind fails.
std::uint16_t bind_loopback(int type, std::uint16_t port) {
  const int fd = ::socket(AF_INET, type, 0);
  if (fd < 0) return 0;
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = htons(port);
  socklen_t length = sizeof address;
  std::uint16_t bound = 0;
  if (::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) == 0 &&
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) == 0)
    bound = ntohs(address.sin_port);
  ::close(fd);
  return bound;
}

}  // namespace

std::uint16_t free_loopback_port() {
  for (int attempt = 0; attempt < 100; ++attempt) {
    const std::uint16_t port = bind_loopback(SOCK_STREAM, 0);
    if (port != 0 && bind_loopback(SOCK_DGRAM, port) == port) return port;
  }
  throw std::runtime_error("no free loopback port");
}

std::string free_loopback_address() { return "127.0.0.1:" + std::to_string(free_loopback_port()); }

}  // namespace kew::testing
