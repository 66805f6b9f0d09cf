#include "service.hpp"

#include <systemd/sd-daemon.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <thread>

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "../nats/ack_follower.hpp"
#include "../nats/leader_lease.hpp"
#include "../nats/nats_publisher.hpp"
#include "logging.hpp"
#include "kew/config/address.hpp"
#include "kew/daemon/modbus_server.hpp"
#include "kew/config/nats_subject.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/protocol/ndjson_writer.hpp"
#include "kew/protocol/version.hpp"

namespace kew::daemon {

namespace asio = boost::asio;
using asio::ip::tcp;

namespace {

constexpr auto kShutdownGrace = std::chrono::seconds(5);
// Alarm state goes to the Modbus thread at most this often (a copy of every active
// alert per publish), and at least once a second for the data age and uptime.
constexpr auto kModbusPublishPeriod = std::chrono::milliseconds(200);

std::chrono::steady_clock::duration seconds(double s) {
  return std::chrono::duration_cast<std::chrono::steady_clock::duration>(std::chrono::duration<double>(s));
}

/// "127.0.0.1:4747" → "0.0.0.0:4747" (and "[::1]:P" → "[::]:P") when the operator asked
/// for every interface; other addresses were chosen on purpose and are kept.
std::string widen_if_loopback(const std::string& address) {
  const std::optional<config::HostPort> parsed = config::parse_host_port(address);
  if (!parsed) return address;
  if (parsed->host == "127.0.0.1" || parsed->host == "localhost") return config::to_string({"0.0.0.0", parsed->port});
  if (parsed->host == "::1") return config::to_string({"::", parsed->port});
  return address;
}

/// Runs `open` (which binds `address`), naming the listener and its address in what it
/// throws: a bare "bind: Address already in use" does not say which port.
template <class Open>
auto open_listener(std::string_view name, std::string_view address, Open&& open) {
  try {
    return open();
  } catch (const std::exception& e) {
    throw std::runtime_error(fmt::format("{} = \"{}\": {}", name, address, e.what()));
  }
}

tcp::endpoint resolve_listen(asio::io_context& io, const std::string& address) {
  const config::HostPort listen = config::require_host_port(address);
  tcp::resolver resolver(io);
  return *resolver.resolve(listen.host, std::to_string(listen.port), tcp::resolver::passive).begin();
}

/// Calls f(track) for every live track (in the kinetic engine), in slot order.
template <class F>
void for_each_live_track(const Pipeline& pipeline, F&& f) {
  for (track::TrackSlot slot = 0; slot < pipeline.tracks().slot_end(); ++slot) {
    const track::Track& track = pipeline.tracks()[slot];
    if (track.in_use && track.in_engine) f(track);
  }
}

}  // namespace

Service::Service(Config config, ServiceOptions options)
    : signals_(io_, SIGTERM, SIGINT, SIGHUP),
      tick_timer_(io_),
      alive_timer_(io_),
      watchdog_timer_(io_),
      shutdown_timer_(io_),
      modbus_timer_(io_),
      housekeeping_timer_(io_),
      nats_tracks_timer_(io_),
      config_(std::move(config)),
      options_(std::move(options)),
      pipeline_(config_.pipeline),
      started_(std::chrono::steady_clock::now()),
      health_(config_.pipeline.tracks.track_timeout_s),
      last_alive_(started_) {
  started_unix_s_ = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  pipeline_.set_alert_sink([this](const AlertEvent& e) { on_alert(e); });
  if (const char* stall = std::getenv("KEWD_TEST_STALL_FILE"); stall && *stall) {
    stall_file_ = stall;
    spdlog::warn("KEWD_TEST_STALL_FILE is set (a test hook): the pipeline blocks while {} exists", stall_file_);
  }
  pipeline_.rejections().set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::warn("record rejected ({}): {}", reason, message);
  });

  if (!config_.service.alert_log.empty())
    alert_log_ = std::make_unique<LineFile>(config_.service.alert_log, config_.service.alert_log_max_bytes,
                                            config_.service.alert_log_keep,
                                            config_.service.alert_log_sync == AlertLogSync::Every);
  // A replay's numbering starts at 1 each time and is kept nowhere (design §5.6).
  if (const std::string directory = state_directory(config_.service); !directory.empty() && !options_.replay)
    state_file_ = std::make_unique<StateFile>(directory);
  if (!config_.service.record_file.empty())
    record_file_ = std::make_unique<LineFile>(config_.service.record_file, 0, 0);
  if (config_.cat004.enabled) cat004_ = std::make_unique<Cat004Sender>(io_, config_.cat004);
  run_id_ = make_run_id();
  if (!config_.nats.url.empty()) nats_ = std::make_unique<NatsPublisher>(config_.nats, run_id_);
  if (config_.nats.hot_standby) {
    // Silent until the lease says otherwise (design §5.9).
    active_ = false;
    std::string instance = config_.nats.instance;
    if (instance.empty()) {
      char host[256] = "kewd";
      ::gethostname(host, sizeof host - 1);
      instance = fmt::format("{}-{}", host, ::getpid());
    }
    LeaderLease::Handlers handlers;
    handlers.on_acquired = [this](std::uint64_t published) {
      asio::post(io_, [this, published] { take_over(published); });
    };
    handlers.on_lost = [this] { asio::post(io_, [this] { step_down(); }); };
    lease_ = std::make_unique<LeaderLease>(config_.nats, instance, std::move(handlers));
    // The active's acknowledgements, kept by the standby for after a takeover.
    acks_ = std::make_unique<AckFollower>(config_.nats, [this](std::vector<std::string> ids) {
      asio::post(io_, [this, ids = std::move(ids)] { follow_acknowledgements(ids); });
    });
  }

  if (config_.modbus.enabled) {
    ModbusConfig modbus = config_.modbus;
    if (options_.listen_any) modbus.listen = widen_if_loopback(modbus.listen);
    modbus_ = open_listener("[modbus] listen", modbus.listen, [&] {
      return std::make_unique<ModbusServer>(modbus, [this](const std::string& client) {
        asio::post(io_, [this, client] { acknowledge("modbus", client); });
      });
    });
    modbus_->set_reporter([](std::string_view reason, std::string_view message) {
      spdlog::warn("modbus: refused a request ({}){}{}", reason, message.empty() ? "" : ": ", message);
    });
  }

  std::string listen = config_.service.alert_listen;
  if (options_.listen_any) listen = widen_if_loopback(listen);
  SubscriberServer::Source source;
  source.snapshot = [this] { return pipeline_.alerts().snapshot(); };
  source.seq = [this] { return last_alert_seq_; };
  source.stats = [this] { return stats_json(); };
  source.start = [this] { return start_line_; };
  subscribers_ = open_listener("[service] alert_listen", listen, [&] {
    return std::make_unique<SubscriberServer>(io_, resolve_listen(io_, listen), subscriber_limits(config_.service),
                                              config_.service.tracks_stream, std::move(source));
  });

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

  if (config_.http.enabled) {
    std::string http_listen = config_.http.listen;
    if (options_.listen_any) http_listen = widen_if_loopback(http_listen);
    http_ = open_listener("[http] listen", http_listen, [&] {
      return std::make_unique<http::HttpServer>(io_, resolve_listen(io_, http_listen), config_.http, http_source());
    });
  }
}

Service::~Service() {
  // The last events reach the server before the lease goes: a standby that took over
  // earlier would find them unpublished and send them again.
  nats_.reset();
  lease_.reset();
  acks_.reset();
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
  if (lease_)
    spdlog::info("hot standby as {}: alerts are computed, and sent once this instance holds the lease {} of {}",
                 lease_->instance(), config_.nats.lease_key, config_.nats.lease_bucket);
  if (nats_)
    spdlog::info("NATS: alerts to {}.<zone>{}, status to {}", config_.nats.alerts_subject,
                 config_.nats.stream.empty() ? ""
                                             : fmt::format(" (kept in the JetStream stream {})", config_.nats.stream),
                 config_.nats.status_subject);
  if (state_file_) spdlog::info("state file: {}", state_file_->path());
  for (const auto& input : inputs_) {
    const std::uint16_t port = input->bound_port();
    spdlog::info("input {}: {} {} {}{}", input->config().name, protocol::to_string(input->config().format),
                 to_string(input->config().transport), input->config().address,
                 port ? fmt::format(" (port {})", port) : std::string());
  }
  if (modbus_) {
    publish_modbus();
    if (active_) start_modbus();
    schedule_modbus_publish();
  }
  wait_for_signal();
  schedule_tick();
  schedule_alive();
  schedule_housekeeping();
  if (nats_ && config_.nats.tracks_interval_s > 0) schedule_nats_tracks();
  std::uint64_t watchdog_us = 0;
  // Three pings per WatchdogSec: one may be withheld for a batch that just arrived.
  if (sd_watchdog_enabled(0, &watchdog_us) > 0 && watchdog_us > 0)
    schedule_watchdog(std::chrono::microseconds(watchdog_us / 3));
  sd_notifyf(0, "READY=1\nSTATUS=serving alerts on port %u", static_cast<unsigned>(subscribers_->port()));
  io_.run();
  if (alert_log_) {
    if (!alert_log_->flush())
      spdlog::error("kewd stops with {} bytes of alert events the alert log could not take",
                    alert_log_->pending_bytes());
    if (config_.service.alert_log_sync != AlertLogSync::None) alert_log_->sync();
  }
  if (record_file_) record_file_->flush();
  save_numbering();
  spdlog::info("kewd stopped: {} records, {} alerts opened", pipeline_.statistics().records,
               pipeline_.alerts().counters().opened);
  spdlog::default_logger()->flush();
  return 0;
}

void Service::on_report(const TrackReport& report, std::size_t input) {
  if (stopping_) return;
  const auto arrival = std::chrono::steady_clock::now();
  record_arrival_ = arrival;
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
  const double wall = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  if (!options_.replay) pipeline_.set_time_ceiling(wall + config_.service.max_future_s);
  InputFigures& figures = input_figures_[input];
  figures.last_record_unix_s = wall;
  const std::uint64_t accepted = pipeline_.statistics().accepted;
  const std::uint64_t refused = pipeline_.rejections().total();
  // Events come out when the batch runs: at once for the first records after a batch
  // (prompt_records), when this record fills it, or right after the handler that
  // delivered the records (a datagram, a read, a replay step) returns.
  if (!batch_arrival_) batch_arrival_ = arrival;
  record_arrival_ = batch_arrival_;
  pipeline_.process(report);
  record_arrival_.reset();
  if (!pipeline_.batch_waiting()) batch_arrival_.reset();
  if (!flush_posted_) {
    flush_posted_ = true;
    boost::asio::post(io_, [this] { flush_pipeline(); });
  }
  if (pipeline_.rejections().total() != refused) figures.pipeline_refused.reject(pipeline_.rejections().last_reason());
  if (pipeline_.statistics().accepted == accepted) return;
  health_.accepted(std::chrono::steady_clock::now());
  if (http_ && http_->has_websockets()) {
    const track::TrackSlot slot = pipeline_.tracks().find(report.source, report.id);
    if (slot == track::kNoTrack) return;
    if (ws_track_marked_.size() <= slot) ws_track_marked_.resize(slot + 1, false);
    if (!ws_track_marked_[slot]) {
      ws_track_marked_[slot] = true;
      ws_tracks_.push_back(slot);
    }
  }
}

void Service::flush_pipeline() {
  if (!stall_file_.empty() && std::filesystem::exists(stall_file_)) {
    // Test-only: the pipeline stuck, as a worker that never returns would leave it.
    spdlog::warn("test hook: the pipeline is stalled while {} exists", stall_file_);
    while (std::filesystem::exists(stall_file_)) std::this_thread::sleep_for(std::chrono::milliseconds(20));
    spdlog::warn("test hook: the pipeline runs again");
  }
  ++flushes_;
  flush_posted_ = false;
  // The record-to-alert latency of a batch counts from its first record's arrival.
  record_arrival_ = batch_arrival_;
  pipeline_.flush();
  record_arrival_.reset();
  batch_arrival_.reset();
}

void Service::begin_run() {
  const std::optional<Numbering> saved = state_file_ ? state_file_->load() : std::nullopt;
  AlertLogTail tail;
  if (alert_log_) tail = read_alert_log_tail(alert_log_->path());
  if (tail.unreadable_lines)
    spdlog::warn("alert log {}: {} of {} lines unreadable (skipped while looking for open alerts)",
                 alert_log_->path(), tail.unreadable_lines, tail.lines);
  Numbering numbering = resume_point(saved, tail);
  const double wall = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
  line_.clear();
  protocol::append_start_json(line_, protocol::StartInfo{run_id_, wall}, numbering.last_seq);
  start_line_ = line_;
  if (alert_log_) alert_log_->append(line_);
  // Ended, not resumed under their ids: this run does not know whether the pair is still
  // in conflict until its tracks are rebuilt; if it is, the alert opens again (new id,
  // new number) within `confirm` evaluations (design §4.7).
  for (AlertEvent event : tail.open) {
    event.state = AlertState::End;
    event.end_reason = AlertEndReason::Restart;
    event.t = tail.last_t;  // the last data time the previous run logged
    event.seq = ++numbering.last_seq;
    line_.clear();
    protocol::append_alert_json(line_, event, event.seq);
    alert_log_->append(line_);
    emit_or_keep(event);
  }
  if (alert_log_) alert_log_->flush();
  pipeline_.alerts().resume(numbering.last_seq, numbering.next_number);
  last_alert_seq_ = numbering.last_seq;
  save_numbering();
  spdlog::info("run {}: seq continues after {}, next alert number {}; {} alerts left open by the last run ended "
               "(reason restart)",
               run_id_, numbering.last_seq, numbering.next_number, tail.open.size());
}

void Service::save_numbering() {
  if (!state_file_) return;
  const Numbering now{pipeline_.alerts().last_seq(), pipeline_.alerts().next_number()};
  if (saved_ && now.last_seq == saved_->last_seq && now.next_number == saved_->next_number) return;
  std::string error;
  if (state_file_->save(now, run_id_, error)) {
    saved_ = now;
    if (state_errors_) spdlog::info("state file {} written again", state_file_->path());
    state_errors_ = 0;
    return;
  }
  // Counted; reported at the first failure and then every minute of them (one a second).
  if (state_errors_++ % 60 == 0)
    spdlog::error("cannot save the numbering: {} ({} failures; the alert log's tail still guards it)", error,
                  state_errors_);
}

void Service::schedule_housekeeping() {
  housekeeping_timer_.expires_after(std::chrono::seconds(1));
  housekeeping_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    if (alert_log_) {
      const bool was_failing = alert_log_->failing();
      if (was_failing) alert_log_->flush();
      if (config_.service.alert_log_sync == AlertLogSync::Interval) alert_log_->sync();
      if (was_failing != alert_log_->failing()) modbus_dirty_ = true;
    }
    save_numbering();
    schedule_housekeeping();
  });
}

protocol::HealthReason Service::health(std::chrono::steady_clock::time_point now) const {
  // The log first: the feed's state is also told by register 4 and ALIVE's "t", a lost
  // record of the alerts by nothing else.
  if (alert_log_ && alert_log_->failing()) return protocol::HealthReason::AlertLogFailing;
  // A display connected to a standby (or to an active that lost its lease) must not
  // take its silence for a quiet sky.
  if (lease_ && !active_) return protocol::HealthReason::Standby;
  return health_.reason(now);
}

void Service::on_alert(const AlertEvent& event) {
  last_alert_seq_ = event.seq;
  if (record_arrival_)
    latency_.observe(std::chrono::duration<double>(std::chrono::steady_clock::now() - *record_arrival_).count());
  if (alert_log_) {
    // Written per alert: an alert nobody was subscribed to must survive a crash. While
    // the file cannot take it, the event waits in memory and each event retries.
    line_.clear();
    protocol::append_alert_json(line_, event, event.seq);
    alert_log_->append(line_);
    const bool was_failing = alert_log_->failing();
    alert_log_->flush();
    if (was_failing != alert_log_->failing()) modbus_dirty_ = true;
  }
  emit_or_keep(event);
  modbus_dirty_ = true;
}

void Service::emit_or_keep(const AlertEvent& event) {
  if (lease_) {
    // Kept whether active or not: an instance that steps down and takes the lease back
    // sends again what its outbox had not published (JetStream keeps each seq once).
    history_.push_back(event);
    if (history_.size() > config_.nats.standby_history) history_.pop_front();
    // The lease thread may be stuck in a slow call: speak only while the last renewal
    // the server took guarantees that nobody else can.
    if (active_ && !lease_->may_speak()) step_down();
  }
  if (active_) emit(event);
}

void Service::emit(const AlertEvent& event) {
  if (event.seq <= emit_floor_) return;  // the previous active published it
  subscribers_->broadcast_alert(event);
  if (http_ && http_->has_websockets()) {
    line_.clear();
    protocol::append_alert_json(line_, event, event.seq);
    http_->push(line_);
  }
  if (cat004_) cat004_->send_alert(event);
  if (nats_) {
    line_.clear();
    protocol::append_alert_json(line_, event, event.seq);
    nats_->publish_alert(nats_zone(event), line_, event.seq);
  }
}

void Service::take_over(std::uint64_t published) {
  if (active_ || stopping_) return;
  emit_floor_ = std::max(emit_floor_, published);
  active_ = true;
  std::size_t sent = 0;
  if (!history_.empty() && history_.front().seq > emit_floor_ + 1)
    spdlog::error("active now, but events {} to {} are neither in the stream nor kept here (standby_history {}): "
                  "they are lost",
                  emit_floor_ + 1, history_.front().seq - 1, config_.nats.standby_history);
  for (const AlertEvent& event : history_) {
    if (event.seq <= emit_floor_) continue;
    emit(event);
    ++sent;
  }
  if (modbus_) start_modbus();
  modbus_dirty_ = true;
  spdlog::warn("active now (hot standby {}): the previous active published up to seq {}; {} later events sent, "
               "{} alerts open",
               lease_->instance(), published, sent, pipeline_.alerts().active_count());
  sd_notifyf(0, "STATUS=active, serving alerts on port %u", static_cast<unsigned>(subscribers_->port()));
}

void Service::follow_acknowledgements(const std::vector<std::string>& ids) {
  if (active_ || stopping_) return;  // the active's own are already applied
  std::size_t applied = 0;
  for (const std::string& id : ids) applied += pipeline_.alerts().acknowledge(id).size();
  if (applied) {
    spdlog::info("standby: {} alerts acknowledged on the active", applied);
    modbus_dirty_ = true;
  }
}

void Service::step_down() {
  if (!active_) return;
  active_ = false;
  // What it has not published yet is the next active's to send.
  if (nats_) nats_->discard_outbox();
  spdlog::error("standby now: the lease is lost; alerts are computed, not sent");
  sd_notify(0, "STATUS=standby (lease lost)");
}

void Service::start_modbus() {
  if (modbus_started_) return;
  modbus_->start();
  modbus_started_ = true;
  spdlog::info("Modbus TCP alarm map on port {} (unit id {})", modbus_->bound_port(), config_.modbus.unit_id);
}

std::string Service::nats_zone(const AlertEvent& event) const {
  const std::optional<zone::ZoneTiling>& tiling = pipeline_.tiling();
  if (!tiling) return "single";
  const zone::ZoneKey owner = tiling->owner({event.a.lat_deg, event.a.lon_deg}, {event.b.lat_deg, event.b.lon_deg});
  return config::nats_subject_token(tiling->name(owner));
}

void Service::schedule_modbus_publish() {
  modbus_timer_.expires_after(kModbusPublishPeriod);
  modbus_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    publish_modbus();
    schedule_modbus_publish();
  });
}

void Service::publish_modbus() {
  if (!modbus_) return;
  const auto now = std::chrono::steady_clock::now();
  // Unchanged alarms are republished once a second anyway: data age and uptime move.
  if (!modbus_dirty_ && now - last_modbus_publish_ < std::chrono::seconds(1)) return;
  protocol::AlarmSnapshot snapshot;
  snapshot.active = pipeline_.alerts().snapshot();
  snapshot.live_tracks = static_cast<std::uint32_t>(pipeline_.live_tracks());
  snapshot.seconds_since_last_record = health_.seconds_since_accepted(now).value_or(1e9);
  snapshot.feed_healthy = health_.reason(now) == protocol::HealthReason::Healthy;
  snapshot.degraded = health(now) != protocol::HealthReason::Healthy;
  snapshot.uptime_s = static_cast<std::uint32_t>(std::chrono::duration<double>(now - started_).count());
  snapshot.unacknowledged = static_cast<std::uint32_t>(pipeline_.alerts().unacknowledged_count());
  modbus_->publish(snapshot);
  modbus_dirty_ = false;
  last_modbus_publish_ = now;
}

std::vector<std::string> Service::acknowledge(std::string_view by, std::string_view client,
                                              std::optional<std::string_view> id) {
  if (stopping_) return {};
  if (!active_) {
    spdlog::warn("{} client {}: acknowledgements go to the active kewd (this one is standby)", by, client);
    return {};
  }
  const std::vector<std::string> ids = id ? pipeline_.alerts().acknowledge(*id) : pipeline_.alerts().acknowledge_all();
  spdlog::info("{} client {} acknowledged {} alerts", by, client, ids.size());
  if (ids.empty()) return ids;
  const protocol::Acknowledgement ack{ids, pipeline_.statistics().last_data_time, by, client};
  if (alert_log_) {
    line_.clear();
    protocol::append_ack_json(line_, ack, last_alert_seq_);
    alert_log_->append(line_);
    alert_log_->flush();
  }
  subscribers_->broadcast_ack(ack);
  if (nats_) {
    // Never below what the previous active published: Kew-Seq grows along the stream.
    const std::uint64_t seq = std::max(last_alert_seq_, emit_floor_);
    line_.clear();
    protocol::append_ack_json(line_, ack, seq);
    nats_->publish_ack(line_, seq);
  }
  if (http_ && http_->has_websockets()) {
    line_.clear();
    protocol::append_ack_json(line_, ack, last_alert_seq_);
    http_->push(line_);
  }
  modbus_dirty_ = true;
  publish_modbus();
  return ids;
}

double Service::data_clock_now() const {
  // Live mode: the data clock runs on with the wall clock between records, so that
  // tracks of a silent feed time out and kinetic events happen on time. A replay's runs
  // at its speed while the file is read, and stops at its end: the last state stays on
  // show; as fast as possible, only records move it (as in kew-replay).
  const double last = pipeline_.statistics().last_data_time;
  if (options_.replay && (replay_ended_ || options_.replay_speed <= 0.0)) return last;
  const double idle = health_.seconds_since_accepted(std::chrono::steady_clock::now()).value_or(0.0);
  return last + idle * (options_.replay ? options_.replay_speed : 1.0);
}

void Service::schedule_tick() {
  tick_timer_.expires_after(seconds(config_.service.tick_interval_s));
  tick_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    tick();
    schedule_tick();
  });
}

void Service::tick() {
  if (record_file_) record_file_->flush();
  flush_websockets();
  const std::optional<double> idle = health_.seconds_since_accepted(std::chrono::steady_clock::now());
  // While records are accepted, their own times drive the clock; only a feed silent (or
  // wholly refused) for a whole tick moves it on, so its tracks time out.
  // A replay's clock stands still at its end, or when only its records move it.
  if (options_.replay && (replay_ended_ || options_.replay_speed <= 0.0)) return;
  if (idle && *idle >= config_.service.tick_interval_s) pipeline_.advance_to(data_clock_now());
}

void Service::schedule_alive() {
  alive_timer_.expires_after(seconds(config_.service.alive_interval_s));
  alive_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    alive();
    schedule_alive();
  });
}

void Service::alive() {
  const auto now = std::chrono::steady_clock::now();
  const double span = std::chrono::duration<double>(now - last_alive_).count();
  const PipelineStatistics& s = pipeline_.statistics();
  const std::uint64_t updates = pipeline_.kinetic_statistics().updates;
  if (span > 0) {
    records_per_s_ = static_cast<double>(s.accepted - accepted_at_last_alive_) / span;
    updates_per_s_ = static_cast<double>(updates - updates_at_last_alive_) / span;
  }
  accepted_at_last_alive_ = s.accepted;
  // Targets on the ground are left out by configuration, not refused for a fault: a
  // receiver beside an airport at night sees mostly those and is healthy.
  health_.sample(s.records - pipeline_.rejections().count("on_ground"), s.accepted);
  updates_at_last_alive_ = updates;
  last_alive_ = now;

  const protocol::AliveStatus status = alive_status(now);
  const bool any_accepted = status.last_data_t.has_value();
  subscribers_->broadcast_alive(status);
  if (http_ && http_->has_websockets()) {
    line_.clear();
    protocol::append_alive_json(line_, status, last_alert_seq_);
    http_->push(line_);
  }
  if (!active_) return;  // a standby's status goes only to its own subscribers and map
  if (nats_) {
    line_.clear();
    protocol::append_alive_json(line_, status, last_alert_seq_);
    nats_->publish_status(line_, last_alert_seq_);
  }
  if (cat004_) {
    protocol::Cat004Alive a;
    a.t = any_accepted ? data_clock_now() : static_cast<double>(std::time(nullptr));
    a.degraded = status.degraded();
    cat004_->send_alive(a);
  }
}

void Service::schedule_watchdog(std::chrono::microseconds period) {
  watchdog_timer_.expires_after(period);
  watchdog_timer_.async_wait([this, period](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    // The pipeline runs on this thread: a pipeline stuck in a batch stops these pings,
    // and systemd restarts kewd. A batch that has waited since the last ping with none
    // run meanwhile is no progress either: no ping then.
    if (!flush_posted_ || flushes_ != flushes_at_last_ping_) {
      sd_notify(0, "WATCHDOG=1");
      flushes_at_last_ping_ = flushes_;
    }
    schedule_watchdog(period);
  });
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
  tick_timer_.cancel();
  alive_timer_.cancel();
  modbus_timer_.cancel();
  housekeeping_timer_.cancel();
  nats_tracks_timer_.cancel();
  if (modbus_) modbus_->stop();
  watchdog_timer_.cancel();
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
  service.uptime_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started_).count();
  service.subscribers_now = subscribers_->sessions();
  service.subscribers = subscribers_->figures();
  for (const auto& input : inputs_) service.inputs.push_back(input->statistics());
  if (cat004_) service.cat004 = protocol::Cat004Statistics{cat004_->datagrams_sent(), cat004_->send_errors()};
  if (modbus_) service.modbus = modbus_->stats();
  if (nats_) {
    service.nats = nats_->statistics();
    if (lease_) service.nats->active = active_;
  }
  if (alert_log_) {
    service.alert_log_errors = alert_log_->write_errors();
    service.alert_log_queued_bytes = alert_log_->pending_bytes();
    service.alert_log_dropped = alert_log_->dropped_lines();
  }
  service.resident_bytes = http::resident_bytes();
  return service;
}

std::string Service::stats_json() const { return protocol::stats_json(pipeline_, service_statistics()); }

protocol::AliveStatus Service::alive_status(std::chrono::steady_clock::time_point now) const {
  protocol::AliveStatus status;
  const PipelineStatistics& s = pipeline_.statistics();
  if (health_.seconds_since_accepted(now)) status.last_data_t = s.last_data_time;
  status.tracks = pipeline_.live_tracks();
  status.alerts = pipeline_.alerts().active_count();
  status.records_per_s = records_per_s_;
  status.updates_per_s = updates_per_s_;
  status.uptime_s = static_cast<std::uint64_t>(std::chrono::duration<double>(now - started_).count());
  status.health = health(now);
  return status;
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
  m.start_time_unix_s = started_unix_s_;
  return http::metrics_text(m);
}

void Service::flush_websockets() {
  if (!http_) return;
  if (http_->has_websockets()) {
    const double now = pipeline_.now();
    for (const track::TrackSlot slot : ws_tracks_) {
      ws_track_marked_[slot] = false;
      const track::Track& track = pipeline_.tracks()[slot];
      if (!track.in_use || !track.in_engine) continue;
      line_.clear();
      protocol::append_live_track_json(line_, track, now, last_alert_seq_);
      http_->push(line_);
    }
  } else {
    for (const track::TrackSlot slot : ws_tracks_) ws_track_marked_[slot] = false;
  }
  ws_tracks_.clear();
  http_->flush();
}

std::string Service::tracks_json() const {
  const double now = pipeline_.now();
  std::string out = fmt::format("{{\"class\":\"TRACKS\",\"seq\":{},\"t\":{:.3f},\"tracks\":[", last_alert_seq_, now);
  bool first = true;
  for_each_live_track(pipeline_, [&](const track::Track& track) {
    if (!first) out.push_back(',');
    first = false;
    protocol::append_live_track_json(out, track, now, last_alert_seq_);
  });
  out += "]}\n";
  return out;
}

void Service::schedule_nats_tracks() {
  nats_tracks_timer_.expires_after(seconds(config_.nats.tracks_interval_s));
  nats_tracks_timer_.async_wait([this](const boost::system::error_code& ec) {
    if (ec || stopping_) return;
    if (active_) nats_->publish_tracks(tracks_json(), last_alert_seq_);
    schedule_nats_tracks();
  });
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
    const double wall = std::chrono::duration<double>(std::chrono::system_clock::now().time_since_epoch()).count();
    protocol::append_status_json(out, alive_status(std::chrono::steady_clock::now()), last_alert_seq_,
                                 data_clock_now(), wall);
    return out;
  };
  source.zones = [this] {
    std::string out;
    protocol::append_zones_json(out, pipeline_);
    return out;
  };
  source.metrics = [this] { return metrics_text(); };
  source.snapshot = [this] {
    const double now = pipeline_.now();
    std::string out = "[";
    std::string line;
    const auto add = [&](std::string_view object) {
      if (out.size() > 1) out.push_back(',');
      if (!object.empty() && object.back() == '\n') object.remove_suffix(1);
      out.append(object);
    };
    for_each_live_track(pipeline_, [&](const track::Track& track) {
      line.clear();
      protocol::append_live_track_json(line, track, now, last_alert_seq_);
      add(line);
    });
    for (const AlertEvent& event : pipeline_.alerts().snapshot()) {
      line.clear();
      protocol::append_alert_json(line, event, event.seq);
      add(line);
    }
    line.clear();
    protocol::append_alive_json(line, alive_status(std::chrono::steady_clock::now()), last_alert_seq_);
    add(line);
    out.push_back(']');
    return out;
  };
  source.acknowledge = [this](const protocol::AckRequest& request, std::string_view client) {
    return acknowledge("web", client, request.all ? std::nullopt : std::optional<std::string_view>(request.id));
  };
  return source;
}

}  // namespace kew::daemon
