#pragma once
// Whether a hot-standby instance is in step with the active (design §5.9): both judge the
// same feed from the pair's origin, so the events this instance computes must be the ones
// the active published, seq for seq. This class holds both sides of that comparison: the
// active's events and acknowledgements read back from the alert stream, and this
// instance's own events. It says when this instance has caught up (it may then take
// over), when it has departed from the active (it may not), which of the active's
// acknowledgements are due, and which alerts the active left open.
//
// The comparison is of each event's identity (id, number, state, severity, end reason):
// what a takeover must continue. The figures are the pipeline's (equal by determinism),
// and the acknowledged flag of an event computed before the acknowledgement reached this
// instance may differ without any consequence for the numbering.
//
// Not thread-safe: the service's I/O thread owns it.

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include "kew/alert/alert_event.hpp"

namespace kew::daemon {

class StandbySync {
 public:
  enum class State : std::uint8_t {
    Syncing,    ///< catching up with the active: may not take over
    InStep,     ///< every event so far equals the active's, and none is missing
    OutOfStep,  ///< an event differs from the active's: may take over only unsynced
  };

  /// The pair's numbering at its origin (PairOrigin::last_seq): this instance's and the
  /// stream's events both continue from it.
  explicit StandbySync(std::uint64_t origin_last_seq);

  /// Begun from a checkpoint (design §5.9): the alerts open in its state are the
  /// active's open alerts at that point (its stream is read from after it).
  void seed_open(const std::vector<AlertEvent>& open);
  /// The active's event, in stream order.
  void active_alert(const AlertEvent& event);
  /// The active's acknowledgement of `ids`, published when its last event was `seq`.
  void active_acknowledgement(std::uint64_t seq, std::vector<std::string> ids);
  /// The stream reader has read every message the stream held when it started; the last
  /// of them carried `seq` (the origin's when none did).
  void stream_read_up_to(std::uint64_t seq);

  /// This instance's event (also while active: it then simply stays in step).
  void own_alert(const AlertEvent& event);
  /// The acknowledgements due now that this instance's last event is `own_seq`: each the
  /// ids of one ACK, in stream order, taken out. Applied by the caller.
  std::vector<std::vector<std::string>> due_acknowledgements();

  State state() const { return state_; }
  bool in_step() const { return state_ == State::InStep; }
  /// The first difference seen (empty while none): for the log.
  const std::string& departure() const { return departure_; }
  std::uint64_t own_seq() const { return own_seq_; }
  std::uint64_t active_seq() const { return active_seq_; }

  /// The alerts the active's stream has open (its last event of each), ordered by the
  /// seq of that event: what an unsynced takeover must end, as it cannot continue them.
  std::vector<AlertEvent> open_on_active() const;

 private:
  struct Identity {
    std::string id;
    std::uint16_t number = 0;
    AlertState state = AlertState::New;
    Severity severity = Severity::None;
    AlertEndReason reason = AlertEndReason::None;
    bool operator==(const Identity&) const = default;
  };
  static Identity identity(const AlertEvent& event);
  static std::string describe(std::uint64_t seq, const Identity& identity);
  void compare(std::uint64_t seq, const Identity& mine, const Identity& theirs);
  void judge();
  void depart(std::string why);

  State state_ = State::Syncing;
  std::string departure_;
  std::uint64_t own_seq_;
  std::uint64_t active_seq_;
  std::optional<std::uint64_t> stream_read_to_;
  // Events one side has and the other not yet, by seq: only one of the two is non-empty
  // at a time (the side that is ahead).
  std::map<std::uint64_t, Identity> own_ahead_;
  std::map<std::uint64_t, Identity> active_ahead_;
  std::deque<std::pair<std::uint64_t, std::vector<std::string>>> acknowledgements_;
  // The active's open alerts: id → its last event.
  std::unordered_map<std::string, AlertEvent> open_on_active_;
};

}  // namespace kew::daemon
