// The checks of a kewd configuration that need more than one key, or the file system
// (design §5.7): listen addresses, distinct ports, writable output files.
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <map>
#include <tuple>

#include <fmt/format.h>

#include "kew/config/address.hpp"
#include "kew/daemon/config.hpp"

namespace kew::daemon {

namespace {

namespace fs = std::filesystem;
using config::ConfigError;

[[noreturn]] void refuse(const Config& c, std::string_view message) {
  throw ConfigError(fmt::format("{}: {}", c.origin.empty() ? "the built-in configuration" : c.origin, message));
}

void check_listen_address(const Config& c, const Listener& l, bool listen_any) {
  if (l.allow_remote || listen_any) return;
  const config::HostPort address = config::require_host_port(l.address);
  const config::ListenScope scope = config::listen_scope(address.host);
  if (scope == config::ListenScope::Loopback) return;
  refuse(c, fmt::format("{} = \"{}\" {}: listeners bind loopback unless their table says allow_remote = true "
                        "or kewd runs with --listen-any",
                        l.name, l.address,
                        scope == config::ListenScope::Wildcard ? "listens on every interface"
                                                               : "is not a loopback address"));
}

void check_distinct_ports(const Config& c, const std::vector<Listener>& all) {
  // (UDP?, IPv6?, port) → the first listener that took it. A name counts as IPv4.
  std::map<std::tuple<bool, bool, std::uint16_t>, const Listener*> taken;
  for (const Listener& l : all) {
    const config::HostPort address = config::require_host_port(l.address);
    const bool v6 = address.host.find(':') != std::string::npos;
    const auto [it, fresh] = taken.emplace(std::tuple(l.udp, v6, address.port), &l);
    if (!fresh)
      refuse(c, fmt::format("{} = \"{}\" uses {} port {} ({}), as {} = \"{}\" does", l.name, l.address,
                            l.udp ? "UDP" : "TCP", address.port, v6 ? "IPv6" : "IPv4", it->second->name,
                            it->second->address));
  }
}

/// `path` is a file kewd appends to; `renames`: it also renames and removes it (rotation).
void check_writable(const Config& c, std::string_view key, const std::string& path, bool renames) {
  if (path.empty()) return;
  const auto fail = [&](std::string_view why) { refuse(c, fmt::format("{} = \"{}\" {}", key, path, why)); };
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) fail("is a directory");
  const fs::path directory = fs::path(path).parent_path();
  if (!fs::is_directory(directory, ec))
    fail(fs::exists(directory, ec) ? fmt::format("cannot be created: {} is not a directory", directory.string())
                                   : fmt::format("cannot be created: its directory {} does not exist", directory.string()));
  const bool exists = fs::exists(status);
  if (exists && !fs::is_regular_file(status) && !fs::is_character_file(status) && !fs::is_fifo(status))
    fail("is not a file kewd can append to");
  if (exists && ::access(path.c_str(), W_OK) != 0) fail(fmt::format("cannot be written: {}", std::strerror(errno)));
  if ((renames || !exists) && ::access(directory.c_str(), W_OK | X_OK) != 0)
    fail(fmt::format("cannot be {}: its directory {}: {}", exists ? "rotated" : "created", directory.string(),
                     std::strerror(errno)));
}

/// kewd creates the state directory when it is missing (a plain run; systemd creates
/// StateDirectory=kew), so its parent must exist then.
void check_state_directory(const Config& c) {
  const std::string directory = state_directory(c.service);
  if (directory.empty()) return;
  const auto fail = [&](std::string_view why) {
    refuse(c, fmt::format("[service] state_directory = \"{}\" {}", directory, why));
  };
  std::error_code ec;
  const fs::file_status status = fs::status(directory, ec);
  if (fs::exists(status) && !fs::is_directory(status)) fail("is not a directory");
  const fs::path existing = fs::exists(status) ? fs::path(directory) : fs::path(directory).parent_path();
  if (!fs::is_directory(existing, ec))
    fail(fmt::format("cannot be created: {} does not exist", existing.string()));
  if (::access(existing.c_str(), W_OK | X_OK) != 0)
    fail(fmt::format("cannot be {}: {}", fs::exists(status) ? "written" : "created", std::strerror(errno)));
}

}  // namespace

std::vector<Listener> listeners(const Config& c) {
  std::vector<Listener> all;
  all.push_back({"[service] alert_listen", c.service.alert_listen, false, c.service.allow_remote});
  if (c.modbus.enabled) all.push_back({"[modbus] listen", c.modbus.listen, false, c.modbus.allow_remote});
  if (c.http.enabled) all.push_back({"[http] listen", c.http.listen, false, c.http.allow_remote});
  for (std::size_t i = 0; i < c.inputs.size(); ++i) {
    const InputConfig& in = c.inputs[i];
    if (in.transport != Transport::Udp && in.transport != Transport::TcpServer) continue;
    all.push_back({fmt::format("[input {}] address", i + 1), in.address, in.transport == Transport::Udp,
                   in.allow_remote});
  }
  return all;
}

void check_config(const Config& c, bool listen_any) {
  const std::vector<Listener> all = listeners(c);
  for (const Listener& l : all) check_listen_address(c, l, listen_any);
  check_distinct_ports(c, all);
  check_writable(c, "[service] alert_log", c.service.alert_log, true);
  check_writable(c, "[service] record_file", c.service.record_file, false);
  check_state_directory(c);
  if (!c.service.alert_log.empty() && c.service.alert_log == c.service.record_file)
    refuse(c, fmt::format("[service] record_file = \"{}\" is the alert log too: give each its own file",
                          c.service.record_file));
}

}  // namespace kew::daemon
