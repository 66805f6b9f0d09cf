#include "service.hpp"

#include <systemd/sd-daemon.h>

#include <algorithm>
#include <optional>

#include <boost/asio/post.hpp>
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include "../outputs/alert_log_output.hpp"
#include "../outputs/cat004_output.hpp"
#include "../outputs/modbus_output.hpp"
#include "../outputs/nats_output.hpp"
#include "../outputs/notify_output.hpp"
#include "../outputs/subscriber_output.hpp"
#include "../outputs/websocket_output.hpp"
#include "../standby/pair_member.hpp"
#include "listen_address.hpp"
#include "logging.hpp"
#include "reload.hpp"
#include "test_hooks.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/protocol/version.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

namespace asio = boost::asio;

namespace {

constexpr auto kShutdownGrace = std::chrono::seconds(5);

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
      status_(pipeline_, config_.pipeline.tracks.track_timeout_s),
      clock_(config_.inputs.size(), {options_.replay, options_.replay_speed}),
      views_(pipeline_, {[this] { return last_alert_seq_; },
                         [this] { return status_.alive(std::chrono::steady_clock::now(), conditions()); },
                         [this] { return data_clock_now(); }}) {
  pipeline_.set_alert_sink([this](const AlertEvent& e) { on_alert(e); });
  test_hooks::announce();
  pipeline_.rejections().set_reporter([](std::string_view reason, std::string_view message) {
    spdlog::warn("record rejected ({}): {}", reason, message);
  });
  open_outputs();
  open_inputs();
}

void Service::open_outputs() {
  StandbyGate gate;
  // Silent until the lease says otherwise (design §5.9); the pair begins with the run.
  if (config_.nats.hot_standby) {
    speaking_right_ = std::make_shared<SpeakingRight>();
    gate = StandbyGate(config_.nats.standby_history, [right = speaking_right_] { return right->keep_speaking(); });
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

  const std::string listen = listen_address(config_.service.alert_listen, options_.listen_any);
  SubscriberServer::Source source;
  source.snapshot = [this] { return pipeline_.alerts().snapshot(); };
  source.seq = [this] { return last_alert_seq_; };
  source.stats = [this] { return protocol::stats_json(pipeline_, gather_statistics(reported())); };
  source.start = [this] { return start_line_; };
  subscribers_ = open_listener("[service] alert_listen", listen, [&] {
    return std::make_unique<SubscriberServer>(io_, resolve_listen(io_, listen), subscriber_limits(config_.service),
                                              config_.service.tracks_stream, std::move(source));
  });
  fan_out_->add(std::make_unique<SubscriberOutput>(*subscribers_));

  if (config_.http.enabled) {
    const std::string http_listen = listen_address(config_.http.listen, options_.listen_any);
    http_ = open_listener("[http] listen", http_listen, [&] {
      return std::make_unique<http::HttpServer>(io_, resolve_listen(io_, http_listen), config_.http, http_source());
    });
    websockets_ = &fan_out_->add(std::make_unique<WebSocketOutput>(*http_, pipeline_.tracks()));
  }
  if (config_.cat004.enabled)
    fan_out_->add(std::make_unique<Cat004Output>(io_, config_.cat004, !pipeline_.config().volumes.empty()));
  if (!config_.nats.servers.empty())
    nats_ = &fan_out_->add(std::make_unique<NatsOutput>(config_.nats, continuity_.run_id(), pipeline_, speaking_right_));
  // Outboxes live with the numbering, which their seqs follow (design §5.10).
  const std::string directory = continuity_.state_path().empty() ? std::string() : state_directory(config_.service);
  for (auto& notify : open_notify_outputs(config_, directory, speaking_right_))
    notifiers_.push_back(&fan_out_->add(std::move(notify)));
  if (config_.modbus.enabled) {
    ModbusConfig modbus = config_.modbus;
    modbus.listen = listen_address(modbus.listen, options_.listen_any);
    modbus_ = &fan_out_->add(open_listener("[modbus] listen", modbus.listen, [&] {
      return std::make_unique<ModbusOutput>(
          modbus,
          [this](const std::string& client) { asio::post(io_, [this, client] { acknowledge("modbus", client); }); },
          [this] { return status_.alarm_state(std::chrono::steady_clock::now(), conditions()); },
          speaking_right_ ? ModbusServer::SpeakingCheck([right = speaking_right_] { return right->may_speak(); })
                          : ModbusServer::SpeakingCheck());
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
    inputs_.back()->set_source_handler(
        [this, i](SourceState state) { clock_.source(i, state, std::chrono::steady_clock::now()); });
  }
  intake_ = std::make_unique<RecordIntake>(io_, pipeline_, config_.service, options_.replay, inputs_.size());
}

Service::~Service() {
  // The last events reach the server before the lease goes: a standby that took over
  // earlier would find them unpublished and send them again.
  if (nats_) nats_->close();
  pair_.reset();
}

int Service::run() {
  begin_run();
  subscribers_->start();
  if (!pair_) start_inputs();
  if (http_) http_->start();
  spdlog::info("kewd {} serving alerts on port {} ({} inputs)", protocol::release(), subscribers_->port(),
               inputs_.size());
  // Paths as resolved (design §5.7: relative to the working directory kewd started in).
  if (const std::string path = intake_->record_file_path(); !path.empty()) spdlog::info("record file: {}", path);
  if (pair_)
    spdlog::info("hot standby as {}: alerts are computed, and sent once this instance holds the lease {} of {}",
                 pair_->instance(), config_.nats.lease_key, config_.nats.lease_bucket);
  if (const std::string state = continuity_.state_path(); !state.empty()) spdlog::info("state file: {}", state);
  fan_out_->start();
  wait_for_signal();
  start_housekeeping();
  sd_notifyf(0, "READY=1\nSTATUS=serving alerts on port %u", static_cast<unsigned>(subscribers_->port()));
  io_.run();
  if (alert_log_) alert_log_->close();
  for (NotifyOutput* notifier : notifiers_) notifier->close();
  intake_->flush_record_file();
  save_numbering();
  spdlog::info("kewd stopped: {} records, {} alerts opened", pipeline_.statistics().records,
               pipeline_.alerts().counters().opened);
  spdlog::default_logger()->flush();
  return 0;
}

void Service::start_inputs() {
  for (auto& input : inputs_) input->start();
  for (const auto& input : inputs_) spdlog::info("{}", describe(*input));
}

void Service::start_housekeeping() {
  housekeeping_.every([this] { return seconds(config_.service.tick_interval_s); }, [this] { tick(); });
  housekeeping_.every([this] { return seconds(config_.service.alive_interval_s); }, [this] { alive(); });
  // Once a second: a failing alert log retried and synced, the numbering saved.
  housekeeping_.every(std::chrono::seconds(1), [this] {
    if (alert_log_) alert_log_->housekeeping();
    save_numbering();
    if (pair_ && nats_ && inputs_.size() == 1)
      pair_->checkpoint_if_due(inputs_.front()->delivered_stream_sequence(), [this] { return nats_->mark_published(); });
  });
  if (modbus_) housekeeping_.every(ModbusOutput::kPublishPeriod, [this] { modbus_->publish(); });
  if (nats_ && config_.nats.tracks_interval_s > 0)
    housekeeping_.every(seconds(config_.nats.tracks_interval_s),
                        [this] { nats_->tracks(views_.tracks(), last_alert_seq_); });
  std::uint64_t watchdog_us = 0;
  // Three pings per WatchdogSec: one may be withheld for a batch that just arrived. The
  // pipeline runs on this thread: a pipeline stuck in a batch stops these pings, and
  // systemd restarts kewd; a batch that has waited since the last ping with none run
  // meanwhile is no progress either.
  if (sd_watchdog_enabled(0, &watchdog_us) > 0 && watchdog_us > 0)
    housekeeping_.every(std::chrono::microseconds(watchdog_us / 3), [this] {
      if (intake_->progressing()) sd_notify(0, "WATCHDOG=1");
    });
}

void Service::on_report(const TrackReport& report, std::size_t input) {
  if (stopping_) return;
  if (subscribers_->anyone_wants_tracks()) subscribers_->broadcast_track(report);
  const RecordOutcome outcome = intake_->take(report, input);
  if (!outcome.applied()) return;
  status_.record_applied(std::chrono::steady_clock::now());
  if (websockets_) websockets_->track_updated(outcome.slot);
}

void Service::begin_run() {
  RunContinuity::Beginning beginning = continuity_.begin(alert_log_ ? alert_log_->path() : std::string());
  start_line_.clear();
  protocol::append_start_json(start_line_, {continuity_.run_id(), util::unix_now_s()},
                              beginning.start_seq);
  if (alert_log_) alert_log_->append(start_line_);
  const Numbering& numbering = beginning.numbering;
  if (config_.nats.hot_standby) {
    // The pair's own numbering and open alerts are in its stream: this instance's log
    // holds only what it computed, and it judges the feed again from the pair's origin.
    fan_out_->set_journal_floor(numbering.last_seq);
    PairMember::Hooks hooks{[this](const PairOrigin& start, const PairCheckpoint* checkpoint) {
                              begin_pair(start, checkpoint);
                            },
                            [this] {
                              if (modbus_) modbus_->mark_changed();
                            },
                            [this](const AlertEvent& event) { on_alert(event); },
                            {}};
    if (pair_feed_checkpointable(config_.inputs)) hooks.usable = checkpoint_fits(config_.pipeline);
    pair_ = std::make_unique<PairMember>(io_, config_.nats, pair_feed_stream(config_.inputs), numbering.last_seq,
                                         numbering.next_number, speaking_right_, pipeline_, *fan_out_,
                                         std::move(hooks));
    spdlog::info("run {}: hot standby: the numbering and the inputs wait for the pair's origin ({} alerts this "
                 "instance's log left open are the pair's to end)",
                 continuity_.run_id(), beginning.ended.size());
    return;
  }
  for (const AlertEvent& event : beginning.ended) fan_out_->alert(event);
  pipeline_.alerts().resume(numbering.last_seq, numbering.next_number);
  last_alert_seq_ = numbering.last_seq;
  save_numbering();
  spdlog::info("run {}: seq continues after {}, next alert number {}; {} alerts left open by the last run ended "
               "(reason restart)",
               continuity_.run_id(), numbering.last_seq, numbering.next_number, beginning.ended.size());
}

void Service::begin_pair(const PairOrigin& origin, const PairCheckpoint* checkpoint) {
  if (stopping_) return;
  if (checkpoint) {
    // Read and tried on the pair's thread already (PairMember::Hooks::usable).
    pipeline_.restore(checkpoint->pipeline);
    spdlog::info("hot standby: the pipeline continues the checkpoint of {} after feed message {} ({} tracks, {} alerts "
                 "open, seq {})",
                 checkpoint->written_by, checkpoint->feed_seq, pipeline_.tracks().size(),
                 pipeline_.alerts().active_count(), pipeline_.alerts().last_seq());
  } else {
    pipeline_.alerts().resume(origin.last_seq, origin.next_number);
  }
  last_alert_seq_ = origin.last_seq;
  save_numbering();
  for (auto& input : inputs_)
    if (input->read_from_stream_sequence(origin.feed_seq)) break;
  start_inputs();
}

void Service::save_numbering() {
  continuity_.save({pipeline_.alerts().last_seq(), pipeline_.alerts().next_number()});
}

ServiceStatus::Conditions Service::conditions() const {
  const bool notify_failing =
      std::any_of(notifiers_.begin(), notifiers_.end(), [](const NotifyOutput* n) { return n->failing(); });
  return {alert_log_ && alert_log_->failing(), fan_out_->hot_standby() && !fan_out_->active(),
          pair_ && pair_->syncing(), clock_.unreachable(), notify_failing};
}

void Service::on_alert(const AlertEvent& event) {
  last_alert_seq_ = event.seq;
  intake_->alert_emitted();
  fan_out_->alert(event);
  if (pair_) pair_->own_alert(event);
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
  const auto now = std::chrono::steady_clock::now();
  return clock_.at(pipeline_.statistics().last_data_time, status_.seconds_since_applied(now), now);
}

void Service::tick() {
  intake_->flush_record_file();
  if (websockets_) websockets_->flush(pipeline_.now(), last_alert_seq_);
  // Only a feed silent for a whole tick moves the clock on, so that its tracks time out.
  const auto now = std::chrono::steady_clock::now();
  const std::optional<double> due = clock_.tick(pipeline_.statistics().last_data_time,
                                                status_.seconds_since_applied(now), now, config_.service.tick_interval_s);
  if (due) pipeline_.advance_to(*due);
}

void Service::alive() {
  const auto now = std::chrono::steady_clock::now();
  std::uint64_t input_losses = 0;
  for (const auto& input : inputs_) {
    const protocol::InputStatistics figures = input->statistics();
    input_losses += figures.datagrams_dropped + figures.messages_dropped;
  }
  status_.sample(now, input_losses);
  fan_out_->alive({status_.alive(now, conditions()), data_clock_now(), last_alert_seq_});
}

void Service::wait_for_signal() {
  signals_.async_wait([this](const boost::system::error_code& ec, int signal) {
    if (ec) return;
    if (signal == SIGHUP) {
      reload_configuration(options_.config_path, options_.log_level_override, config_, *subscribers_, http_.get());
      wait_for_signal();
      return;
    }
    spdlog::info("kewd: {} received, shutting down", signal == SIGTERM ? "SIGTERM" : "SIGINT");
    shutdown();
  });
}

void Service::shutdown() {
  if (stopping_) return;
  stopping_ = true;
  sd_notify(0, "STOPPING=1");
  for (auto& input : inputs_) input->stop();
  // Records already taken are judged, and their alerts sent, before subscribers go.
  intake_->flush();
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
  if (clock_.replay_ended() || stopping_) return;
  clock_.end_of_replay();
  pipeline_.end_of_input();
  const auto& input = inputs_.front()->config();
  spdlog::info("replay of {} ended: {} records, {} alerts opened, {} active; {}", input.address,
               pipeline_.statistics().records, pipeline_.alerts().counters().opened, pipeline_.alerts().active_count(),
               options_.exit_at_end ? "exiting (--exit-at-end)" : "serving the last state until SIGINT or SIGTERM");
  if (options_.exit_at_end) shutdown();
}

ReportedParts Service::reported() const {
  return {pipeline_, status_, conditions(), last_alert_seq_, inputs_, *intake_, *fan_out_, *subscribers_, pair_.get(),
          http_.get()};
}

http::HttpSource Service::http_source() {
  http::HttpSource source;
  source.tracks = [this] { return views_.tracks(); };
  source.alerts = [this] { return views_.alerts(); };
  source.status = [this] { return views_.status(); };
  source.zones = [this] { return views_.zones(); };
  source.aerodromes = config_.pipeline.eligibility.aerodromes;
  source.volumes = std::make_shared<const std::vector<volume::WatchedVolume>>(pipeline_.config().volumes);
  source.snapshot = [this] { return views_.snapshot(); };
  source.metrics = [this] { return gather_metrics(reported()); };
  source.acknowledge = [this](const protocol::AckRequest& request, std::string_view client) {
    return acknowledge("web", client, request.all ? std::nullopt : std::optional<std::string_view>(request.id));
  };
  return source;
}

}  // namespace kew::daemon
