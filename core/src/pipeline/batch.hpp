#pragma once
// What the track stage hands the zones and the alert stage (design §3.3): the records
// of one batch as track snapshots and steps, in record order.

#include <cstdint>
#include <vector>

#include "kew/track/track_table.hpp"
#include "kew/zone/zone.hpp"
#include "pair_judge.hpp"

namespace kew::pipeline {

/// What the zones and the alert stage know of a track after one of its records.
struct Snapshot {
  track::Track track;
  zone::ProbeState base;  ///< everything but the plane: t, region, intent, turn, slot
};

/// One record's work for the alert stage, in record order.
struct AlertStep {
  enum class Kind : std::uint8_t { Update, DropAlerts };
  Kind kind;
  track::TrackSlot slot;
  std::uint32_t snapshot = 0;                    ///< Update: in Batch::snapshots
  std::uint32_t first_zone = 0, zone_count = 0;  ///< Update: in Batch::step_zones
  double t = 0.0;                                ///< the clock of its record (UTC s)
};

/// A pair a zone's probe found in conflict and owns (design §4.9), judged once there:
/// the alert stage takes the verdict and does not test the pair again.
struct FoundPair {
  track::TrackSlot other = track::kNoTrack;
  PairKinematics pair;
};

struct Batch {
  std::vector<Snapshot> snapshots;
  std::vector<AlertStep> steps;
  std::vector<zone::ZoneKey> step_zones;  ///< the zones each Update step was probed in

  void clear() {
    snapshots.clear();
    steps.clear();
    step_zones.clear();
  }
};

}  // namespace kew::pipeline
