#pragma once
// The subscriber stream (design §5.3) as an output: each event's line to the sessions
// that watch (and, for alerts, that want that alert).

#include "../service/subscribers.hpp"
#include "output.hpp"

namespace kew::daemon {

class SubscriberOutput final : public Output {
 public:
  /// `server` outlives this output (the service owns both).
  explicit SubscriberOutput(SubscriberServer& server) : server_(server) {}

  std::string_view name() const override { return "subscribers"; }
  Audience audience() const override { return Audience::OwnClients; }
  void alert(const AlertEvent& event, const SharedLine& line) override { server_.broadcast_alert(event, line); }
  void acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine& line) override {
    server_.broadcast_to_watchers(line);
  }
  void alive(const AliveEvent&, const SharedLine& line) override { server_.broadcast_to_watchers(line); }
  void resynchronise(std::span<const AlertEvent> active, std::uint64_t seq) override {
    server_.send_snapshot_to_watchers(active, seq);
  }
  void report(protocol::ServiceStatistics& statistics) const override {
    statistics.subscribers_now = server_.sessions();
    statistics.subscribers = server_.figures();
  }

 private:
  SubscriberServer& server_;
};

}  // namespace kew::daemon
