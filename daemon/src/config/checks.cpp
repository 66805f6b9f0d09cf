// The checks of a kewd configuration that need more than one key, or the file system
// (design §5.7): listen addresses, distinct ports, writable output files, readable secrets.
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

/// The configuration being checked, with what the check accepts on trust.
struct Check {
  const Config& config;
  const CheckOptions& options;
  std::vector<std::string> notes;

  /// `directory` is missing, systemd creates it before kewd starts, and it can (its
  /// parent exists): noted, with `key` and `value` the setting that needs it.
  bool left_to_systemd(const fs::path& directory, std::string_view key, const std::string& value) {
    const fs::path normal = directory.lexically_normal();
    bool listed = false;
    for (const std::string& d : options.created_by_systemd) listed = listed || fs::path(d).lexically_normal() == normal;
    std::error_code ec;
    if (!listed || fs::exists(fs::symlink_status(normal, ec)) || !fs::is_directory(normal.parent_path(), ec))
      return false;
    notes.push_back(fmt::format("{} = \"{}\": {} does not exist yet; systemd creates it when kewd.service starts",
                                key, value, normal.string()));
    return true;
  }
};

/// `path` is a file kewd appends to; `renames`: it also renames and removes it (rotation).
void check_writable(Check& check, std::string_view key, const std::string& path, bool renames) {
  const Config& c = check.config;
  if (path.empty()) return;
  const auto fail = [&](std::string_view why) { refuse(c, fmt::format("{} = \"{}\" {}", key, path, why)); };
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) fail("is a directory");
  const fs::path directory = fs::path(path).parent_path();
  if (check.left_to_systemd(directory, key, path)) return;
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
void check_state_directory(Check& check) {
  const Config& c = check.config;
  const std::string directory = state_directory(c.service);
  if (directory.empty()) return;
  if (check.left_to_systemd(directory, "[service] state_directory", directory)) return;
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

/// A file kewd reads at start (`table` and `key` name the setting): a regular file it
/// can read.
void check_readable_file(const Config& c, std::string_view table, std::string_view key, const std::string& path) {
  if (path.empty()) return;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) refuse(c, fmt::format("[{}] {} = \"{}\" is not a file", table, key, path));
  if (::access(path.c_str(), R_OK) != 0)
    refuse(c, fmt::format("[{}] {} = \"{}\" cannot be read: {}", table, key, path, std::strerror(errno)));
}

/// An http input's secret, credentials and certificate files, and a notifier's URL, token
/// and certificate files.
void check_secret_files(const Config& c) {
  for (std::size_t i = 0; i < c.inputs.size(); ++i) {
    const InputConfig& in = c.inputs[i];
    const std::string table = fmt::format("input {}", i + 1);
    check_readable_file(c, table, "secret_file", in.secret_file);
    check_readable_file(c, table, "credentials_file", in.credentials_file);
    check_readable_file(c, table, "ca_file", in.ca_file);
  }
  for (const NotifyConfig& n : c.notify) {
    const std::string table = "notify " + n.name;
    check_readable_file(c, table, "url_file", n.url_file);
    check_readable_file(c, table, "token_file", n.token_file);
    check_readable_file(c, table, "ca_file", n.ca_file);
  }
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

std::vector<std::string> systemd_directories() { return {KEW_SYSTEMD_LOGS_DIRECTORY, KEW_SYSTEMD_STATE_DIRECTORY}; }

std::vector<std::string> check_config(const Config& c, const CheckOptions& options) {
  const std::vector<Listener> all = listeners(c);
  for (const Listener& l : all) check_listen_address(c, l, options.listen_any);
  check_distinct_ports(c, all);
  Check check{c, options, {}};
  check_writable(check, "[service] alert_log", c.service.alert_log, true);
  check_writable(check, "[service] record_file", c.service.record_file, false);
  check_state_directory(check);
  check_secret_files(c);
  if (!c.service.alert_log.empty() && c.service.alert_log == c.service.record_file)
    refuse(c, fmt::format("[service] record_file = \"{}\" is the alert log too: give each its own file",
                          c.service.record_file));
  return std::move(check.notes);
}

}  // namespace kew::daemon
