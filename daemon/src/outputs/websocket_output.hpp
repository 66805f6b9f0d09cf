#pragma once
// The live map's WebSocket clients (design §5.8) as an output: alert, acknowledgement and
// status objects, and the tracks updated since the last tick, batched into one message a
// tick.

#include <functional>
#include <vector>

#include "../http/http_server.hpp"
#include "kew/track/track_table.hpp"
#include "output.hpp"

namespace kew::daemon {

class WebSocketOutput final : public Output {
 public:
  /// `server` and `tracks` outlive this output (the service owns them).
  WebSocketOutput(http::HttpServer& server, const track::TrackTable& tracks) : server_(server), tracks_(tracks) {}

  std::string_view name() const override { return "websocket"; }
  Audience audience() const override { return Audience::OwnClients; }
  void alert(const AlertEvent&, const SharedLine& line) override { server_.push(*line); }
  void acknowledgement(const protocol::Acknowledgement&, std::uint64_t, const SharedLine& line) override {
    server_.push(*line);
  }
  void alive(const AliveEvent&, const SharedLine& line) override { server_.push(*line); }
  /// An ALERTS object in the next batch: the map replaces its alerts with it.
  void resynchronise(std::span<const AlertEvent> active, std::uint64_t seq) override;

  /// A record updated the track in `slot`: sent at the next flush (only while anyone
  /// watches).
  void track_updated(track::TrackSlot slot);
  /// Once a tick: the updated tracks still live, as at data time `now` with the stream's
  /// `seq`, then the tick's batch to every client.
  void flush(double now, std::uint64_t seq);

 private:
  http::HttpServer& server_;
  const track::TrackTable& tracks_;
  std::vector<track::TrackSlot> updated_;
  std::vector<bool> marked_;
  std::string line_;  // scratch
};

}  // namespace kew::daemon
