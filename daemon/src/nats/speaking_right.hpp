#pragma once
// Hot standby's right to speak (design §5.9): written by the lease's thread and its
// connection's callbacks, read by every thread that sends (the service's gate, the NATS
// publisher's outbox). It holds the lease revision of the current holding, the fencing
// token every publication carries, and the steady-clock moment until which the last
// renewal the server took guarantees that no other instance can hold the lease. A thread
// that wakes from a stall finds that moment passed and says nothing more.
//
// The bus away: when every NATS server is lost while that moment has not passed, no
// other instance can take the lease either until a server answers again (it lives on
// the servers), so the outputs that do not need NATS keep speaking (may_speak) while
// NATS publication waits for a renewal (may_publish). The first answer decides: the
// holding renewed or taken again, or given up when another instance holds it.
//
// A lapse seen by the outputs ends the holding: the gate in front of the outputs closes
// when it finds that the right no longer vouches (keep_speaking), and a renewal the
// server takes a moment later must not leave the lease held by an instance whose outputs
// are shut; the lease thread gives the holding up when it finds it lapsed.

#include <atomic>
#include <chrono>
#include <cstdint>

namespace kew::daemon {

class SpeakingRight {
 public:
  using Clock = std::chrono::steady_clock;

  /// The lease is held at `revision` (≥ 1) until `until`; the bus answers.
  void hold(std::uint64_t revision, Clock::time_point until) {
    until_ns_ = ns(until);
    bus_away_ = false;
    revision_ = revision;
  }
  void release() {
    revision_ = 0;
    bus_away_ = false;
    lapsed_ = false;
  }

  /// Every server was lost at `at`: while the holding vouched for that moment, the
  /// outputs that do not need NATS go on speaking until the lease thread hears the bus.
  void bus_lost(Clock::time_point at) {
    if (revision_.load() != 0 && ns(at) < until_ns_.load()) bus_away_ = true;
  }
  /// Speaking on the strength of a holding the bus cannot confirm or end (see above).
  bool bus_away() const { return revision_.load() != 0 && bus_away_.load(); }

  /// The outputs kew serves itself (stream, CAT004, Modbus, map, alert log): held, and
  /// the last renewal still vouches for now or the bus went away while it did.
  bool may_speak(Clock::time_point now = Clock::now()) const {
    return may_publish(now) || bus_away();
  }
  /// may_speak(), for the one gate in front of the outputs, which closes on a false: a
  /// holding found not vouching is marked lapsed (see lapsed()).
  bool keep_speaking(Clock::time_point now = Clock::now()) {
    if (may_speak(now)) return true;
    if (revision_.load() != 0) lapsed_ = true;
    return false;
  }
  /// The outputs stopped on this holding: the lease thread is to give it up, whatever a
  /// later renewal says. Cleared by release().
  bool lapsed() const { return lapsed_.load(); }

  /// Publication on the bus: held, and the last renewal still vouches for now.
  bool may_publish(Clock::time_point now = Clock::now()) const {
    return revision_.load() != 0 && ns(now) < until_ns_.load();
  }
  /// The revision of the holding (0: not held): the fencing token.
  std::uint64_t revision() const { return revision_.load(); }

 private:
  static std::int64_t ns(Clock::time_point t) {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(t.time_since_epoch()).count();
  }

  std::atomic<std::uint64_t> revision_{0};
  std::atomic<std::int64_t> until_ns_{0};
  std::atomic<bool> bus_away_{false};
  std::atomic<bool> lapsed_{false};
};

}  // namespace kew::daemon
