// kewd --replay (design §5.6): the configuration of a replay built from the command line
// and, optionally, the shared tables of a configuration file.
#include <filesystem>

#include "kew/daemon/config.hpp"

namespace kew::daemon {

void apply_replay(Config& config, const ReplaySettings& replay) {
  InputConfig input;
  input.name = "replay";
  input.format = replay.format;
  input.transport = Transport::File;
  input.address = std::filesystem::absolute(replay.file).string();
  input.pace = replay.speed > 0.0;
  input.speed = replay.speed > 0.0 ? replay.speed : 1.0;
  config.inputs = {input};

  ServiceConfig& service = config.service;
  if (!replay.alert_listen.empty()) service.alert_listen = replay.alert_listen;
  service.allow_remote = false;
  // Nothing written unless asked: a replay is watched, not archived, and a production
  // file's alert log and state directory belong to the production daemon.
  service.alert_log = replay.alert_log.empty() ? std::string() : std::filesystem::absolute(replay.alert_log).string();
  service.record_file.clear();
  service.state_directory.clear();
  // Replayed alerts must never reach a live display, a PLC or a person's phone.
  config.cat004.enabled = false;
  config.modbus.enabled = false;
  config.notify.clear();
  config.modbus.allow_remote = false;
  // Nor a production bus (its subscribers, MQTT integrations, a hot-standby lease).
  config.nats = NatsConfig{};
  // The map and API stay (they are how a replay is watched), on loopback like the rest.
  config.http.allow_remote = false;
  if (!replay.http_listen.empty()) config.http.listen = replay.http_listen;
}

}  // namespace kew::daemon
