#pragma once
// Hot standby's right to speak (design §5.9): written by the lease's thread, read by
// every thread that sends (the service's gate, the NATS publisher's outbox). It holds the
// lease revision of the current holding, the fencing token every publication carries, and
// the steady-clock moment until which the last renewal the server took guarantees that no
// other instance can hold the lease. A thread that wakes from a stall finds that moment
// passed and says nothing more.

#include <atomic>
#include <chrono>
#include <cstdint>

namespace kew::daemon {

class SpeakingRight {
 public:
  using Clock = std::chrono::steady_clock;

  /// The lease is held at `revision` (≥ 1) until `until`.
  void hold(std::uint64_t revision, Clock::time_point until) {
    until_ns_ = std::chrono::duration_cast<std::chrono::nanoseconds>(until.time_since_epoch()).count();
    revision_ = revision;
  }
  void release() { revision_ = 0; }

  /// Held, and the last renewal still vouches for now.
  bool may_speak(Clock::time_point now = Clock::now()) const {
    return revision_.load() != 0 &&
           std::chrono::duration_cast<std::chrono::nanoseconds>(now.time_since_epoch()).count() < until_ns_.load();
  }
  /// The revision of the holding (0: not held): the fencing token.
  std::uint64_t revision() const { return revision_.load(); }

 private:
  std::atomic<std::uint64_t> revision_{0};
  std::atomic<std::int64_t> until_ns_{0};
};

}  // namespace kew::daemon
