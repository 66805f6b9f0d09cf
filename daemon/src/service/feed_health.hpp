#pragma once
// Whether kewd's picture of the traffic can be trusted (design §6.6). A safety net that
// has silently stopped seeing traffic, or some of it, is worse than one that says so:
// every interface (ALIVE, Modbus discrete inputs 4-5 and register 4, CAT004 Alive)
// reports this verdict.

#include "kew/protocol/encoders/alert_json.hpp"

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>

namespace kew::daemon {

class FeedHealth {
 public:
  using Clock = std::chrono::steady_clock;

  /// `stale_after_s`: no accepted record for this long is a stale feed (> 0 s).
  explicit FeedHealth(double stale_after_s) : stale_after_s_(stale_after_s) {}

  /// A record was accepted by the pipeline at `now`.
  void accepted(Clock::time_point now) { last_accepted_ = now; }

  /// At every ALIVE (once a second by default): the running totals of records offered to
  /// the pipeline and accepted by it, and of the datagrams and messages the inputs lost
  /// before kewd read them. The last kWindow samples judge "most records refused" and
  /// "an input is dropping": a loss keeps the verdict for kWindow samples.
  void sample(std::uint64_t offered, std::uint64_t accepted, std::uint64_t input_losses);

  protocol::HealthReason reason(Clock::time_point now) const;

  /// Seconds since the last accepted record; nullopt before the first.
  std::optional<double> seconds_since_accepted(Clock::time_point now) const;

  /// Under this many records offered in the window, refusals are too few to judge.
  static constexpr std::uint64_t kMinOffered = 10;
  static constexpr std::size_t kWindow = 10;

 private:
  double stale_after_s_;
  std::optional<Clock::time_point> last_accepted_;
  struct Totals {
    std::uint64_t offered = 0, accepted = 0, input_losses = 0;
  };
  std::array<Totals, kWindow + 1> history_{};  // running totals, oldest overwritten
  std::size_t samples_ = 0;
};

}  // namespace kew::daemon
