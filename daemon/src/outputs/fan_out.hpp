#pragma once
// The fan-out of kewd's events (design §3.4): each alert, acknowledgement and status is
// encoded once and handed to every output, through the standby gate for those that hot
// standby silences (Audience).

#include <cstdint>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "output.hpp"
#include "standby_gate.hpp"

namespace kew::daemon {

class FanOut {
 public:
  /// Called after the gate opened (true) or closed (false), outputs already told.
  using RoleHandler = std::function<void(bool active)>;

  explicit FanOut(StandbyGate gate, RoleHandler on_role = {});
  FanOut(const FanOut&) = delete;
  FanOut& operator=(const FanOut&) = delete;

  /// Adds an output and returns it (owned here) for the caller's own uses.
  template <class O>
  O& add(std::unique_ptr<O> output) {
    O& ref = *output;
    outputs_.push_back(std::move(output));
    return ref;
  }
  /// Tells every output its first role; before the first event.
  void start();

  /// An alert event: to the journal always, to the others when the gate lets it pass.
  void alert(const AlertEvent& event);
  /// An acknowledgement, `seq` the stream's sequence number it carries: only while active.
  void acknowledgement(const protocol::Acknowledgement& ack, std::uint64_t seq);
  /// The status: to this instance's own clients always, to the shared outputs while active.
  void alive(const AliveEvent& alive);

  bool active() const { return gate_.open(); }
  bool hot_standby() const { return gate_.hot_standby(); }
  /// Events up to this seq were published by the previous active (hot standby).
  std::uint64_t floor() const { return gate_.floor(); }
  /// Opens the gate (the lease is ours; the previous active published up to `published`),
  /// sends the kept events after it, then `active` (every active alert as of the stream's
  /// `seq`) to the outputs whose clients were sent no alert event while standby. Returns
  /// how many events were sent.
  std::size_t take_over(std::uint64_t published, std::span<const AlertEvent> active, std::uint64_t seq);
  /// Closes the gate (the lease is lost); false when it was closed.
  bool step_down();

  /// Events up to this seq are not written to the journal again (a hot-standby instance
  /// judging the feed again from the pair's origin computes events its log already has).
  void set_journal_floor(std::uint64_t seq) { journal_floor_ = seq; }

  /// Every output's part of ?STATS and /metrics.
  void report(protocol::ServiceStatistics& statistics) const;

 private:
  void send_alert(const AlertEvent& event, const SharedLine& line, bool to_journal, bool to_others);
  void tell_role(bool active);

  StandbyGate gate_;
  RoleHandler on_role_;
  std::uint64_t journal_floor_ = 0;
  std::vector<std::unique_ptr<Output>> outputs_;
};

}  // namespace kew::daemon
