#pragma once
// Hot standby's one gate in front of the outputs (design §5.9): a standby computes every
// alert and lets none through; it keeps its recent events so that, taking over, it sends
// what the previous active had not published.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <vector>

#include "kew/alert/alert_event.hpp"

namespace kew::daemon {

class StandbyGate {
 public:
  /// No hot standby: open from the start, keeps nothing.
  StandbyGate() = default;
  /// Hot standby: closed until take_over(); keeps the last `history` events (≥ 1).
  /// `may_speak` tells whether the lease's last renewal still guarantees that no other
  /// instance is active (called on the service thread).
  StandbyGate(std::size_t history, std::function<bool()> may_speak);

  bool hot_standby() const { return static_cast<bool>(may_speak_); }
  bool open() const { return open_; }
  /// Events up to this seq were published by the previous active.
  std::uint64_t floor() const { return floor_; }

  /// What becomes of an alert event at the gate.
  enum class Passage : std::uint8_t {
    Pass,      ///< open, and not published before: send it
    Hold,      ///< closed, or the previous active published it: kept only
    StepDown,  ///< open, but the lease cannot vouch for it any more: the gate closes
  };
  /// Keeps `event` for a takeover (hot standby) and says whether it passes.
  Passage admit(const AlertEvent& event);
  /// Whether anything else the pair shares (a status, an acknowledgement) may pass now:
  /// open, and the lease still vouches for this instance (else the gate closes).
  Passage speak();

  /// The lease is this instance's; the previous active published up to seq `published`.
  /// Opens the gate and returns the kept events after the floor, to be sent in order;
  /// `lost_before` is the first seq it kept when events between the floor and it were
  /// kept by nobody (0 when none were lost). Idempotent while open: returns nothing.
  struct Takeover {
    std::vector<AlertEvent> to_send;
    std::uint64_t lost_before = 0;
  };
  Takeover take_over(std::uint64_t published);
  /// Closes the gate; false when it was closed already.
  bool step_down();

 private:
  std::function<bool()> may_speak_;
  std::size_t history_limit_ = 0;
  std::deque<AlertEvent> history_;
  bool open_ = true;
  std::uint64_t floor_ = 0;
};

}  // namespace kew::daemon
