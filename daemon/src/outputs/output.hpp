#pragma once
// What every kewd output implements (design §3.4): the alert log, the subscriber stream,
// the WebSocket clients, NATS, CAT004, the Modbus alarm map and the notifiers each receive the service's
// events through this one interface, from the FanOut that encodes each event once.

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>

#include "kew/alert/alert_event.hpp"
#include "kew/protocol/encoders/alert_json.hpp"
#include "kew/protocol/encoders/statistics_json.hpp"

namespace kew::daemon {

/// An event's JSON line (with its '\n'), encoded once and shared by every output that
/// sends it; outputs that queue it keep the pointer, not a copy.
using SharedLine = std::shared_ptr<const std::string>;

/// Who reads an output, which decides what hot standby lets through to it (design §5.9).
enum class Audience : std::uint8_t {
  /// This instance's own record (the alert log, a notifier's outbox): every alert event,
  /// active or standby.
  Journal,
  /// Clients connected to this instance (subscribers, WebSocket): alerts and
  /// acknowledgements only while active; its ALIVE always, so that a client of a standby
  /// sees "standby" rather than a quiet sky.
  OwnClients,
  /// Shared by the pair (NATS, CAT004's destination, the Modbus panel): only while active.
  Shared,
};

/// The once-a-second status: the ALIVE figures, the data clock when sent (UTC s) and the
/// stream's sequence number the object carries.
struct AliveEvent {
  protocol::AliveStatus status;
  double data_clock_t = 0.0;
  std::uint64_t seq = 0;
};

class Output {
 public:
  virtual ~Output() = default;
  /// For logs: "alert log", "nats", ...
  virtual std::string_view name() const = 0;
  virtual Audience audience() const = 0;
  /// What it serves, for the log at start ("alert log: PATH"); "" says nothing.
  virtual std::string describe() const { return {}; }
  /// An alert event (new, update or end), in seq order; `line` is its ALERT object.
  virtual void alert(const AlertEvent& event, const SharedLine& line) = 0;
  /// Alerts acknowledged by an operator; `line` is the ACK object, `seq` the stream's
  /// sequence number it carries.
  virtual void acknowledgement(const protocol::Acknowledgement& ack, std::uint64_t seq, const SharedLine& line) = 0;
  /// The once-a-second status; `line` is the ALIVE object.
  virtual void alive(const AliveEvent& alive, const SharedLine& line) = 0;
  /// Hot standby: this instance became the active one (true) or a standby (false).
  virtual void role_changed(bool /*active*/) {}
  /// Hot standby's takeover, after the kept events and before any later event: `active`
  /// is every active alert as of `seq`, the view of clients that were sent no alert
  /// event while standby (design §5.9).
  virtual void resynchronise(std::span<const AlertEvent> /*active*/, std::uint64_t /*seq*/) {}
  /// Its part of ?STATS and /metrics.
  virtual void report(protocol::ServiceStatistics& /*statistics*/) const {}
};

}  // namespace kew::daemon
