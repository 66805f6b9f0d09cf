#pragma once
// Support for the Modbus server integration tests: a server on an ephemeral loopback
// port serving a known snapshot, raw TCP sockets, subprocess clients, bounded waits.

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "kew/daemon/modbus_server.hpp"

namespace kew::test {

/// The snapshot every test serves, and the registers it must produce (heartbeat excepted).
protocol::AlarmSnapshot known_snapshot();
/// Input registers 0–15 then 4 table rows, for known_snapshot() with table_entries = 4;
/// register 5 (heartbeat) is set to 0 and must be skipped when comparing.
std::vector<std::uint16_t> expected_registers();
inline constexpr int kTableEntries = 4;

/// The clients ("HOST:PORT") that acknowledged, in order; written on the server thread.
class AcknowledgingClients {
 public:
  void add(const std::string& client) {
    std::lock_guard lock(mutex_);
    clients_.push_back(client);
  }
  std::vector<std::string> list() const {
    std::lock_guard lock(mutex_);
    return clients_;
  }

 private:
  mutable std::mutex mutex_;
  std::vector<std::string> clients_;
};

/// A ModbusServer on 127.0.0.1, ephemeral port, serving known_snapshot(), counting
/// acknowledgements and keeping who made them.
struct RunningServer {
  explicit RunningServer(bool read_only = false, int max_connections = 4, int unit_id = 1,
                         std::vector<std::string> acknowledge_from = {});
  std::uint16_t port() const { return server->bound_port(); }

  std::shared_ptr<std::atomic<int>> acknowledgements = std::make_shared<std::atomic<int>>(0);
  std::shared_ptr<AcknowledgingClients> acknowledged_by = std::make_shared<AcknowledgingClients>();
  std::unique_ptr<daemon::ModbusServer> server;
};

/// A connected TCP socket to 127.0.0.1:port (closed on destruction).
class RawClient {
 public:
  explicit RawClient(std::uint16_t port);
  ~RawClient();
  RawClient(const RawClient&) = delete;
  RawClient& operator=(const RawClient&) = delete;

  bool connected() const { return fd_ >= 0; }
  void send(const std::vector<std::uint8_t>& bytes);
  /// Exactly `count` bytes, waiting up to 5 s; fewer when the peer closed or time ran out.
  std::vector<std::uint8_t> receive(std::size_t count);
  /// True when the server closed the connection within 5 s (no data expected).
  bool closed_by_peer();
  void close();

 private:
  int fd_ = -1;
};

/// Output (stdout and stderr together) and exit status of a shell command.
struct CommandResult {
  int exit_code = -1;
  std::string output;
};
CommandResult run_command(const std::string& command);

/// Waits (up to 5 s, polling) for `condition`; returns its final value.
bool wait_for(const std::function<bool()>& condition);

/// The python interpreter that can import pymodbus, or nothing.
std::optional<std::string> python_with_pymodbus();
bool have_mbpoll();

/// Runs tests/daemon/modbus_client.py with `arguments` against `port`.
CommandResult modbus_client(const std::string& python, std::uint16_t port, const std::string& arguments);
/// The "values" array of the client's JSON output (empty when absent).
std::vector<long> json_values(const std::string& output);
/// The "client" of the client's JSON output (its own "HOST:PORT"), or "".
std::string json_client(const std::string& output);
/// The "exception_code" of the client's JSON output, or −1.
int json_exception_code(const std::string& output);

/// mbpoll's "[ref]: value" lines: reference → unsigned value.
std::map<int, long> mbpoll_values(const std::string& output);

}  // namespace kew::test
