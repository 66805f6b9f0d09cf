#include "live_views.hpp"

#include <algorithm>

#include "kew/protocol/encoders/statistics_json.hpp"
#include "kew/util/clocks.hpp"

namespace kew::daemon {

std::vector<const track::Track*> LiveViews::live_tracks() const {
  std::vector<const track::Track*> live;
  const track::TrackTable& tracks = pipeline_.tracks();
  for (track::TrackSlot slot = 0; slot < tracks.slot_end(); ++slot)
    if (tracks[slot].in_use && tracks[slot].in_engine) live.push_back(&tracks[slot]);
  return live;
}

std::string LiveViews::tracks() const {
  std::string out;
  protocol::append_tracks_json(out, live_tracks(), pipeline_.now(), sources_.seq());
  return out;
}

std::string LiveViews::alerts() const {
  std::vector<AlertEvent> active = pipeline_.alerts().snapshot();
  std::stable_sort(active.begin(), active.end(),
                   [](const AlertEvent& a, const AlertEvent& b) { return a.severity > b.severity; });
  std::string out;
  protocol::append_alerts_json(out, active, sources_.seq(), pipeline_.now());
  return out;
}

std::string LiveViews::status() const {
  const double wall = util::unix_now_s();
  std::string out;
  protocol::append_status_json(out, sources_.alive(), sources_.seq(), sources_.data_clock(), wall);
  return out;
}

std::string LiveViews::zones() const {
  std::string out;
  protocol::append_zones_json(out, pipeline_);
  return out;
}

std::string LiveViews::snapshot() const {
  std::string out;
  protocol::append_snapshot_json(out, live_tracks(), pipeline_.alerts().snapshot(), sources_.alive(), pipeline_.now(),
                                 sources_.seq());
  return out;
}

}  // namespace kew::daemon
