#pragma once
// kewd's service: one Boost.Asio I/O thread runs the inputs, the pipeline (so alerts
// are deterministic for a given record order), the subscriber stream and the outputs;
// the Modbus server has its own thread and receives copies of the alarm state.

#include <chrono>
#include <deque>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "../http/http_server.hpp"
#include "../http/metrics.hpp"
#include "cat004_sender.hpp"
#include "continuity.hpp"
#include "feed_health.hpp"
#include "inputs.hpp"
#include "line_file.hpp"
#include "subscribers.hpp"
#include "kew/daemon/config.hpp"
#include "kew/pipeline/pipeline.hpp"

namespace kew::daemon {

class ModbusServer;
class AckFollower;
class LeaderLease;
class NatsPublisher;


struct ServiceOptions {
  std::string config_path;  ///< re-read on SIGHUP; empty: built-in defaults
  /// Serve subscribers, Modbus and loopback inputs on every interface (check_config has
  /// allowed any listen address).
  bool listen_any = false;
  /// kewd -l: the log level stays this one whatever a reloaded file says.
  std::optional<LogLevel> log_level_override;
  /// kewd --replay: the configuration's one input is the recording (apply_replay). No
  /// wall-clock ceiling on data times and no state file; the data clock runs at
  /// `replay_speed` × wall time between records (0: records alone move it, as in
  /// kew-replay) and stops when the file ends.
  bool replay = false;
  double replay_speed = 1.0;
  bool exit_at_end = false;  ///< with replay: shut down when the file ends
};

class Service {
 public:
  /// Binds every socket and opens every file; throws std::exception on failure.
  Service(Config config, ServiceOptions options);
  ~Service();
  /// Runs until SIGTERM or SIGINT, then shuts down cleanly. Returns the exit status.
  int run();

 private:
  /// A record decoded by inputs_[input].
  void on_report(const TrackReport& report, std::size_t input);
  /// Runs the pipeline's pending batch (posted after the handler that took its records).
  void flush_pipeline();
  void on_alert(const AlertEvent& event);
  /// An alert event to every output when active; kept for a takeover when standby.
  void emit_or_keep(const AlertEvent& event);
  /// To the subscribers, the map, CAT004 and NATS, unless the previous active sent it.
  void emit(const AlertEvent& event);
  /// Hot standby (design §5.9): the lease is this instance's; the previous active
  /// published up to seq `published`. Sends the kept events after it and serves.
  void take_over(std::uint64_t published);
  /// Standby: the active acknowledged these alerts.
  void follow_acknowledgements(const std::vector<std::string>& ids);
  /// The lease is lost: computes on, silently.
  void step_down();
  void start_modbus();
  /// Before the inputs start: the run id, the START line, the End ("restart") of every
  /// alert the last run left open, and the numbering continued (design §4.7).
  void begin_run();
  /// Once a second: retries a failing alert log, syncs it (alert_log_sync "interval"),
  /// saves the numbering when it moved.
  void schedule_housekeeping();
  void save_numbering();
  /// The verdict every interface reports: the alert log's, then the feed's.
  protocol::HealthReason health(std::chrono::steady_clock::time_point now) const;
  void schedule_tick();
  void schedule_alive();
  void schedule_watchdog(std::chrono::microseconds period);
  void tick();
  void alive();
  void schedule_modbus_publish();
  void publish_modbus();
  /// Coil 0 written 1 (posted from the Modbus thread), or POST /api/ack, through interface
  /// `by` by `client` ("HOST:PORT" of its socket): every active alert, or only `id`.
  /// Returns the ids acknowledged.
  std::vector<std::string> acknowledge(std::string_view by, std::string_view client,
                                       std::optional<std::string_view> id = std::nullopt);
  /// The HTTP server's view of the service (design §5.8).
  http::HttpSource http_source();
  /// Sends the tracks updated since the last tick and the batch to WebSocket clients.
  void flush_websockets();
  protocol::AliveStatus alive_status(std::chrono::steady_clock::time_point now) const;
  protocol::ServiceStatistics service_statistics() const;
  std::string metrics_text() const;
  void wait_for_signal();
  void reload();
  void shutdown();
  /// The replayed file ended: applies what the time guard holds, as kew-replay does at
  /// its end, and keeps serving (or shuts down with exit_at_end).
  void end_replay();
  std::string stats_json() const;
  /// The TRACKS object of every live track (GET /api/tracks, [nats] tracks_subject).
  std::string tracks_json() const;
  void schedule_nats_tracks();
  /// The subject token of the zone that judges the event's pair ("single" in single mode).
  std::string nats_zone(const AlertEvent& event) const;
  double data_clock_now() const;

  boost::asio::io_context io_;
  boost::asio::signal_set signals_;
  boost::asio::steady_timer tick_timer_;
  boost::asio::steady_timer alive_timer_;
  boost::asio::steady_timer watchdog_timer_;
  boost::asio::steady_timer shutdown_timer_;
  boost::asio::steady_timer modbus_timer_;
  boost::asio::steady_timer housekeeping_timer_;
  boost::asio::steady_timer nats_tracks_timer_;
  Config config_;
  ServiceOptions options_;
  Pipeline pipeline_;
  std::unique_ptr<SubscriberServer> subscribers_;
  std::vector<std::unique_ptr<Input>> inputs_;
  std::unique_ptr<LineFile> alert_log_;
  std::unique_ptr<LineFile> record_file_;
  std::unique_ptr<StateFile> state_file_;  // none without a state directory
  std::string run_id_;
  std::string start_line_;  // this run's START object, for each new subscriber
  std::optional<Numbering> saved_;  // as last written to the state file
  std::uint64_t state_errors_ = 0;
  std::unique_ptr<Cat004Sender> cat004_;
  std::unique_ptr<ModbusServer> modbus_;
  std::unique_ptr<http::HttpServer> http_;
  std::unique_ptr<NatsPublisher> nats_;
  std::unique_ptr<LeaderLease> lease_;  // hot standby only
  std::unique_ptr<AckFollower> acks_;   // hot standby only
  /// Serving outputs: always, unless in hot standby without the lease.
  bool active_ = true;
  bool modbus_started_ = false;
  /// Events up to this seq were published by the previous active: not sent again.
  std::uint64_t emit_floor_ = 0;
  /// A standby's recent events, for a takeover.
  std::deque<AlertEvent> history_;
  /// Per input: what /metrics says of it beyond its own statistics.
  struct InputFigures {
    Rejections pipeline_refused;  ///< the pipeline's refusals of its records
    std::optional<double> last_record_unix_s;
  };
  std::vector<InputFigures> input_figures_;
  http::LatencyHistogram latency_;
  /// While a record is processed: when it reached on_report (alert events it causes are
  /// measured from there).
  std::optional<std::chrono::steady_clock::time_point> record_arrival_;
  // The arrival of the first record of the pipeline's pending batch, and whether a
  // flush of it is posted.
  std::optional<std::chrono::steady_clock::time_point> batch_arrival_;
  bool flush_posted_ = false;
  /// Batches the pipeline has run, and how many had run at the last watchdog ping.
  std::uint64_t flushes_ = 0, flushes_at_last_ping_ = 0;
  /// Test-only (docs/testing.md): while this file exists, a batch blocks the pipeline
  /// (KEWD_TEST_STALL_FILE), so that the watchdog's reaction can be tested.
  std::string stall_file_;
  /// Tracks updated since the last tick, for the WebSocket clients (only while any).
  std::vector<track::TrackSlot> ws_tracks_;
  std::vector<bool> ws_track_marked_;
  double started_unix_s_ = 0.0;
  bool modbus_dirty_ = true;  // alarm state changed since the last publish
  std::chrono::steady_clock::time_point last_modbus_publish_{};
  std::string line_;  // scratch for encoding

  std::chrono::steady_clock::time_point started_;
  FeedHealth health_;
  std::uint64_t last_alert_seq_ = 0;
  std::uint64_t accepted_at_last_alive_ = 0;
  std::uint64_t updates_at_last_alive_ = 0;
  std::chrono::steady_clock::time_point last_alive_;
  double records_per_s_ = 0.0;
  double updates_per_s_ = 0.0;
  bool stopping_ = false;
  bool replay_ended_ = false;
};

}  // namespace kew::daemon
