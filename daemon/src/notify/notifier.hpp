#pragma once
// One [[notify]] endpoint (design §5.10): the alert events it is given wait in its outbox
// and are posted, one message at a time, by its own thread, so that a slow or dead
// endpoint never holds up the service. Failures are retried with a doubling backoff and
// never sooner than the endpoint asks (Retry-After); messages are paced by
// max_per_minute. It delivers only while active (hot standby: while the lease vouches).

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "kew/daemon/notify_config.hpp"
#include "notify_filter.hpp"
#include "outbox.hpp"
#include "progress_store.hpp"

namespace kew::daemon {

class HttpClient;
class RepeatedFailure;

/// What ?STATS and /metrics say of a notifier.
struct NotifierFigures {
  std::uint64_t delivered = 0;  ///< messages the endpoint took (2xx)
  std::uint64_t failures = 0;   ///< attempts that failed (no answer, or not 2xx)
  std::uint64_t dropped = 0;    ///< events dropped from a full outbox
  std::uint64_t queued = 0;     ///< events waiting
  std::uint64_t outbox_write_errors = 0;
  bool failing = false;  ///< failing, with an event waiting longer than failing_after_s
};

class Notifier {
 public:
  /// `outbox_path` "": kept in memory only. `store`: hot standby's shared progress (null
  /// without). `may_speak`: whether a delivery may go now (hot standby's lease; null:
  /// always). Reads the URL and token files (throws std::runtime_error naming the file
  /// when it cannot) and the outbox of an earlier run.
  Notifier(NotifyConfig config, std::string outbox_path, std::unique_ptr<ProgressStore> store,
           std::function<bool()> may_speak);
  ~Notifier();
  Notifier(const Notifier&) = delete;
  Notifier& operator=(const Notifier&) = delete;

  const NotifyConfig& config() const { return config_; }
  /// An alert event in seq order, `line` its ALERT object (the caller's thread).
  void alert(const AlertEvent& event, const std::string& line);
  /// Delivers from now on (true), or keeps what comes without delivering (false).
  void set_active(bool active);
  NotifierFigures figures() const;
  /// At shutdown: stops the thread (a delivery in flight is abandoned and waits in the
  /// outbox) and forces the outbox to the disk; says what is left.
  void stop();

 private:
  void run();
  /// Delivers `entry` (a copy); true when the endpoint took it, else `wait_s` is what
  /// the endpoint asked to wait (0: nothing asked).
  bool deliver(const OutboxEntry& entry, HttpClient& client, RepeatedFailure& failure, double& wait_s);
  /// Reads the shared progress and forgets what it covers; false when it cannot be read.
  bool catch_up_with_store();
  void save_progress();

  NotifyConfig config_;
  std::string url_;
  std::string token_;
  std::unique_ptr<ProgressStore> store_;
  std::function<bool()> may_speak_;
  NotifyFilter filter_;  // the caller's thread only

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  Outbox outbox_;
  bool active_ = false;
  bool caught_up_ = false;  // the shared progress was read since this instance became active
  bool stopping_ = false;
  std::atomic<bool> abort_{false};
  std::uint64_t delivered_ = 0;
  std::uint64_t failures_ = 0;
  std::uint64_t consecutive_failures_ = 0;
  std::thread thread_;
};

}  // namespace kew::daemon
