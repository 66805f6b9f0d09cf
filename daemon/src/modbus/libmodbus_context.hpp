#pragma once
// The one libmodbus context of the Modbus server, and the only code that calls libmodbus.
// Not thread-safe (libmodbus is not): owned and used by the server thread alone, after
// construction.

#include <cstdint>
#include <span>
#include <string>

#include "kew/protocol/modbus_map.hpp"

struct _modbus;
struct _modbus_mapping_t;

namespace kew::daemon {

class LibmodbusContext {
 public:
  /// Listens on host:port (port 0: ephemeral) with a backlog of `backlog` connections;
  /// the map holds `registers` input registers and as many holding registers.
  /// Throws std::runtime_error naming the address and the system error when it cannot.
  LibmodbusContext(const std::string& host, std::uint16_t port, int backlog, std::size_t registers);
  ~LibmodbusContext();
  LibmodbusContext(const LibmodbusContext&) = delete;
  LibmodbusContext& operator=(const LibmodbusContext&) = delete;

  /// Non-blocking listening socket (for poll), or −1 once closed.
  int listen_fd() const { return listen_fd_; }
  std::uint16_t bound_port() const { return bound_port_; }
  void close_listener();

  /// Accepts one pending connection: its socket (non-blocking, close-on-exec; the caller
  /// owns it), or −1 when none is pending.
  int accept_client();

  /// Copies `map` into the served tables (holding registers mirror the input registers;
  /// the coil reads 0). Tables larger than the context's are cut, smaller ones leave the
  /// rest zero.
  void load(const protocol::RegisterMap& map);

  /// Answers `adu`, a request the caller has checked (check_modbus_request) on client
  /// socket `fd`. Coil writes are echoed and the coil reset to 0. False when the reply
  /// could not be sent whole (the caller drops the client).
  bool reply(int fd, std::span<const std::uint8_t> adu);
  /// Answers `adu` with an exception response. False when it could not be sent.
  bool reply_exception(int fd, std::span<const std::uint8_t> adu, protocol::ModbusException code);

 private:
  _modbus* ctx_ = nullptr;
  _modbus_mapping_t* mapping_ = nullptr;
  int listen_fd_ = -1;
  std::uint16_t bound_port_ = 0;
};

}  // namespace kew::daemon
