#include "service.hpp"

#include <systemd/sd-daemon.h>

#include <algorithm>
#include <filesystem>
#include <optional>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "../nats/hot_standby.hpp"
#include "../outputs/alert_log_output.hpp"
#include "../outputs/cat004_output.hpp"
#include "../outputs/modbus_output.hpp"
#include "../outputs/nats_output.hpp"
#include "../outputs/subscriber_output.hpp"
#include "../outputs/websocket_output.hpp"
#include "listen_address.hpp"
#include "logging.hpp"
#include "test_hooks.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/version.hpp"

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

constexpr auto kShutdownGrace = std::chrono::seconds(5);

double wall_clock_s() {
  return std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
}

}  // namespace

Service::Service(Config config, ServiceOptions options)
    : signals_(io_, SIGTERM, SIGINT, SIGHUP),
      shutdown_timer_(io_),
      housekeeping_(io_),
      config_(std::move(config)),
      options_(std::move(options)),
      pipeline_(config_.pipeline),
      // A replay's numbering starts at 1 each time and is kept nowhere (design §5.6).
      continuity_(options_.replay ? std::string() : state_directory(config_.service)),
      status_(pipeline_, config_.pipeline.tracks.track_timeout_s) {
  pipeline_.set_alert_sink([this](const AlertEvent& e) { on_alert(e); });
  test_hooks::announce();
  pipeline_.rejections().set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::warn("record rejected ({}): {}", reason, message);
  });
  if (!config_.service.record_file.empty())
    record_file_ = std::make_unique<LineFile>(config_.service.record_file, 0, 0);
  open_outputs();
  open_inputs();
}

void Service::open_outputs() {
  StandbyGate gate;
  if (config_.nats.hot_standby) {
    // Silent until the lease says otherwise (design §5.9).
    HotStandby::Handlers handlers;
    handlers.on_acquired = [this](std::uint64_t published) { take_over(published); };
    handlers.on_lost = [this] { step_down(); };
    handlers.on_acknowledged = [this](const std::vector<std::string>& ids) { follow_acknowledgements(ids); };
    standby_ = std::make_unique<HotStandby>(io_, config_.nats, std::move(handlers));
    gate = StandbyGate(config_.nats.standby_history, [this] { return standby_->may_speak(); });
  }
  fan_out_ = std::make_unique<FanOut>(std::move(gate), [this](bool active) {
    if (active) {
      sd_notifyf(0, "STATUS=active, serving alerts on port %u", static_cast<unsigned>(subscribers_->port()));
    } else {
      spdlog::error("standby now: the lease is lost; alerts are computed, not sent");
      sd_notify(0, "STATUS=standby (lease lost)");
    }
  });
  if (!config_.service.alert_log.empty())
    alert_log_ = &fan_out_->add(std::make_unique<AlertLogOutput>(config_.service));

  std::string listen = config_.service.alert_listen;
  if (options_.listen_any) listen = widen_if_loopback(listen);
  SubscriberServer::Source source;
  source.snapshot = [this] { return pipeline_.alerts().snapshot(); };
  source.seq = [this] { return last_alert_seq_; };
  source.stats = [this] { return protocol::stats_json(pipeline_, service_statistics()); };
  source.start = [this] { return start_line_; };
  subscribers_ = open_listener("[service] alert_listen", listen, [&] {
    return std::make_unique<SubscriberServer>(io_, resolve_listen(io_, listen), subscriber_limits(config_.service),
                                              config_.service.tracks_stream, std::move(source));
  });
  fan_out_->add(std::make_unique<SubscriberOutput>(*subscribers_));

  if (config_.http.enabled) {
    std::string http_listen = config_.http.listen;
    if (options_.listen_any) http_listen = widen_if_loopback(http_listen);
    http_ = open_listener("[http] listen", http_listen, [&] {
      return std::make_unique<http::HttpServer>(io_, resolve_listen(io_, http_listen), config_.http, http_source());
    });
    websockets_ = &fan_out_->add(std::make_unique<WebSocketOutput>(*http_, pipeline_.tracks()));
  }
  if (config_.cat004.enabled) fan_out_->add(std::make_unique<Cat004Output>(io_, config_.cat004));
  if (!config_.nats.url.empty())
    nats_ = &fan_out_->add(std::make_unique<NatsOutput>(config_.nats, continuity_.run_id(), pipeline_));
  if (config_.modbus.enabled) {
    ModbusConfig modbus = config_.modbus;
    if (options_.listen_any) modbus.listen = widen_if_loopback(modbus.listen);
    modbus_ = &fan_out_->add(open_listener("[modbus] listen", modbus.listen, [&] {
      return std::make_unique<ModbusOutput>(
          modbus, [this](const std::string& client) { asio::post(io_, [this, client] { acknowledge("modbus", client); }); },
          [this] { return status_.alarm_state(std::chrono::steady_clock::now(), conditions()); });
    }));
  }
}

void Service::open_inputs() {
  for (std::size_t i = 0; i < config_.inputs.size(); ++i) {
    InputConfig input = config_.inputs[i];
    if (options_.listen_any && (input.transport == Transport::TcpServer || input.transport == Transport::Udp))
      input.address = widen_if_loopback(input.address);
    inputs_.push_back(open_listener(fmt::format("[input {}] address", i + 1), input.address, [&] {
      return make_input(io_, input, config_.decoding, [this, i](const TrackReport& r) { on_report(r, i); });
    }));
    if (options_.replay) inputs_.back()->set_end_handler([this] { asio::post(io_, [this] { end_replay(); }); });
  }
  input_figures_.resize(inputs_.size());
}

Service::~Service() {
  // The last events reach the server before the lease goes: a standby that took over
  // earlier would find them unpublished and send them again.
  if (nats_) nats_->close();
  standby_.reset();
}

int Service::run() {
  begin_run();
  subscribers_->start();
  for (auto& input : inputs_) input->start();
  if (http_) {
    http_->start();
    const std::string& root = http_->router().web().root();
    spdlog::info("HTTP (map, API, metrics) on port {}, files from {}", http_->port(), root);
    std::error_code ec;
    if (!std::filesystem::is_directory(root, ec))
      spdlog::warn("[http] web_root {} is not a directory: the map is not served (the API is)", root);
  }
  spdlog::info("kewd {} serving alerts on port {} ({} inputs)", protocol::release(), subscribers_->port(),
               inputs_.size());
  // Paths as resolved (design §5.7: relative to the working directory kewd started in).
  if (alert_log_) spdlog::info("alert log: {}", alert_log_->path());
  if (record_file_) spdlog::info("record file: {}", record_file_->path());
  if (standby_)
    spdlog::info("hot standby as {}: alerts are computed, and sent once this instance holds the lease {} of {}",
                 standby_->instance(), config_.nats.lease_key, config_.nats.lease_bucket);
  if (nats_)
    spdlog::info("NATS: alerts to {}.<zone>{}, status to {}", config_.nats.alerts_subject,
                 config_.nats.stream.empty() ? ""
                                             : fmt::format(" (kept in the JetStream stream {})", config_.nats.stream),
                 config_.nats.status_subject);
  if (const std::string state = continuity_.state_path(); !state.empty()) spdlog::info("state file: {}", state);
  for (const auto& input : inputs_) {
    const std::uint16_t port = input->bound_port();
    spdlog::info("input {}: {} {} {}{}", input->config().name, protocol::to_string(input->config().format),
                 to_string(input->config().transport), input->config().address,
                 port ? fmt::format(" (port {})", port) : std::string());
  }
  fan_out_->start();
  wait_for_signal();
  start_housekeeping();
  sd_notifyf(0, "READY=1\nSTATUS=serving alerts on port %u", static_cast<unsigned>(subscribers_->port()));
  io_.run();
  if (alert_log_) alert_log_->close();
  if (record_file_) record_file_->flush();
  save_numbering();
  spdlog::info("kewd stopped: {} records, {} alerts opened", pipeline_.statistics().records,
               pipeline_.alerts().counters().opened);
  spdlog::default_logger()->flush();
  return 0;
}

void Service::start_housekeeping() {
  housekeeping_.every([this] { return seconds(config_.service.tick_interval_s); }, [this] { tick(); });
  housekeeping_.every([this] { return seconds(config_.service.alive_interval_s); }, [this] { alive(); });
  // Once a second: a failing alert log retried and synced, the numbering saved.
  housekeeping_.every(std::chrono::seconds(1), [this] {
    if (alert_log_) alert_log_->housekeeping();
    save_numbering();
  });
  if (modbus_) housekeeping_.every(ModbusOutput::kPublishPeriod, [this] { modbus_->publish(); });
  if (nats_ && config_.nats.tracks_interval_s > 0)
    housekeeping_.every(seconds(config_.nats.tracks_interval_s), [this] { nats_->tracks(tracks_json(), last_alert_seq_); });
  std::uint64_t watchdog_us = 0;
  // Three pings per WatchdogSec: one may be withheld for a batch that just arrived. The
  // pipeline runs on this thread: a pipeline stuck in a batch stops these pings, and
  // systemd restarts kewd; a batch that has waited since the last ping with none run
  // meanwhile is no progress either.
  if (sd_watchdog_enabled(0, &watchdog_us) > 0 && watchdog_us > 0)
    housekeeping_.every(std::chrono::microseconds(watchdog_us / 3), [this] {
      if (!flush_posted_ || flushes_ != flushes_at_last_ping_) {
        sd_notify(0, "WATCHDOG=1");
        flushes_at_last_ping_ = flushes_;
      }
    });
}

void Service::on_report(const TrackReport& report, std::size_t input) {
  if (stopping_) return;
  const auto arrival = std::chrono::steady_clock::now();
  if (record_file_) {
    line_.clear();
    protocol::append_ndjson(line_, report);
    line_ += '\n';  // a recording is NDJSON: one record per line, as kew-replay reads it
    record_file_->append(line_);
  }
  if (subscribers_->anyone_wants_tracks()) subscribers_->broadcast_track(report);
  // No record may carry the clock past the wall clock (a host synchronised by NTP is the
  // best time kewd has; recordings played into a live input are in the past). A replay
  // (--replay) has no such ceiling: its clock is the recording's, and the pipeline's time
  // guard still holds a lone record dated ahead of the others, as in kew-replay.
  const double wall = wall_clock_s();
  if (!options_.replay) pipeline_.set_time_ceiling(wall + config_.service.max_future_s);
  InputFigures& figures = input_figures_[input];
  figures.last_record_unix_s = wall;
  // Events come out when the batch runs: at once for the first records after a batch
  // (prompt_records), when this record fills it, or right after the handler that
  // delivered the records (a datagram, a read, a replay step) returns.
  if (!batch_arrival_) batch_arrival_ = arrival;
  record_arrival_ = batch_arrival_;
  const RecordOutcome outcome = pipeline_.process(report);
  record_arrival_.reset();
  if (!pipeline_.batch_waiting()) batch_arrival_.reset();
  if (!flush_posted_) {
    flush_posted_ = true;
    asio::post(io_, [this] { flush_pipeline(); });
  }
  if (outcome.kind == RecordOutcome::Kind::Refused)
    figures.pipeline_refused.reject(track::kRefusalNames.name(outcome.refusal));
  if (!outcome.applied()) return;
  status_.record_applied(std::chrono::steady_clock::now());
  if (websockets_) websockets_->track_updated(outcome.slot);
}

void Service::flush_pipeline() {
  test_hooks::maybe_stall_pipeline();
  ++flushes_;
  flush_posted_ = false;
  // The record-to-alert latency of a batch counts from its first record's arrival.
  record_arrival_ = batch_arrival_;
  pipeline_.flush();
  record_arrival_.reset();
  batch_arrival_.reset();
}

void Service::begin_run() {
  RunContinuity::Beginning beginning = continuity_.begin(alert_log_ ? alert_log_->path() : std::string());
  line_.clear();
  protocol::append_start_json(line_, protocol::StartInfo{continuity_.run_id(), wall_clock_s()}, beginning.start_seq);
  start_line_ = line_;
  if (alert_log_) alert_log_->append(line_);
  for (const AlertEvent& event : beginning.ended) fan_out_->alert(event);
  const Numbering& numbering = beginning.numbering;
  pipeline_.alerts().resume(numbering.last_seq, numbering.next_number);
  last_alert_seq_ = numbering.last_seq;
  save_numbering();
  spdlog::info("run {}: seq continues after {}, next alert number {}; {} alerts left open by the last run ended "
               "(reason restart)",
               continuity_.run_id(), numbering.last_seq, numbering.next_number, beginning.ended.size());
}

void Service::save_numbering() {
  continuity_.save({pipeline_.alerts().last_seq(), pipeline_.alerts().next_number()});
}

ServiceStatus::Conditions Service::conditions() const {
  return {alert_log_ && alert_log_->failing(), fan_out_->hot_standby() && !fan_out_->active()};
}

void Service::on_alert(const AlertEvent& event) {
  last_alert_seq_ = event.seq;
  if (record_arrival_)
    latency_.observe(std::chrono::duration<double>(std::chrono::steady_clock::now() - *record_arrival_).count());
  fan_out_->alert(event);
}

void Service::take_over(std::uint64_t published) {
  if (stopping_) return;
  const std::size_t sent = fan_out_->take_over(published);
  spdlog::warn("active now (hot standby {}): the previous active published up to seq {}; {} later events sent, "
               "{} alerts open",
               standby_->instance(), published, sent, pipeline_.alerts().active_count());
}

void Service::step_down() { fan_out_->step_down(); }

void Service::follow_acknowledgements(const std::vector<std::string>& ids) {
  if (fan_out_->active() || stopping_) return;  // the active's own are already applied
  std::size_t applied = 0;
  for (const std::string& id : ids) applied += pipeline_.alerts().acknowledge(id).size();
  if (!applied) return;
  spdlog::info("standby: {} alerts acknowledged on the active", applied);
  if (modbus_) modbus_->mark_changed();
}

std::vector<std::string> Service::acknowledge(std::string_view by, std::string_view client,
                                              std::optional<std::string_view> id) {
  if (stopping_) return {};
  if (!fan_out_->active()) {
    spdlog::warn("{} client {}: acknowledgements go to the active kewd (this one is standby)", by, client);
    return {};
  }
  const std::vector<std::string> ids = id ? pipeline_.alerts().acknowledge(*id) : pipeline_.alerts().acknowledge_all();
  spdlog::info("{} client {} acknowledged {} alerts", by, client, ids.size());
  if (ids.empty()) return ids;
  // Never below what the previous active published: seq grows along the stream.
  fan_out_->acknowledgement({ids, pipeline_.statistics().last_data_time, by, client},
                            std::max(last_alert_seq_, fan_out_->floor()));
  return ids;
}

double Service::data_clock_now() const {
  // Live mode: the data clock runs on with the wall clock between records, so that
  // tracks of a silent feed time out and kinetic events happen on time. A replay's runs
  // at its speed while the file is read, and stops at its end: the last state stays on
  // show; as fast as possible, only records move it (as in kew-replay).
  const double last = pipeline_.statistics().last_data_time;
  if (options_.replay && (replay_ended_ || options_.replay_speed <= 0.0)) return last;
  const double idle = status_.seconds_since_applied(std::chrono::steady_clock::now()).value_or(0.0);
  return last + idle * (options_.replay ? options_.replay_speed : 1.0);
}

void Service::tick() {
  if (record_file_) record_file_->flush();
  if (websockets_) websockets_->flush(pipeline_.now(), last_alert_seq_);
  const std::optional<double> idle = status_.seconds_since_applied(std::chrono::steady_clock::now());
  // While records are accepted, their own times drive the clock; only a feed silent (or
  // wholly refused) for a whole tick moves it on, so its tracks time out.
  // A replay's clock stands still at its end, or when only its records move it.
  if (options_.replay && (replay_ended_ || options_.replay_speed <= 0.0)) return;
  if (idle && *idle >= config_.service.tick_interval_s) pipeline_.advance_to(data_clock_now());
}

void Service::alive() {
  const auto now = std::chrono::steady_clock::now();
  status_.sample(now);
  fan_out_->alive({status_.alive(now, conditions()), data_clock_now(), last_alert_seq_});
}

void Service::wait_for_signal() {
  signals_.async_wait([this](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    if (signal == SIGHUP) {
      reload();
      wait_for_signal();
      return;
    }
    spdlog::info("kewd: {} received, shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
    shutdown();
  });
}

void Service::reload() {
  if (options_.config_path.empty()) {
    spdlog::info("SIGHUP: no configuration file to reload");
    return;
  }
  sd_notify(0, "RELOADING=1");
  try {
    Config fresh = load_config(options_.config_path);
    // What can change in flight: logging, subscriber limits, timers. Inputs, outputs and
    // pipeline parameters would change results mid-stream: they need a restart.
    if (options_.log_level_override) fresh.service.log_level = *options_.log_level_override;
    set_log_level(fresh.service.log_level);
    config_.service.log_level = fresh.service.log_level;
    subscribers_->set_limits(subscriber_limits(fresh.service));
    config_.service.max_subscribers = fresh.service.max_subscribers;
    config_.service.subscriber_queue = fresh.service.subscriber_queue;
    config_.service.subscriber_queue_bytes = fresh.service.subscriber_queue_bytes;
    config_.service.alive_interval_s = fresh.service.alive_interval_s;
    config_.service.tick_interval_s = fresh.service.tick_interval_s;
    spdlog::info("SIGHUP: reloaded {} (log level {}, {} subscribers of {} queued objects and {} bytes at most)",
                 options_.config_path, to_string(fresh.service.log_level), fresh.service.max_subscribers,
                 fresh.service.subscriber_queue, fresh.service.subscriber_queue_bytes);
    if (http_) {
      http_->set_limits(fresh.http);
      spdlog::info("SIGHUP: HTTP limits: {} connections, {} silent per address, requests within {} s",
                   fresh.http.max_connections, fresh.http.silent_per_address, fresh.http.request_timeout_s);
    }
    spdlog::info("SIGHUP: inputs, outputs and pipeline settings apply at the next restart");
  } catch (const std::exception& e) {
    spdlog::error("SIGHUP: {} (configuration kept)", e.what());
  }
  sd_notify(0, "READY=1");
}

void Service::shutdown() {
  if (stopping_) return;
  stopping_ = true;
  sd_notify(0, "STOPPING=1");
  for (auto& input : inputs_) input->stop();
  // Records already taken are judged, and their alerts sent, before subscribers go.
  flush_pipeline();
  boost::system::error_code ignored;
  signals_.cancel(ignored);
  housekeeping_.stop();
  if (modbus_) modbus_->stop();
  // Subscribers get what is queued for them, then the connection closes; io_.run()
  // returns when the last one is done, or the grace period ends it.
  subscribers_->shutdown();
  if (http_) http_->shutdown();
  shutdown_timer_.expires_after(kShutdownGrace);
  shutdown_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (!ec) io_.stop();
  });
  if (subscribers_->sessions() == 0) shutdown_timer_.cancel();
  subscribers_->on_empty([this] { shutdown_timer_.cancel(); });
}

void Service::end_replay() {
  if (replay_ended_ || stopping_) return;
  replay_ended_ = true;
  pipeline_.end_of_input();
  const auto& input = inputs_.front()->config();
  spdlog::info("replay of {} ended: {} records, {} alerts opened, {} active; {}", input.address,
               pipeline_.statistics().records, pipeline_.alerts().counters().opened, pipeline_.alerts().active_count(),
               options_.exit_at_end ? "exiting (--exit-at-end)" : "serving the last state until SIGINT or SIGTERM");
  if (options_.exit_at_end) shutdown();
}

protocol::ServiceStatistics Service::service_statistics() const {
  protocol::ServiceStatistics service;
  service.seq = last_alert_seq_;
  service.uptime_s = status_.uptime_s(std::chrono::steady_clock::now());
  for (const auto& input : inputs_) service.inputs.push_back(input->statistics());
  fan_out_->report(service);
  service.resident_bytes = http::resident_bytes();
  return service;
}

std::string Service::metrics_text() const {
  http::MetricsSources m;
  m.pipeline = &pipeline_;
  const protocol::ServiceStatistics service = service_statistics();
  for (std::size_t i = 0; i < service.inputs.size(); ++i) {
    const protocol::InputStatistics& in = service.inputs[i];
    http::InputMetrics metrics{in.name, in.reports, in.bytes, in.rejected, input_figures_[i].last_record_unix_s};
    metrics.rejected.merge(input_figures_[i].pipeline_refused);
    m.inputs.push_back(std::move(metrics));
  }
  m.subscribers = subscribers_->sessions();
  m.subscriber_queued_bytes = subscribers_->queued_bytes();
  m.subscriber_figures = service.subscribers;
  if (http_) {
    m.http = &http_->statistics();
    m.http_connections = http_->connections();
    m.websockets = http_->websockets();
    m.websocket_queued_bytes = http_->queued_bytes();
  }
  m.alert_log_queued_bytes = service.alert_log_queued_bytes;
  m.nats = service.nats;
  m.latency = &latency_;
  m.start_time_unix_s = status_.started_unix_s();
  return http::metrics_text(m);
}

std::vector<const track::Track*> Service::live_tracks() const {
  std::vector<const track::Track*> live;
  const track::TrackTable& tracks = pipeline_.tracks();
  for (track::TrackSlot slot = 0; slot < tracks.slot_end(); ++slot)
    if (tracks[slot].in_use && tracks[slot].in_engine) live.push_back(&tracks[slot]);
  return live;
}

std::string Service::tracks_json() const {
  std::string out;
  protocol::append_tracks_json(out, live_tracks(), pipeline_.now(), last_alert_seq_);
  return out;
}

http::HttpSource Service::http_source() {
  http::HttpSource source;
  source.tracks = [this] { return tracks_json(); };
  source.alerts = [this] {
    std::vector<AlertEvent> active = pipeline_.alerts().snapshot();
    std::stable_sort(active.begin(), active.end(),
                     [](const AlertEvent& a, const AlertEvent& b) { return a.severity > b.severity; });
    std::string out;
    protocol::append_alerts_json(out, active, last_alert_seq_, pipeline_.now());
    return out;
  };
  source.status = [this] {
    std::string out;
    protocol::append_status_json(out, status_.alive(std::chrono::steady_clock::now(), conditions()), last_alert_seq_,
                                 data_clock_now(), wall_clock_s());
    return out;
  };
  source.zones = [this] {
    std::string out;
    protocol::append_zones_json(out, pipeline_);
    return out;
  };
  source.metrics = [this] { return metrics_text(); };
  source.snapshot = [this] {
    std::string out;
    protocol::append_snapshot_json(out, live_tracks(), pipeline_.alerts().snapshot(),
                                   status_.alive(std::chrono::steady_clock::now(), conditions()), pipeline_.now(), last_alert_seq_);
    return out;
  };
  source.acknowledge = [this](const protocol::AckRequest& request, std::string_view client) {
    return acknowledge("web", client, request.all ? std::nullopt : std::optional<std::string_view>(request.id));
  };
  return source;
}

}  // namespace kew::daemon
