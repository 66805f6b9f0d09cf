#include "libmodbus_context.hpp"

#include <fcntl.h>
#include <modbus.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace kew::daemon {
namespace {

bool set_nonblocking(int fd) {
  const int flags = fcntl(fd, F_GETFL, 0);
  return flags >= 0 && fcntl(fd, F_SETFL, flags | O_NONBLOCK) == 0;
}

std::uint16_t local_port(int fd) {
  sockaddr_storage address{};
  socklen_t length = sizeof address;
  if (getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) return 0;
  if (address.ss_family == AF_INET) {
    return ntohs(reinterpret_cast<const sockaddr_in*>(&address)->sin_port);
  }
  if (address.ss_family == AF_INET6) {
    return ntohs(reinterpret_cast<const sockaddr_in6*>(&address)->sin6_port);
  }
  return 0;
}

std::runtime_error listen_error(const std::string& host, std::uint16_t port, const char* what) {
  return std::runtime_error("modbus: cannot listen on " + host + ":" + std::to_string(port) + ": " +
                            what);
}

}  // namespace

LibmodbusContext::LibmodbusContext(const std::string& host, std::uint16_t port, int backlog,
                                   std::size_t registers) {
  // The "pi" (protocol independent) variant resolves the host with getaddrinfo, so IPv6
  // listen addresses work as well as IPv4 ones.
  ctx_ = modbus_new_tcp_pi(host.c_str(), std::to_string(port).c_str());
  if (ctx_ == nullptr) throw listen_error(host, port, std::strerror(errno));
  const int nb_registers = static_cast<int>(registers);
  mapping_ = modbus_mapping_new_start_address(0, static_cast<int>(protocol::kModbusCoilCount), 0,
                                              static_cast<int>(protocol::kModbusDiscreteInputCount),
                                              0, nb_registers, 0, nb_registers);
  if (mapping_ == nullptr) {
    modbus_free(ctx_);
    throw listen_error(host, port, "cannot allocate the register map");
  }
  listen_fd_ = modbus_tcp_pi_listen(ctx_, backlog);
  if (listen_fd_ < 0 || !set_nonblocking(listen_fd_)) {
    const int error = errno;
    if (listen_fd_ >= 0) ::close(listen_fd_);
    modbus_mapping_free(mapping_);
    modbus_free(ctx_);
    throw listen_error(host, port, std::strerror(error));
  }
  bound_port_ = local_port(listen_fd_);
}

LibmodbusContext::~LibmodbusContext() {
  close_listener();
  modbus_mapping_free(mapping_);
  // Not modbus_close(): the context's socket is whichever client was served last, and
  // the server closes its clients itself.
  modbus_free(ctx_);
}

void LibmodbusContext::close_listener() {
  if (listen_fd_ >= 0) ::close(listen_fd_);
  listen_fd_ = -1;
}

int LibmodbusContext::accept_client() {
  if (listen_fd_ < 0) return -1;
  int listener = listen_fd_;
  // accept4 inherits nothing on Linux: the client socket is made non-blocking here so
  // that a reply to a client that stopped reading fails instead of stalling the thread.
  const int fd = modbus_tcp_pi_accept(ctx_, &listener);
  if (fd < 0) return -1;
  if (!set_nonblocking(fd)) {
    ::close(fd);
    return -1;
  }
  return fd;
}

void LibmodbusContext::load(const protocol::RegisterMap& map) {
  const auto inputs = std::min<std::size_t>(map.discrete_inputs.size(),
                                            static_cast<std::size_t>(mapping_->nb_input_bits));
  std::fill_n(mapping_->tab_input_bits, mapping_->nb_input_bits, 0);
  std::copy_n(map.discrete_inputs.begin(), inputs, mapping_->tab_input_bits);

  const auto registers = std::min<std::size_t>(
      map.input_registers.size(), static_cast<std::size_t>(mapping_->nb_input_registers));
  std::fill_n(mapping_->tab_input_registers, mapping_->nb_input_registers, 0);
  std::copy_n(map.input_registers.begin(), registers, mapping_->tab_input_registers);
  std::copy_n(mapping_->tab_input_registers, mapping_->nb_registers, mapping_->tab_registers);

  std::fill_n(mapping_->tab_bits, mapping_->nb_bits, 0);
}

bool LibmodbusContext::reply(int fd, std::span<const std::uint8_t> adu) {
  modbus_set_socket(ctx_, fd);
  const int sent = modbus_reply(ctx_, adu.data(), static_cast<int>(adu.size()), mapping_);
  // Coil 0 is a push button: it never holds the value written.
  std::fill_n(mapping_->tab_bits, mapping_->nb_bits, 0);
  return sent > 0;
}

bool LibmodbusContext::reply_exception(int fd, std::span<const std::uint8_t> adu,
                                       protocol::ModbusException code) {
  modbus_set_socket(ctx_, fd);
  return modbus_reply_exception(ctx_, adu.data(), static_cast<unsigned>(code)) > 0;
}

}  // namespace kew::daemon
