#pragma once
// The JSON documents of kewd's live state (design §5.8): what GET /api/tracks, /alerts,
// /status, /zones and /snapshot answer and the NATS tracks subject carries, each written
// by the protocol's encoders from the pipeline and the service's status.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "kew/pipeline/pipeline.hpp"
#include "kew/protocol/encoders/alert_json.hpp"

namespace kew::daemon {

class LiveViews {
 public:
  struct Sources {
    /// The stream's sequence number every object carries.
    std::function<std::uint64_t()> seq;
    /// The ALIVE figures now.
    std::function<protocol::AliveStatus()> alive;
    /// The data clock now (UTC s).
    std::function<double()> data_clock;
  };
  /// `pipeline` outlives this.
  LiveViews(const Pipeline& pipeline, Sources sources) : pipeline_(pipeline), sources_(std::move(sources)) {}

  /// TRACKS: every live track (in a kinetic engine), in slot order.
  std::string tracks() const;
  /// ALERTS: the active alerts, most severe first.
  std::string alerts() const;
  /// ALIVE with the data clock and the wall clock.
  std::string status() const;
  std::string zones() const;
  /// Every live track, every active alert and ALIVE, as one array.
  std::string snapshot() const;

 private:
  std::vector<const track::Track*> live_tracks() const;

  const Pipeline& pipeline_;
  Sources sources_;
};

}  // namespace kew::daemon
