// kewd (design §5.6): the kew service. Without -N it forks into the background and logs
// to syslog; under systemd (Type=notify) it runs with -N and logs to the journal.

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <spdlog/spdlog.h>

#include "logging.hpp"
#include "service.hpp"
#include "kew/config/address.hpp"
#include "kew/config/nats_servers.hpp"
#include "kew/daemon/config.hpp"
#include "kew/protocol/formats.hpp"
#include "kew/protocol/version.hpp"
#include "kew/replay/recording_reader.hpp"
#include "kew/util/units.hpp"

namespace {

constexpr int kUsageError = 64;   // EX_USAGE: bad flags or configuration
constexpr int kStartFailed = 1;
constexpr const char* kSystemConfig = KEW_SYSTEM_CONFIG;  // set by CMake from the install prefix

/// One line of --check-config per region (design §4.8): its shape, band and effect.
std::string describe(const kew::region::Region& r) {
  std::string text = r.polygon.empty() ? fmt::format("circle of {} NM", r.radius_m / kew::units::kMetresPerNauticalMile)
                                       : fmt::format("polygon of {} vertices", r.polygon.size());
  const kew::region::Region unbounded;
  if (r.floor_ft != unbounded.floor_ft) text += fmt::format(", from {} ft", r.floor_ft);
  if (r.ceiling_ft != unbounded.ceiling_ft) text += fmt::format(", below {} ft", r.ceiling_ft);
  if (r.inhibit) return text + ", inhibits alerts";
  const kew::region::RegionParameters& p = r.parameters;
  std::vector<std::string> set;
  if (p.horizontal_m) set.push_back(fmt::format("horizontal {} NM", *p.horizontal_m / kew::units::kMetresPerNauticalMile));
  if (p.vertical_m) set.push_back(fmt::format("vertical {} ft", *p.vertical_m / kew::units::kMetresPerFoot));
  if (p.lookahead_s) set.push_back(fmt::format("look-ahead {} s", *p.lookahead_s));
  if (p.warning_s) set.push_back(fmt::format("warning {} s", *p.warning_s));
  if (p.confirm) set.push_back(fmt::format("confirm {}", *p.confirm));
  if (p.clear) set.push_back(fmt::format("clear {}", *p.clear));
  return text + (set.empty() ? ", the default parameters" : fmt::format(", {}", fmt::join(set, ", ")));
}

struct Flags {
  std::string config_path;
  bool foreground = false;
  bool listen_any = false;
  bool check_config = false;
  std::string log_level;
  // --replay FILE (design §5.6)
  kew::daemon::ReplaySettings replay;
  bool max_speed = false;
  bool exit_at_end = false;
};

constexpr const char* kFooter = R"(Watching a recording:
  kewd --replay FILE [--speed X | --max-speed] [--format F] [-c FILE] [--exit-at-end]
       [--alert-listen HOST:PORT] [--http-listen HOST:PORT] [--alert-log FILE]
replays FILE (any recording kew-replay reads) through kewd, paced by its data time at X
times the recorded speed, with the alert stream on loopback; nothing to configure and no
file written. It stays in the foreground and keeps serving the last state after the file
ends (logging "replay of FILE ended") until SIGINT or SIGTERM, or exits with
--exit-at-end. Without -c it uses the built-in defaults (not the installed file). With
-c, the file's shared tables ([projection], [tracks], [kinetic], [probe], [alerts],
[eligibility], [decoding], [[radar]], [[region]], [regions]) and its [service] limits
apply; its [[input]] tables are replaced by FILE; CAT004, Modbus, the record file, the
state directory and the alert log are off (--alert-log asks for one); every listener
must be on loopback (--listen-any is refused). Data times are not checked against the
wall clock ([service] max_future_s): a replay's clock is the recording's.)";

/// Detaches from the terminal. Returns in the daemon process with the write end of a
/// pipe on which it reports readiness; the original process waits for that report so
/// that a daemon that cannot start (port in use) fails the command that started it.
int daemonize() {
  int ready[2];
  if (::pipe(ready) != 0) {
    std::perror("kewd: pipe");
    std::exit(kStartFailed);
  }
  const pid_t child = ::fork();
  if (child < 0) {
    std::perror("kewd: fork");
    std::exit(kStartFailed);
  }
  if (child > 0) {
    ::close(ready[1]);
    char status = 1;
    const bool started = ::read(ready[0], &status, 1) == 1 && status == 0;
    std::exit(started ? 0 : kStartFailed);
  }
  ::close(ready[0]);
  ::setsid();
  // A second fork: the daemon is not a session leader and cannot reacquire a terminal.
  const pid_t grandchild = ::fork();
  if (grandchild < 0) std::exit(kStartFailed);
  if (grandchild > 0) std::_Exit(0);
  ::umask(022);
  const int null = ::open("/dev/null", O_RDWR);
  if (null >= 0) {
    ::dup2(null, STDIN_FILENO);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    if (null > STDERR_FILENO) ::close(null);
  }
  return ready[1];
}

void report_ready(int fd, bool ok) {
  if (fd < 0) return;
  const char status = ok ? 0 : 1;
  [[maybe_unused]] const auto written = ::write(fd, &status, 1);
  ::close(fd);
}

}  // namespace

int main(int argc, char** argv) {
  Flags flags;
  CLI::App app{"kewd: kinetic early warning of losses of separation between aircraft"};
  app.set_version_flag("--version", kew::protocol::version_line("kewd"));
  app.add_option("-c,--config", flags.config_path,
                 std::string("configuration file (default: ") + kSystemConfig + " if present, else built-in defaults)")
      ->check(CLI::ExistingFile);
  app.add_flag("-N,--foreground", flags.foreground, "stay in the foreground and log to stderr (systemd, terminals)");
  app.add_flag("--listen-any", flags.listen_any,
               "serve subscribers, Modbus and loopback inputs on every interface, and allow any listen address");
  app.add_flag("--check-config", flags.check_config, "validate the configuration, then exit 0, or 64 on error");
  app.add_option("-l,--log-level", flags.log_level,
                 "one of " + kew::daemon::kLogLevelNames.list() + " (overrides the file)")
      ->check(CLI::IsMember(kew::daemon::kLogLevelNames.names()));
  auto* replay = app.add_option("--replay", flags.replay.file,
                                "replay a recording with a built-in configuration on loopback (below)")
                     ->check(CLI::Validator([](std::string& path) { return kew::replay::recording_path_problem(path); }, "RECORDING"))
                     ->excludes("--listen-any");
  // Every format but the live-only asterix-datagram, as kew-replay.
  const auto file_formats = {kew::protocol::Format::AsterixDatagram};
  std::string format = "auto";
  app.add_option("--format", format, "with --replay: the recording's format (auto: detected, as kew-replay)")
      ->check(CLI::IsMember(kew::protocol::kFormatNames.names(file_formats)))
      ->needs(replay)
      ->capture_default_str();
  auto* speed = app.add_option("--speed", flags.replay.speed, "with --replay: multiple of recorded speed")
                    ->check(CLI::Range(0.001, 1000.0))
                    ->needs(replay)
                    ->capture_default_str();
  app.add_flag("--max-speed", flags.max_speed, "with --replay: as fast as kewd takes it")->excludes(speed)->needs(replay);
  app.add_flag("--exit-at-end", flags.exit_at_end, "with --replay: exit 0 when the file ends")->needs(replay);
  app.add_option("--alert-listen", flags.replay.alert_listen,
                 "with --replay: the alert stream's loopback HOST:PORT (default: alert_listen, 127.0.0.1:4747)")
      ->needs(replay);
  app.add_option("--http-listen", flags.replay.http_listen,
                 "with --replay: the map and HTTP API's loopback HOST:PORT (default: [http] listen, 127.0.0.1:8747)")
      ->needs(replay);
  app.add_option("--alert-log", flags.replay.alert_log, "with --replay: write the alert log here (default: none)")
      ->needs(replay);
  app.footer(kFooter);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : kUsageError;
  }

  const bool replaying = !flags.replay.file.empty();
  // A replay is reproducible from its command line: the installed file only when named.
  if (!replaying && flags.config_path.empty() && std::filesystem::exists(kSystemConfig))
    flags.config_path = kSystemConfig;
  kew::daemon::Config config;
  try {
    config = flags.config_path.empty() ? kew::daemon::default_config() : kew::daemon::load_config(flags.config_path);
    if (replaying) {
      flags.replay.format = *kew::protocol::kFormatNames.parse(format);
      if (flags.max_speed) flags.replay.speed = 0.0;
      if (!flags.replay.alert_listen.empty()) kew::config::require_host_port(flags.replay.alert_listen);
      if (!flags.replay.http_listen.empty()) kew::config::require_host_port(flags.replay.http_listen);
      kew::daemon::apply_replay(config, flags.replay);
    }
  } catch (const kew::config::ConfigError& e) {
    std::fprintf(stderr, "kewd: %s\n", e.what());
    return kUsageError;
  }
  std::vector<std::string> notes;
  try {
    // Before starting as well: a file that passes --check-config must not fail at start.
    // The check alone trusts systemd to create the unit's directories (the package's
    // configuration is checked before the service ever ran); kewd about to start does not.
    kew::daemon::CheckOptions check;
    check.listen_any = flags.listen_any;
    if (flags.check_config) check.created_by_systemd = kew::daemon::systemd_directories();
    notes = kew::daemon::check_config(config, check);
  } catch (const kew::config::ConfigError& e) {
    // The check names allow_remote and --listen-any, which a replay overrides and refuses.
    const bool listener = std::string_view(e.what()).find("loopback") != std::string_view::npos;
    std::fprintf(stderr, "kewd: %s%s\n", e.what(),
                 replaying && listener ? " (a replay serves on loopback only: --alert-listen or --http-listen 127.0.0.1:PORT)" : "");
    return kUsageError;
  }
  if (!flags.log_level.empty()) config.service.log_level = *kew::daemon::kLogLevelNames.parse(flags.log_level);
  if (flags.check_config) {
    std::printf("kewd: %s is valid: %zu inputs, alerts on %s%s%s\n",
                flags.config_path.empty() ? "the built-in configuration" : flags.config_path.c_str(),
                config.inputs.size(), config.service.alert_listen.c_str(), config.cat004.enabled ? ", CAT004" : "",
                config.modbus.enabled ? ", Modbus" : "");
    // Relative paths as resolved (against the working directory).
    if (!config.service.alert_log.empty()) std::printf("alert log: %s\n", config.service.alert_log.c_str());
    if (!config.service.record_file.empty()) std::printf("record file: %s\n", config.service.record_file.c_str());
    if (const std::string state = kew::daemon::state_directory(config.service); !state.empty())
      std::printf("state directory: %s\n", state.c_str());
    for (const std::string& note : notes) std::printf("note: %s\n", note.c_str());
    if (!config.nats.servers.empty())
      std::printf("nats: %s (%d replicas)\n", kew::config::join_nats_servers(config.nats.servers).c_str(),
                  config.nats.replicas);
    for (const auto& input : config.inputs)
      if (input.transport == kew::daemon::Transport::File)
        std::printf("input %s: file %s\n", input.name.c_str(), input.address.c_str());
    std::printf("aerodromes file: %s (%zu aerodromes)\n", config.aerodromes_file.c_str(),
                config.pipeline.eligibility.aerodromes->size());
    if (!config.regions_geojson.empty()) std::printf("regions file: %s\n", config.regions_geojson.c_str());
    for (const auto& region : config.pipeline.regions)
      std::printf("region %s: %s\n", region.name.c_str(), describe(region).c_str());
    return 0;
  }

  // A replay is watched from a terminal: it never forks.
  if (replaying) flags.foreground = true;
  const int ready_fd = flags.foreground ? -1 : daemonize();
  kew::daemon::setup_logging(flags.foreground ? kew::daemon::LogTarget::Stderr : kew::daemon::LogTarget::Syslog,
                             config.service.log_level);
  try {
    kew::daemon::ServiceOptions options;
    options.config_path = flags.config_path.empty() ? std::string() : std::filesystem::absolute(flags.config_path).string();
    options.listen_any = flags.listen_any;
    if (!flags.log_level.empty()) options.log_level_override = config.service.log_level;
    options.replay = replaying;
    options.replay_speed = flags.replay.speed;
    options.exit_at_end = flags.exit_at_end;
    if (replaying) options.config_path.clear();  // SIGHUP would reload a file the replay only partly uses
    kew::daemon::Service service(std::move(config), options);
    report_ready(ready_fd, true);
    if (!flags.foreground && ::chdir("/") != 0) spdlog::warn("kewd: cannot change directory to /");
    return service.run();
  } catch (const std::exception& e) {
    spdlog::critical("kewd: cannot start: {}", e.what());
    spdlog::default_logger()->flush();
    report_ready(ready_fd, false);
    return kStartFailed;
  }
}
