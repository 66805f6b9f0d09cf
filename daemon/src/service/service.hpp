#pragma once
// kewd's service: one Boost.Asio I/O thread runs the inputs, the pipeline (so alerts
// are deterministic for a given record order) and the outputs behind one fan-out
// (design §3.3, §3.4); the Modbus server has its own thread and receives copies of the alarm
// state.

#include <chrono>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <boost/asio/io_context.hpp>
#include <boost/asio/signal_set.hpp>
#include <boost/asio/steady_timer.hpp>

#include "../http/http_server.hpp"
#include "../http/metrics.hpp"
#include "../inputs/inputs.hpp"
#include "../outputs/fan_out.hpp"
#include "../standby/pair_origin.hpp"
#include "continuity.hpp"
#include "data_clock.hpp"
#include "housekeeping.hpp"
#include "live_views.hpp"
#include "record_intake.hpp"
#include "self_report.hpp"
#include "service_status.hpp"
#include "subscribers.hpp"
#include "kew/daemon/config.hpp"
#include "kew/pipeline/pipeline.hpp"

namespace kew::daemon {

class AlertLogOutput;
class PairMember;
struct PairCheckpoint;
class SpeakingRight;
class ModbusOutput;
class NatsOutput;
class NotifyOutput;
class WebSocketOutput;

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
  void open_outputs();
  void open_inputs();
  /// A record decoded by inputs_[input].
  void on_report(const TrackReport& report, std::size_t input);
  void on_alert(const AlertEvent& event);
  /// Before the inputs start: the START line, the End ("restart") of every alert the
  /// last run left open, and the numbering continued (design §4.7). Hot standby: the
  /// pair's stream, not this instance's log, says what is open; the numbering and the
  /// inputs wait for the pair's origin (begin_pair).
  void begin_run();
  /// Hot standby: where this instance begins is known (the pair's origin, or its latest
  /// checkpoint, whose state the pipeline takes); the inputs start (design §5.9).
  void begin_pair(const PairOrigin& origin, const PairCheckpoint* checkpoint);
  void start_inputs();
  void save_numbering();
  void start_housekeeping();
  /// What the status needs beyond the feed: the alert log failing, standby.
  ServiceStatus::Conditions conditions() const;
  void tick();
  void alive();
  /// Coil 0 written 1 (posted from the Modbus thread), or POST /api/ack, through interface
  /// `by` by `client` ("HOST:PORT" of its socket): every active alert, or only `id`.
  /// Returns the ids acknowledged.
  std::vector<std::string> acknowledge(std::string_view by, std::string_view client,
                                       std::optional<std::string_view> id = std::nullopt);
  /// The HTTP server's view of the service (design §5.8).
  http::HttpSource http_source();
  /// The parts ?STATS and /metrics report on (self_report.hpp).
  ReportedParts reported() const;
  void wait_for_signal();
  void shutdown();
  /// The replayed file ended: applies what the time guard holds, as kew-replay does at
  /// its end, and keeps serving (or shuts down with exit_at_end).
  void end_replay();
  /// The data clock now (DataClock::at).
  double data_clock_now() const;

  boost::asio::io_context io_;
  boost::asio::signal_set signals_;
  boost::asio::steady_timer shutdown_timer_;
  Housekeeping housekeeping_;
  Config config_;
  ServiceOptions options_;
  Pipeline pipeline_;
  RunContinuity continuity_;
  std::unique_ptr<SubscriberServer> subscribers_;
  std::unique_ptr<http::HttpServer> http_;
  std::vector<std::unique_ptr<Input>> inputs_;
  std::unique_ptr<RecordIntake> intake_;
  std::unique_ptr<PairMember> pair_;  // hot standby only, from the start of the run
  std::shared_ptr<SpeakingRight> speaking_right_;  // hot standby only
  std::unique_ptr<FanOut> fan_out_;
  // The outputs the service also asks for more than events (owned by fan_out_).
  AlertLogOutput* alert_log_ = nullptr;
  ModbusOutput* modbus_ = nullptr;
  NatsOutput* nats_ = nullptr;
  WebSocketOutput* websockets_ = nullptr;
  std::vector<NotifyOutput*> notifiers_;
  std::string start_line_;  // this run's START object, for each new subscriber

  ServiceStatus status_;
  DataClock clock_;
  LiveViews views_;
  std::uint64_t last_alert_seq_ = 0;
  bool stopping_ = false;
};

}  // namespace kew::daemon
