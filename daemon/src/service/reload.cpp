#include "reload.hpp"

#include <systemd/sd-daemon.h>

#include <exception>

#include <spdlog/spdlog.h>

namespace kew::daemon {

void apply_in_flight(const std::string& path, const Config& fresh, const std::optional<LogLevel>& log_level_override,
                     Config& current, SubscriberServer& subscribers, http::HttpServer* http) {
  ServiceConfig& service = current.service;
  service.log_level = log_level_override.value_or(fresh.service.log_level);
  set_log_level(service.log_level);
  subscribers.set_limits(subscriber_limits(fresh.service));
  service.max_subscribers = fresh.service.max_subscribers;
  service.subscriber_queue = fresh.service.subscriber_queue;
  service.subscriber_queue_bytes = fresh.service.subscriber_queue_bytes;
  service.alive_interval_s = fresh.service.alive_interval_s;
  service.tick_interval_s = fresh.service.tick_interval_s;
  spdlog::info("SIGHUP: reloaded {} (log level {}, {} subscribers of {} queued objects and {} bytes at most)", path,
               to_string(service.log_level), service.max_subscribers, service.subscriber_queue,
               service.subscriber_queue_bytes);
  if (http) {
    http->set_limits(fresh.http);
    spdlog::info("SIGHUP: HTTP limits: {} connections, {} silent per address, requests within {} s",
                 fresh.http.max_connections, fresh.http.silent_per_address, fresh.http.request_timeout_s);
  }
  spdlog::info("SIGHUP: inputs, outputs and pipeline settings apply at the next restart");
}

void reload_configuration(const std::string& path, const std::optional<LogLevel>& log_level_override,
                          Config& current, SubscriberServer& subscribers, http::HttpServer* http) {
  if (path.empty()) {
    spdlog::info("SIGHUP: no configuration file to reload");
    return;
  }
  sd_notify(0, "RELOADING=1");
  try {
    apply_in_flight(path, load_config(path), log_level_override, current, subscribers, http);
  } catch (const std::exception& e) {
    spdlog::error("SIGHUP: {} (configuration kept)", e.what());
  }
  sd_notify(0, "READY=1");
}

}  // namespace kew::daemon
