#include "test_modbus_support.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <thread>

#include "free_port.hpp"

namespace kew::test {
namespace {

constexpr auto kWaitLimit = std::chrono::seconds(5);

AlertEvent alert(std::uint16_t number, Severity severity, AlertState state, double t_los_s,
                 std::uint16_t track_a, std::uint16_t track_b, double cpa_h_m, double cpa_v_ft) {
  AlertEvent e;
  e.id = "alert-" + std::to_string(number);
  e.number = number;
  e.severity = severity;
  e.state = state;
  e.t_los_s = t_los_s;
  e.a.track_number = track_a;
  e.b.track_number = track_b;
  e.cpa_h_m = cpa_h_m;
  e.cpa_v_ft = cpa_v_ft;
  return e;
}

int remaining_ms(std::chrono::steady_clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
      deadline - std::chrono::steady_clock::now());
  return static_cast<int>(std::max<long>(left.count(), 0));
}

}  // namespace

protocol::AlarmSnapshot known_snapshot() {
  protocol::AlarmSnapshot s;
  s.active = {
      alert(11, Severity::Caution, AlertState::Update, 95.4, 101, 102, 3210.0, 800.0),
      alert(12, Severity::Loss, AlertState::New, 0.0, 103, 104, 1200.0, 300.0),
      alert(13, Severity::Warning, AlertState::New, 44.6, 105, 40000, 5049.0, 0.0),
  };
  s.live_tracks = 57;
  s.seconds_since_last_record = 3.2;
  s.feed_healthy = true;
  s.degraded = false;
  s.uptime_s = 123456;  // 0x0001'E240
  s.unacknowledged = 2;
  return s;
}

std::vector<std::uint16_t> expected_registers() {
  return {1, 3, 3, 57, 3, 0, 1, 0xE240, 2, 0, 0, 0, 0, 0, 0, 0,
          // The loss first, then the warning, then the caution; one empty row.
          12, 3, 103, 104, 0, 120, 30, 1,
          13, 2, 105, 40000, 45, 505, 0, 1,
          11, 1, 101, 102, 95, 321, 80, 2,
          0, 0, 0, 0, 0, 0, 0, 0};
}

RunningServer::RunningServer(bool read_only, int max_connections, int unit_id,
                             std::vector<std::string> acknowledge_from) {
  daemon::ModbusConfig config;
  config.enabled = true;
  config.listen = kew::testing::free_loopback_address();
  config.unit_id = unit_id;
  config.table_entries = kTableEntries;
  config.read_only = read_only;
  config.max_connections = max_connections;
  config.acknowledge_from = std::move(acknowledge_from);
  server = std::make_unique<daemon::ModbusServer>(
      config, [count = acknowledgements, by = acknowledged_by](const std::string& client) {
        by->add(client);
        ++*count;
      });
  server->publish(known_snapshot());
  server->start();
}

RawClient::RawClient(std::uint16_t port) {
  fd_ = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_port = htons(port);
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0) close();
}

RawClient::~RawClient() { close(); }

void RawClient::close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

void RawClient::send(const std::vector<std::uint8_t>& bytes) {
  ASSERT_EQ(::send(fd_, bytes.data(), bytes.size(), MSG_NOSIGNAL), static_cast<ssize_t>(bytes.size()));
}

std::vector<std::uint8_t> RawClient::receive(std::size_t count) {
  std::vector<std::uint8_t> out;
  const auto deadline = std::chrono::steady_clock::now() + kWaitLimit;
  while (out.size() < count) {
    pollfd p{fd_, POLLIN, 0};
    if (::poll(&p, 1, remaining_ms(deadline)) <= 0) break;
    std::array<std::uint8_t, 512> buffer;
    const ssize_t n = ::recv(fd_, buffer.data(), std::min(buffer.size(), count - out.size()), 0);
    if (n <= 0) break;
    out.insert(out.end(), buffer.begin(), buffer.begin() + n);
  }
  return out;
}

bool RawClient::closed_by_peer() {
  pollfd p{fd_, POLLIN, 0};
  if (::poll(&p, 1, static_cast<int>(std::chrono::milliseconds(kWaitLimit).count())) <= 0) return false;
  std::uint8_t byte = 0;
  return ::recv(fd_, &byte, 1, 0) <= 0;
}

CommandResult run_command(const std::string& command) {
  CommandResult result;
  FILE* pipe = ::popen((command + " 2>&1").c_str(), "r");
  if (pipe == nullptr) return result;
  std::array<char, 4096> buffer;
  for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;) {
    result.output.append(buffer.data(), n);
  }
  const int status = ::pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

bool wait_for(const std::function<bool()>& condition) {
  const auto deadline = std::chrono::steady_clock::now() + kWaitLimit;
  while (!condition()) {
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return true;
}

std::optional<std::string> python_with_pymodbus() {
  // Debian's python3-pymodbus lives in the system interpreter, which a PATH python3
  // (pyenv, virtualenv) may not be.
  for (const std::string candidate : {"/usr/bin/python3", "python3"}) {
    if (run_command(candidate + " -c 'import pymodbus.client'").exit_code == 0) return candidate;
  }
  return std::nullopt;
}

bool have_mbpoll() { return run_command("command -v mbpoll").exit_code == 0; }

CommandResult modbus_client(const std::string& python, std::uint16_t port, const std::string& arguments) {
  return run_command(python + " '" KEW_MODBUS_CLIENT_SCRIPT "' --port " + std::to_string(port) + " " +
                     arguments);
}

// Hand-written scanners rather than std::regex: GCC 12's <regex> trips
// -Wmaybe-uninitialized under the sanitizer build.

std::vector<long> json_values(const std::string& output) {
  std::vector<long> values;
  const std::string key = "\"values\": [";
  const auto begin = output.find(key);
  if (begin == std::string::npos) return values;
  const auto end = output.find(']', begin);
  std::istringstream list(output.substr(begin + key.size(), end - begin - key.size()));
  for (std::string item; std::getline(list, item, ',');) values.push_back(std::stol(item));
  return values;
}

std::string json_client(const std::string& output) {
  const std::string key = "\"client\": \"";
  const auto at = output.find(key);
  if (at == std::string::npos) return {};
  const auto start = at + key.size();
  return output.substr(start, output.find('"', start) - start);
}

int json_exception_code(const std::string& output) {
  const std::string key = "\"exception_code\": ";
  const auto at = output.find(key);
  return at == std::string::npos ? -1 : std::stoi(output.substr(at + key.size()));
}

std::map<int, long> mbpoll_values(const std::string& output) {
  std::map<int, long> values;
  std::istringstream lines(output);
  for (std::string line; std::getline(lines, line);) {
    int reference = 0;
    long value = 0;
    if (std::sscanf(line.c_str(), "[%d]: %ld", &reference, &value) == 2) values[reference] = value;
  }
  return values;
}

}  // namespace kew::test
