#pragma once
// Which record times may move the data clock (design §4.1). One misdated record (a date
// in 2100, a flipped bit in an ASTERIX time of day) must not carry the clock into the
// future: every track would time out and every later record be refused as too late.

#include "kew/track/track_report.hpp"

#include <cstddef>
#include <vector>

namespace kew::track {

/// Holds the records that are more than `max_jump_s` ahead of the clock instead of
/// applying them. A later record *contradicts* a held one when it would have been too
/// late (more than `max_lateness_s` behind) had the held one moved the clock: the held
/// record is then refused. `confirm` held records that nothing contradicted show the
/// data really jumped (a gap in a recording, a feed back after an outage): they are
/// released and applied in their order, so a real jump delays records but loses none.
class TimeGuard {
 public:
  /// `max_jump_s`, `max_lateness_s` ≥ 0 s; `confirm` ≥ 1 record.
  TimeGuard(double max_jump_s, double max_lateness_s, std::size_t confirm);

  /// True when a record at `t` may not move a clock at `clock` (both UTC s) at once.
  bool ahead(double t, double clock) const { return t > clock + max_jump_s_; }

  /// Moves the held records that a record at `t` contradicts into `refused`.
  void refuse_contradicted(double t, std::vector<TrackReport>& refused);

  /// Holds a record that is ahead; true when `confirm` records are held (release them).
  bool hold(const TrackReport& r);

  /// Moves every held record into `released`, in arrival order.
  void release(std::vector<TrackReport>& released);

  /// Moves the held records no longer ahead of `clock` into `released`, in arrival order.
  void release_reached(double clock, std::vector<TrackReport>& released);

  std::size_t held() const { return held_.size(); }

 private:
  double max_jump_s_;
  double max_lateness_s_;
  std::size_t confirm_;
  std::vector<TrackReport> held_;
};

}  // namespace kew::track
