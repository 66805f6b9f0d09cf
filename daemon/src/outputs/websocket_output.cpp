#include "websocket_output.hpp"

namespace kew::daemon {

void WebSocketOutput::track_updated(track::TrackSlot slot) {
  if (!server_.has_websockets()) return;
  if (marked_.size() <= slot) marked_.resize(slot + 1, false);
  if (marked_[slot]) return;
  marked_[slot] = true;
  updated_.push_back(slot);
}

void WebSocketOutput::resynchronise(std::span<const AlertEvent> active, std::uint64_t seq) {
  if (!server_.has_websockets()) return;
  line_.clear();
  protocol::append_alerts_snapshot_json(line_, active, seq);
  server_.push(line_);
}

void WebSocketOutput::flush(double now, std::uint64_t seq) {
  const bool watched = server_.has_websockets();
  for (const track::TrackSlot slot : updated_) {
    marked_[slot] = false;
    const track::Track& track = tracks_[slot];
    if (!watched || !track.in_use || !track.in_engine) continue;
    line_.clear();
    protocol::append_live_track_json(line_, track, now, seq);
    server_.push(line_);
  }
  updated_.clear();
  server_.flush();
}

}  // namespace kew::daemon
