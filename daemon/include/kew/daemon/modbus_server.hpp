#pragma once
// The Modbus TCP server of the alarm register map (design §5.5, README.md, "Modbus TCP alarm map").
// libmodbus contexts are not thread-safe, so one thread owns the one context: it accepts
// clients, answers their requests from the latest published snapshot and increments the
// heartbeat register once a second. The daemon's thread only publishes copies of its
// state (under a lock) and receives acknowledgements through a callback.

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "kew/daemon/config.hpp"
#include "kew/protocol/modbus_map.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

class ModbusServer {
 public:
  /// Connections follow the rule of every listener (design §6.6, slot_policy.hpp): a
  /// client that has completed no request is silent; one address holds at most
  /// `config.silent_per_address` silent clients (one more closes its own longest-silent),
  /// and when every slot is taken a new client replaces the longest-silent client of the
  /// address holding the most, else, every slot holding an answered client, the quietest
  /// of all if quiet half of `config.idle_timeout_s`. A client that completes no request
  /// for `config.idle_timeout_s` is closed. Silent or reconnecting floods thus never lock
  /// a panel out.
  /// Out of descriptors, accepting pauses this long at first, doubling up to 1 s.
  static constexpr std::chrono::milliseconds kAcceptBackoff{100};

  /// Called with the client's "HOST:PORT" (its socket's peer; IPv6 in brackets, an
  /// IPv4-mapped address as IPv4).
  using AcknowledgeHandler = std::function<void(const std::string& client)>;

  /// Binds and listens on `config.listen` ("HOST:PORT"; port 0 binds an ephemeral port,
  /// see bound_port()). `on_acknowledge` is called on the server thread each time a client
  /// writes 1 to coil 0; it must be cheap and must not call back into this object (the
  /// daemon posts it to its own thread). A client whose address is not in a non-empty
  /// `config.acknowledge_from` may read but not write: every write is answered ILLEGAL
  /// FUNCTION, as in read-only mode, and counted ("modbus_write_not_permitted"). Throws
  /// std::runtime_error when the address is malformed, the configuration is out of range
  /// (unit_id 0–247, table_entries 0–64, max_connections ≥ 1) or the socket cannot be
  /// bound.
  ModbusServer(const ModbusConfig& config, AcknowledgeHandler on_acknowledge);
  /// Stops (see stop()).
  ~ModbusServer();
  ModbusServer(const ModbusServer&) = delete;
  ModbusServer& operator=(const ModbusServer&) = delete;

  /// Hot standby: whether this instance may still speak (SpeakingRight::may_speak),
  /// asked on the server thread before answering from a snapshot published as active.
  using SpeakingCheck = std::function<bool()>;

  /// Where the messages of refusals go (rate-limited as kew::Rejections does); called on
  /// the server thread. Set it before start().
  void set_reporter(Rejections::Reporter reporter);

  /// Set it before start(). While the snapshot served was published `as_active` and
  /// `check` says no (a stalled instance whose lease has passed to another), every request
  /// is answered SERVER DEVICE BUSY (exception 6) and counted (`modbus_not_speaking`)
  /// until a snapshot published as standby replaces it.
  void set_speaking_check(SpeakingCheck check);

  /// Spawns the server thread; the heartbeat starts at 0. A second call does nothing.
  void start();
  /// Wakes the server thread, joins it, closes every client connection and the listening
  /// socket. Final: the server cannot be started again. Returns within milliseconds.
  void stop();

  /// Replaces the served state with a copy of `snapshot`. Thread-safe; clients see it from
  /// their next request on. `as_active`: published by the active instance of a
  /// hot-standby pair (see set_speaking_check()).
  void publish(const protocol::AlarmSnapshot& snapshot, bool as_active = false);

  /// The TCP port actually bound (the configured one, or the ephemeral one for port 0).
  std::uint16_t bound_port() const;

  /// Counters and rejections since construction. Thread-safe; a copy.
  protocol::ModbusStatistics stats() const;

 private:
  class Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kew::daemon
